//! # osd-ref — OpenSubdiv as a reference (tests and benches only)
//!
//! Runs Pixar's OpenSubdiv 3.5 (`Far` API, `libosdCPU`) in-process through a small C++ shim
//! (`shim/shim.cpp`, C ABI in `shim/shim.h`), so that subsurf's tests and benchmarks can
//! compare against OpenSubdiv's own numbers:
//!
//! - [`refine_uniform`]: every level of a uniform refinement (topology, positions, UVs);
//! - [`limit_stencil_positions`]: the last level's vertices projected to the limit;
//! - [`eval_limit_grid`] / [`patch_counts`]: adaptive refinement + patch table evaluation;
//! - [`OsdRefiner`] / [`OsdStencils`]: handles that separate topology and positions costs;
//! - [`patch_basis`]: the basis weights of one patch type at one `(u, v)`;
//! - [`bfr_tessellation`]: `Bfr::Tessellation`'s pattern of one face for given rates.
//!
//! When OpenSubdiv was not found at build time the crate still compiles: [`available`]
//! returns `false` and every entry point returns [`Error::Unavailable`].
//!
//! This crate is not published and is not a dependency of the library.

#![warn(missing_docs)]
#![allow(unsafe_code)] // the FFI boundary; every `unsafe` block states its invariant

mod adaptive;
mod adaptive_f64;
mod ffi;
mod from_subsurf;
mod mesh;
mod patch_basis;
mod tessellation;
mod uniform;

pub use adaptive::{
    eval_limit_grid, eval_limit_grid_with, patch_counts, patch_stats, patch_table_only, EndCap,
    LimitSample, PatchOptions, PatchStats, PatchTableBuild,
};
pub use adaptive_f64::{eval_limit_grid_f64, LimitSampleF64};
pub use from_subsurf::fan_triangulated_loop;
pub use mesh::{OsdBoundary, OsdCreaseMethod, OsdMesh, OsdOptions, OsdScheme};
pub use patch_basis::{patch_basis, OsdBasis, OsdPatchType};
pub use tessellation::{bfr_tessellation, BfrParam, BfrPattern};
pub use uniform::{
    limit_stencil_positions, refine_uniform, OsdLevel, OsdRefiner, OsdStencils, MAX_LEVEL,
};

/// Errors of the OpenSubdiv bridge.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// OpenSubdiv was not found when this crate was built.
    #[error("OpenSubdiv is not installed (apt-get install libosd-dev): osd-ref is unavailable")]
    Unavailable,
    /// The input was rejected before reaching OpenSubdiv.
    #[error("invalid input: {0}")]
    Invalid(String),
    /// OpenSubdiv reported a failure.
    #[error("OpenSubdiv: {0}")]
    Osd(String),
}

/// Result alias.
pub type Result<T> = std::result::Result<T, Error>;

/// Whether OpenSubdiv was found when this crate was built.
pub fn available() -> bool {
    !cfg!(osd_missing)
}

/// One malloc arena for every thread of the process (glibc's `M_ARENA_MAX`, as
/// `GLIBC_TUNABLES=glibc.malloc.arena_max=1` sets it), for the side-by-side benchmarks; call it
/// first in `main`, before any other thread exists. A no-op elsewhere than glibc.
///
/// A benchmark that runs one library on the main thread and another on a rayon worker, or a
/// two-thread pool after a one-thread one, would otherwise compare allocators: each thread
/// allocates from an arena of its own, a worker's arena gives its freed pages back to the
/// kernel (`MADV_DONTNEED`) and faults them in anew, and no side reuses the pages the other
/// freed. With one arena every side allocates from the same heap.
pub fn one_malloc_arena() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        extern "C" {
            fn mallopt(param: i32, value: i32) -> i32;
        }
        /// `M_ARENA_MAX` of glibc's `malloc.h`.
        const M_ARENA_MAX: i32 = -8;
        // SAFETY: `mallopt` only sets an allocator parameter.
        unsafe {
            mallopt(M_ARENA_MAX, 1);
        }
    }
}

/// Binds the calling thread to CPU `cpu` (Linux `sched_setaffinity`; a no-op elsewhere or
/// where `cpu` does not exist), for a benchmark's thread pool: call it from a rayon pool's
/// `start_handler` to give each worker a core of its own, as `OMP_PROC_BIND` does.
///
/// Measured in `peer-bench` on this 2-core machine: unbound, the kernel often ran both workers
/// of the two-thread pool on one core (the one the single-threaded runs had just left idle,
/// about 40 involuntary context switches per worker per car level-4 setup), and subsurf's
/// two-thread setup read 18–31 ms; bound, 15.0–15.6 ms with none.
pub fn bind_to_cpu(cpu: usize) {
    #[cfg(target_os = "linux")]
    {
        if cpu >= libc::CPU_SETSIZE as usize {
            return;
        }
        // SAFETY: `cpu_set_t` is plain bits (all zero is the empty set), `CPU_SET` writes
        // one bit of it inside its size (checked above), and `sched_setaffinity` of thread 0
        // (the caller) only reads it; a CPU that is not online makes the call fail, ignored.
        unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            libc::CPU_SET(cpu, &mut set);
            libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &set);
        }
    }
}

/// For tests that compare with OpenSubdiv: true when it is available; otherwise prints a loud
/// SKIPPED line naming `test` (straight to stderr, past the harness's capture) and returns
/// false — or panics when the `CI` environment variable is set, since CI must run them.
pub fn available_or_skip(test: &str) -> bool {
    if available() {
        return true;
    }
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "0" && v != "false");
    assert!(
        !ci,
        "OpenSubdiv not installed but CI is set: {test} must run"
    );
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "!!!!! OpenSubdiv not installed: SKIPPED {test} (apt-get install libosd-dev) !!!!!"
    );
    false
}

/// The error for a failed shim call: [`Error::Unavailable`] or the shim's message.
fn unavailable_or_osd() -> Error {
    if available() {
        Error::Osd(ffi::last_error())
    } else {
        Error::Unavailable
    }
}

/// Turns a shim status code into a `Result`.
fn check(status: i32) -> Result<()> {
    if status == 0 {
        Ok(())
    } else {
        Err(unavailable_or_osd())
    }
}
