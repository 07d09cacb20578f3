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
