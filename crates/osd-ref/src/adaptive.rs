//! Limit-surface evaluation through feature-adaptive refinement and a `Far::PatchTable`
//! (Nießner, Loop, Meyer & DeRose 2012), the way OpenSubdiv's own CPU evaluation does it.

use std::ptr::NonNull;

use crate::ffi;
use crate::mesh::{Desc, OsdMesh};
use crate::{check, unavailable_or_osd, Error, Result};

/// End-cap patches for irregular regions left at the isolation level
/// (`Far::PatchTableFactory::Options::EndCapType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum EndCap {
    /// `ENDCAP_BSPLINE_BASIS`: B-spline approximations.
    BSpline,
    /// `ENDCAP_GREGORY_BASIS`: Gregory patches (OpenSubdiv's default).
    #[default]
    Gregory,
    /// `ENDCAP_LEGACY_GREGORY`: 2.x-style Gregory patches. They can be counted
    /// ([`patch_stats`]) but OpenSubdiv cannot evaluate them on the CPU.
    LegacyGregory,
}

impl EndCap {
    pub(crate) fn raw(self) -> i32 {
        match self {
            EndCap::BSpline => 2,
            EndCap::Gregory => 3,
            EndCap::LegacyGregory => 4,
        }
    }
}

/// Options of the adaptive refinement and patch table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PatchOptions {
    /// Isolation level of extraordinary features (`AdaptiveOptions::isolationLevel`, 0..=10).
    pub isolation_level: u32,
    /// `useSingleCreasePatch`: semi-sharp regular creases become one patch.
    pub use_single_crease: bool,
    /// `useInfSharpPatch`: infinitely sharp features end isolation early.
    pub use_inf_sharp: bool,
    /// End-cap type.
    pub end_cap: EndCap,
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            isolation_level: 4,
            use_single_crease: false,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        }
    }
}

/// One limit-surface sample: position and first derivatives with respect to the ptex
/// face's own `(u, v)` (the patch's `PatchParam` normalisation is undone by
/// `PatchTable::EvaluateBasis`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LimitSample {
    /// Ptex face index (`Far::PtexIndices`): one per quad, one per corner of an n-gon.
    pub face: u32,
    /// Ptex coordinate along the face's first edge.
    pub u: f32,
    /// Ptex coordinate along the face's last edge.
    pub v: f32,
    /// Limit position.
    pub p: [f32; 3],
    /// ∂p/∂u.
    pub du: [f32; 3],
    /// ∂p/∂v.
    pub dv: [f32; 3],
}

/// Size of a patch table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PatchStats {
    /// `GetNumPatchesTotal()`.
    pub num_patches: usize,
    /// Bytes of the patch control-vertex indices plus the `PatchParam`s.
    pub bytes: usize,
    /// Ptex faces of the coarse mesh.
    pub num_ptex_faces: usize,
    /// End-cap local points (`GetNumLocalPoints()`).
    pub num_local_points: usize,
    /// Regular patches: those of the scheme's regular type (`REGULAR` B-spline patches for
    /// Catmark, `LOOP` box-spline patches for Loop); the other patches are end caps.
    pub num_regular_patches: usize,
}

/// An adaptively refined mesh with its patch table, patch map and all points computed.
#[derive(Debug)]
struct Adaptive {
    raw: NonNull<ffi::Adaptive>,
}

impl Adaptive {
    fn new(mesh: &OsdMesh, o: &PatchOptions) -> Result<Self> {
        if o.isolation_level > 10 {
            return Err(Error::Invalid(format!(
                "isolation level {} > 10",
                o.isolation_level
            )));
        }
        let desc = Desc::new(mesh)?;
        let raw_desc = desc.raw();
        // SAFETY: `raw_desc` points into validated data alive for the call.
        let ptr = unsafe {
            ffi::osd_adaptive_new(
                &raw_desc,
                o.isolation_level as i32,
                o.use_single_crease as i32,
                o.use_inf_sharp as i32,
                o.end_cap.raw(),
            )
        };
        Ok(Adaptive {
            raw: NonNull::new(ptr).ok_or_else(unavailable_or_osd)?,
        })
    }

    fn stats(&self) -> Result<PatchStats> {
        let mut c = [0i64; 5];
        // SAFETY: live handle; 5 slots.
        check(unsafe { ffi::osd_adaptive_counts(self.raw.as_ptr(), c.as_mut_ptr()) })?;
        Ok(PatchStats {
            num_patches: c[0] as usize,
            bytes: c[1] as usize,
            num_ptex_faces: c[2] as usize,
            num_local_points: c[3] as usize,
            num_regular_patches: c[4] as usize,
        })
    }
}

impl Drop for Adaptive {
    fn drop(&mut self) {
        // SAFETY: the handle came from `osd_adaptive_new` and is freed once.
        unsafe { ffi::osd_adaptive_free(self.raw.as_ptr()) }
    }
}

/// Samples the limit surface on an `n × n` grid of every ptex face: `u, v = i/(n−1)`, `v`
/// the outer loop, faces in ptex order. Faces without patches (holes, and faces at
/// unsharpened boundaries under `OsdBoundary::None`) give no samples. For the Loop scheme
/// only the triangle `u + v ≤ 1` is sampled.
pub fn eval_limit_grid(
    mesh: &OsdMesh,
    samples_per_side: usize,
    isolation_level: u32,
    use_single_crease: bool,
    end_cap: EndCap,
) -> Result<Vec<LimitSample>> {
    let o = PatchOptions {
        isolation_level,
        use_single_crease,
        use_inf_sharp: false,
        end_cap,
    };
    eval_limit_grid_with(mesh, samples_per_side, &o)
}

/// [`eval_limit_grid`] with every [`PatchOptions`] field.
pub fn eval_limit_grid_with(
    mesh: &OsdMesh,
    samples_per_side: usize,
    o: &PatchOptions,
) -> Result<Vec<LimitSample>> {
    let n = samples_per_side;
    if !(2..=4096).contains(&n) {
        return Err(Error::Invalid(format!(
            "samples per side {n} not in 2..=4096"
        )));
    }
    let a = Adaptive::new(mesh, o)?;
    let cap = a.stats()?.num_ptex_faces * n * n;
    let mut out = vec![LimitSample::default(); cap];
    // SAFETY: `out` has room for `cap` samples; `LimitSample` is `repr(C)` with the
    // layout of `osd_limit_sample`.
    let count =
        unsafe { ffi::osd_adaptive_eval_grid(a.raw.as_ptr(), n as i32, out.as_mut_ptr(), cap) };
    if count < 0 {
        return Err(unavailable_or_osd());
    }
    out.truncate(count as usize);
    Ok(out)
}

/// `(number of patches, bytes of control-vertex + param arrays)` of the patch table.
pub fn patch_counts(
    mesh: &OsdMesh,
    isolation_level: u32,
    use_single_crease: bool,
    end_cap: EndCap,
) -> Result<(usize, usize)> {
    let o = PatchOptions {
        isolation_level,
        use_single_crease,
        use_inf_sharp: false,
        end_cap,
    };
    let s = patch_stats(mesh, &o)?;
    Ok((s.num_patches, s.bytes))
}

/// Every size of the patch table built with `o`.
pub fn patch_stats(mesh: &OsdMesh, o: &PatchOptions) -> Result<PatchStats> {
    Adaptive::new(mesh, o)?.stats()
}

/// Result of [`patch_table_only`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PatchTableBuild {
    /// `GetNumPatchesTotal()`.
    pub num_patches: usize,
    /// Bytes of the patch control-vertex indices plus the `PatchParam`s.
    pub bytes: usize,
    /// Vertices of every adaptively refined level (`GetNumVerticesTotal()`).
    pub num_refined_vertices: usize,
}

/// Builds the topology refiner, refines adaptively and builds the patch table, nothing more
/// (no patch map, no point evaluation): OpenSubdiv's patch-table construction, for timing.
pub fn patch_table_only(mesh: &OsdMesh, o: &PatchOptions) -> Result<PatchTableBuild> {
    if o.isolation_level > 10 {
        return Err(Error::Invalid(format!(
            "isolation level {} > 10",
            o.isolation_level
        )));
    }
    let desc = Desc::new(mesh)?;
    let raw_desc = desc.raw();
    let mut c = [0i64; 3];
    // SAFETY: `raw_desc` points into validated data alive for the call; 3 count slots.
    let rc = unsafe {
        ffi::osd_patch_table_only(
            &raw_desc,
            o.isolation_level as i32,
            o.use_single_crease as i32,
            o.use_inf_sharp as i32,
            o.end_cap.raw(),
            c.as_mut_ptr(),
        )
    };
    if rc != 0 {
        return Err(unavailable_or_osd());
    }
    Ok(PatchTableBuild {
        num_patches: c[0] as usize,
        bytes: c[1] as usize,
        num_refined_vertices: c[2] as usize,
    })
}
