//! Declarations of the C ABI in `shim/shim.h`.
//!
//! Without OpenSubdiv (`cfg(osd_missing)`) the same names are defined here as stubs that
//! fail, so that the crate links and every entry point reports [`crate::Error::Unavailable`].

use std::os::raw::{c_char, c_float, c_int};

use crate::adaptive::LimitSample;
use crate::adaptive_f64::LimitSampleF64;

/// `osd_mesh_desc`: a mesh borrowed for one call.
#[repr(C)]
#[derive(Debug)]
pub(crate) struct MeshDesc {
    pub num_vertices: c_int,
    pub positions: *const c_float,
    pub num_faces: c_int,
    pub face_counts: *const c_int,
    pub face_indices: *const c_int,
    pub num_creases: c_int,
    pub crease_pairs: *const c_int,
    pub crease_weights: *const c_float,
    pub num_corners: c_int,
    pub corner_vertices: *const c_int,
    pub corner_weights: *const c_float,
    pub num_holes: c_int,
    pub holes: *const c_int,
    pub num_uvs: c_int,
    pub uvs: *const c_float,
    pub uv_indices: *const c_int,
    pub scheme: c_int,
    pub boundary: c_int,
    pub crease_method: c_int,
    pub triangle_smooth: c_int,
    pub fvar_interp: c_int,
    pub positions_f64: *const f64,
}

/// Opaque `osd_uniform`.
#[repr(C)]
pub(crate) struct Uniform {
    _private: [u8; 0],
}

/// Opaque `osd_stencils`.
#[repr(C)]
pub(crate) struct Stencils {
    _private: [u8; 0],
}

/// Opaque `osd_adaptive`.
#[repr(C)]
pub(crate) struct Adaptive {
    _private: [u8; 0],
}

#[cfg(not(osd_missing))]
extern "C" {
    pub(crate) fn osd_last_error(buf: *mut c_char, len: usize) -> usize;

    pub(crate) fn osd_uniform_new(
        mesh: *const MeshDesc,
        level: c_int,
        full_last: c_int,
    ) -> *mut Uniform;
    pub(crate) fn osd_uniform_free(u: *mut Uniform);
    pub(crate) fn osd_uniform_level_sizes(
        u: *const Uniform,
        level: c_int,
        sizes: *mut c_int,
    ) -> c_int;
    pub(crate) fn osd_uniform_level_topology(
        u: *const Uniform,
        level: c_int,
        face_counts: *mut c_int,
        face_verts: *mut c_int,
        edge_verts: *mut c_int,
        face_is_hole: *mut u8,
        fvar_indices: *mut c_int,
    ) -> c_int;
    pub(crate) fn osd_uniform_interpolate_all(
        u: *const Uniform,
        coarse: *const c_float,
        all: *mut c_float,
    ) -> c_int;
    pub(crate) fn osd_uniform_interpolate_last(
        u: *mut Uniform,
        coarse: *const c_float,
        last: *mut c_float,
    ) -> c_int;
    pub(crate) fn osd_uniform_interpolate_last_f64(
        u: *const Uniform,
        coarse: *const f64,
        last: *mut f64,
    ) -> c_int;
    pub(crate) fn osd_uniform_interpolate_fvar_all(
        u: *const Uniform,
        coarse: *const c_float,
        all: *mut c_float,
    ) -> c_int;
    pub(crate) fn osd_uniform_limit(
        u: *const Uniform,
        last_level: *const c_float,
        limit: *mut c_float,
    ) -> c_int;
    pub(crate) fn osd_uniform_limit_fvar(
        u: *const Uniform,
        last_level: *const c_float,
        limit: *mut c_float,
    ) -> c_int;

    pub(crate) fn osd_stencils_new(u: *const Uniform) -> *mut Stencils;
    pub(crate) fn osd_stencils_free(s: *mut Stencils);
    pub(crate) fn osd_stencils_num(s: *const Stencils) -> c_int;
    pub(crate) fn osd_stencils_update(
        s: *const Stencils,
        coarse: *const c_float,
        out: *mut c_float,
    ) -> c_int;

    pub(crate) fn osd_adaptive_new(
        mesh: *const MeshDesc,
        isolation: c_int,
        single_crease: c_int,
        inf_sharp: c_int,
        end_cap: c_int,
    ) -> *mut Adaptive;
    pub(crate) fn osd_adaptive_free(a: *mut Adaptive);
    pub(crate) fn osd_patch_table_only(
        mesh: *const MeshDesc,
        isolation: c_int,
        single_crease: c_int,
        inf_sharp: c_int,
        end_cap: c_int,
        counts: *mut i64,
    ) -> c_int;
    pub(crate) fn osd_adaptive_counts(a: *const Adaptive, counts: *mut i64) -> c_int;
    pub(crate) fn osd_adaptive_eval_grid(
        a: *const Adaptive,
        n: c_int,
        out: *mut LimitSample,
        cap: usize,
    ) -> i64;
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn osd_adaptive_eval_grid_f64(
        mesh: *const MeshDesc,
        isolation: c_int,
        single_crease: c_int,
        inf_sharp: c_int,
        end_cap: c_int,
        n: c_int,
        out: *mut LimitSampleF64,
        cap: usize,
    ) -> i64;
}

#[cfg(osd_missing)]
pub(crate) use stubs::*;

/// Failing stand-ins, compiled only when OpenSubdiv is absent. The constructors return
/// null, so no other function is ever reached with a handle.
#[cfg(osd_missing)]
#[allow(clippy::missing_safety_doc)]
mod stubs {
    use super::*;
    use std::ptr::null_mut;

    pub(crate) unsafe fn osd_last_error(_: *mut c_char, _: usize) -> usize {
        0
    }
    pub(crate) unsafe fn osd_uniform_new(_: *const MeshDesc, _: c_int, _: c_int) -> *mut Uniform {
        null_mut()
    }
    pub(crate) unsafe fn osd_uniform_free(_: *mut Uniform) {}
    pub(crate) unsafe fn osd_uniform_level_sizes(
        _: *const Uniform,
        _: c_int,
        _: *mut c_int,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_level_topology(
        _: *const Uniform,
        _: c_int,
        _: *mut c_int,
        _: *mut c_int,
        _: *mut c_int,
        _: *mut u8,
        _: *mut c_int,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_interpolate_all(
        _: *const Uniform,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_interpolate_last_f64(
        _: *const Uniform,
        _: *const f64,
        _: *mut f64,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_interpolate_last(
        _: *mut Uniform,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_interpolate_fvar_all(
        _: *const Uniform,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_limit(
        _: *const Uniform,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_uniform_limit_fvar(
        _: *const Uniform,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_stencils_new(_: *const Uniform) -> *mut Stencils {
        null_mut()
    }
    pub(crate) unsafe fn osd_stencils_free(_: *mut Stencils) {}
    pub(crate) unsafe fn osd_stencils_num(_: *const Stencils) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_stencils_update(
        _: *const Stencils,
        _: *const c_float,
        _: *mut c_float,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_adaptive_new(
        _: *const MeshDesc,
        _: c_int,
        _: c_int,
        _: c_int,
        _: c_int,
    ) -> *mut Adaptive {
        null_mut()
    }
    pub(crate) unsafe fn osd_adaptive_free(_: *mut Adaptive) {}
    pub(crate) unsafe fn osd_patch_table_only(
        _: *const MeshDesc,
        _: c_int,
        _: c_int,
        _: c_int,
        _: c_int,
        _: *mut i64,
    ) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_adaptive_counts(_: *const Adaptive, _: *mut i64) -> c_int {
        -1
    }
    pub(crate) unsafe fn osd_adaptive_eval_grid(
        _: *const Adaptive,
        _: c_int,
        _: *mut LimitSample,
        _: usize,
    ) -> i64 {
        -1
    }
    #[allow(clippy::too_many_arguments)]
    pub(crate) unsafe fn osd_adaptive_eval_grid_f64(
        _: *const MeshDesc,
        _: c_int,
        _: c_int,
        _: c_int,
        _: c_int,
        _: c_int,
        _: *mut LimitSampleF64,
        _: usize,
    ) -> i64 {
        -1
    }
}

/// The shim's last error message on this thread.
pub(crate) fn last_error() -> String {
    let mut buf = vec![0u8; 1024];
    // SAFETY: the buffer is writable for its whole length; the shim NUL-terminates.
    let n = unsafe { osd_last_error(buf.as_mut_ptr().cast(), buf.len()) };
    buf.truncate(n.min(buf.len() - 1));
    let msg = String::from_utf8_lossy(&buf).trim().to_string();
    if msg.is_empty() {
        "unspecified OpenSubdiv failure".to_string()
    } else {
        msg
    }
}
