//! Uniform refinement (`Far::TopologyRefiner::RefineUniform`), primvar interpolation
//! (`Far::PrimvarRefiner`), limit positions and stencil tables (`Far::StencilTable`).

use std::ptr::NonNull;

use crate::ffi;
use crate::mesh::{Desc, OsdMesh};
use crate::{check, unavailable_or_osd, Error, Result};

/// Deepest level the shim accepts (`UniformOptions::refinementLevel` has 4 bits).
pub const MAX_LEVEL: usize = 15;

/// One level of a uniform refinement, read through `Far::TopologyLevel`.
#[derive(Debug, Clone, PartialEq)]
pub struct OsdLevel {
    /// Vertex positions (`PrimvarRefiner::Interpolate`).
    pub positions: Vec<[f32; 3]>,
    /// Vertices per face.
    pub face_counts: Vec<u32>,
    /// Face vertices, concatenated (`GetFaceVertices`).
    pub face_verts: Vec<u32>,
    /// Edge end points (`GetEdgeVertices`).
    pub edge_verts: Vec<[u32; 2]>,
    /// `IsFaceHole` for every face.
    pub face_is_hole: Vec<bool>,
    /// Face-varying channel 0: values (`PrimvarRefiner::InterpolateFaceVarying`) and
    /// one index per face corner (`GetFaceFVarValues`); `None` without UVs.
    pub uvs: Option<(Vec<[f32; 2]>, Vec<u32>)>,
}

/// A `Far::TopologyRefiner` refined uniformly (full topology in the last level, unless built
/// with [`OsdRefiner::with_last_level`]).
///
/// Building it is the "topology" cost of a refinement; [`OsdRefiner::interpolate`] is the
/// "positions" cost. The handle is neither `Send` nor `Sync` (it keeps scratch memory).
#[derive(Debug)]
pub struct OsdRefiner {
    raw: NonNull<ffi::Uniform>,
    max_level: usize,
    num_vertices: Vec<usize>,
    num_fvar: Option<Vec<usize>>,
    full_last: bool,
}

impl OsdRefiner {
    /// Builds the refiner from `mesh` and refines it uniformly `level` times, the last level
    /// with its full topology.
    pub fn new(mesh: &OsdMesh, level: usize) -> Result<Self> {
        Self::with_last_level(mesh, level, true)
    }

    /// As [`OsdRefiner::new`]; `full_topology_in_last_level = false` (OpenSubdiv's default)
    /// builds only what interpolation needs in the last level, and [`OsdRefiner::limit`] is
    /// then refused.
    pub fn with_last_level(
        mesh: &OsdMesh,
        level: usize,
        full_topology_in_last_level: bool,
    ) -> Result<Self> {
        if level > MAX_LEVEL {
            return Err(Error::Invalid(format!("level {level} > {MAX_LEVEL}")));
        }
        let desc = Desc::new(mesh)?;
        let raw_desc = desc.raw();
        // SAFETY: `raw_desc` points into `mesh` and `desc`, both alive for the call, and
        // every index was validated.
        let ptr = unsafe {
            ffi::osd_uniform_new(&raw_desc, level as i32, full_topology_in_last_level as i32)
        };
        let raw = NonNull::new(ptr).ok_or_else(unavailable_or_osd)?;
        let mut r = OsdRefiner {
            raw,
            max_level: level,
            num_vertices: Vec::new(),
            num_fvar: None,
            full_last: full_topology_in_last_level || level == 0,
        };
        let mut fvar = Vec::new();
        for l in 0..=level {
            let sizes = r.level_sizes(l)?;
            r.num_vertices.push(sizes[0] as usize);
            fvar.push(sizes[4]);
        }
        if fvar.iter().all(|&n| n >= 0) {
            r.num_fvar = Some(fvar.into_iter().map(|n| n as usize).collect());
        }
        Ok(r)
    }

    /// The refinement level.
    pub fn max_level(&self) -> usize {
        self.max_level
    }

    /// Number of vertices at `level` (0 = the coarse mesh); 0 past the last level.
    pub fn num_vertices(&self, level: usize) -> usize {
        self.num_vertices.get(level).copied().unwrap_or(0)
    }

    fn level_sizes(&self, level: usize) -> Result<[i32; 5]> {
        let mut sizes = [0i32; 5];
        // SAFETY: the handle is live; `sizes` has the 5 slots the shim writes.
        check(unsafe {
            ffi::osd_uniform_level_sizes(self.raw.as_ptr(), level as i32, sizes.as_mut_ptr())
        })?;
        Ok(sizes)
    }

    fn check_coarse<T>(&self, positions: &[T]) -> Result<()> {
        if positions.len() != self.num_vertices[0] {
            return Err(Error::Invalid(format!(
                "{} positions for {} coarse vertices",
                positions.len(),
                self.num_vertices[0]
            )));
        }
        Ok(())
    }

    /// Interpolates coarse `positions` through every level and returns the last one.
    pub fn interpolate(&self, positions: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
        let mut out = vec![[0.0; 3]; self.num_vertices(self.max_level)];
        self.interpolate_into(positions, &mut out)?;
        Ok(out)
    }

    /// As [`OsdRefiner::interpolate`], into a caller buffer of the last level's size.
    pub fn interpolate_into(&self, positions: &[[f32; 3]], out: &mut [[f32; 3]]) -> Result<()> {
        self.check_coarse(positions)?;
        if out.len() != self.num_vertices(self.max_level) {
            return Err(Error::Invalid("output buffer has the wrong size".into()));
        }
        // SAFETY: sizes checked above; the shim's scratch is only touched through this
        // handle, which is not `Sync`.
        check(unsafe {
            ffi::osd_uniform_interpolate_last(
                self.raw.as_ptr(),
                positions.as_ptr().cast(),
                out.as_mut_ptr().cast(),
            )
        })
    }

    /// The last level in double precision (`PrimvarRefinerReal<double>`) from `f64` coarse
    /// positions (a subsurf mesh's [`subsurf::Positions::to_f64`]).
    pub fn interpolate_f64(&self, positions: &[[f64; 3]]) -> Result<Vec<[f64; 3]>> {
        self.check_coarse(positions)?;
        let mut out = vec![[0.0f64; 3]; self.num_vertices(self.max_level)];
        // SAFETY: `positions` holds level 0 and `out` the last level, in packed doubles.
        check(unsafe {
            ffi::osd_uniform_interpolate_last_f64(
                self.raw.as_ptr(),
                positions.as_ptr().cast(),
                out.as_mut_ptr().cast(),
            )
        })?;
        Ok(out)
    }

    /// Positions of every level, concatenated (level 0 first).
    pub fn interpolate_all(&self, positions: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
        self.check_coarse(positions)?;
        let total: usize = self.num_vertices.iter().sum();
        let mut all = vec![[0.0f32; 3]; total];
        // SAFETY: `all` holds the total vertex count; `positions` holds level 0.
        check(unsafe {
            ffi::osd_uniform_interpolate_all(
                self.raw.as_ptr(),
                positions.as_ptr().cast(),
                all.as_mut_ptr().cast(),
            )
        })?;
        Ok(all)
    }

    /// Moves the last level's `points` to the limit surface (`PrimvarRefiner::Limit`).
    pub fn limit(&self, points: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
        let n = self.num_vertices(self.max_level);
        // SAFETY: both buffers hold the last level's vertex count (checked by `last_level`).
        self.last_level("limit", points, n, |src, dst| unsafe {
            ffi::osd_uniform_limit(self.raw.as_ptr(), src, dst)
        })
    }

    /// Moves the last level's face-varying `values` (channel 0) to the limit surface
    /// (`PrimvarRefiner::LimitFaceVarying`).
    pub fn limit_fvar(&self, values: &[[f32; 2]]) -> Result<Vec<[f32; 2]>> {
        let n = self
            .num_fvar
            .as_ref()
            .ok_or_else(|| Error::Invalid("the mesh has no face-varying channel".into()))?
            [self.max_level];
        // SAFETY: both buffers hold the last level's value count (checked by `last_level`).
        self.last_level("limit_fvar", values, n, |src, dst| unsafe {
            ffi::osd_uniform_limit_fvar(self.raw.as_ptr(), src, dst)
        })
    }

    /// `run(input, output)` over `n` elements of the last level, which must be refined with
    /// its full topology.
    fn last_level<const N: usize>(
        &self,
        what: &str,
        input: &[[f32; N]],
        n: usize,
        run: impl FnOnce(*const f32, *mut f32) -> i32,
    ) -> Result<Vec<[f32; N]>> {
        if input.len() != n {
            return Err(Error::Invalid(format!(
                "{what} needs the last level's {n} elements, got {}",
                input.len()
            )));
        }
        if !self.full_last {
            return Err(Error::Invalid(format!(
                "{what} needs the last level's full topology"
            )));
        }
        let mut out = vec![[0.0f32; N]; n];
        check(run(input.as_ptr().cast(), out.as_mut_ptr().cast()))?;
        Ok(out)
    }

    /// Topology of one level, without positions.
    fn level_topology(&self, level: usize) -> Result<OsdLevel> {
        let s = self.level_sizes(level)?;
        let (nf, nfv, ne) = (s[1] as usize, s[3] as usize, s[2] as usize);
        let mut face_counts = vec![0i32; nf];
        let mut face_verts = vec![0i32; nfv];
        let mut edge_verts = vec![0i32; 2 * ne];
        let mut holes = vec![0u8; nf];
        let mut fvar = self.num_fvar.as_ref().map(|_| vec![0i32; nfv]);
        let fvar_ptr = fvar
            .as_mut()
            .map_or(std::ptr::null_mut(), |v| v.as_mut_ptr());
        // SAFETY: each buffer has the size reported by `osd_uniform_level_sizes`.
        check(unsafe {
            ffi::osd_uniform_level_topology(
                self.raw.as_ptr(),
                level as i32,
                face_counts.as_mut_ptr(),
                face_verts.as_mut_ptr(),
                edge_verts.as_mut_ptr(),
                holes.as_mut_ptr(),
                fvar_ptr,
            )
        })?;
        let to_u32 = |v: Vec<i32>| v.into_iter().map(|x| x as u32).collect::<Vec<u32>>();
        Ok(OsdLevel {
            positions: Vec::new(),
            face_counts: to_u32(face_counts),
            face_verts: to_u32(face_verts),
            edge_verts: edge_verts
                .chunks_exact(2)
                .map(|e| [e[0] as u32, e[1] as u32])
                .collect(),
            face_is_hole: holes.into_iter().map(|h| h != 0).collect(),
            uvs: fvar.map(|idx| (Vec::new(), to_u32(idx))),
        })
    }
}

impl Drop for OsdRefiner {
    fn drop(&mut self) {
        // SAFETY: the handle came from `osd_uniform_new` and is freed once.
        unsafe { ffi::osd_uniform_free(self.raw.as_ptr()) }
    }
}

/// Refines `mesh` uniformly and returns levels `0..=level`: topology, positions and UVs.
///
/// # Example
///
/// subsurf and OpenSubdiv on the same cube, two levels: identical faces, positions within
/// f32 rounding (without OpenSubdiv the call is [`Error::Unavailable`]):
///
/// ```
/// use osd_ref::{refine_uniform, Error, OsdMesh};
///
/// let cube = subsurf::shapes::cube();
/// let levels = match refine_uniform(&OsdMesh::from(&cube), 2) {
///     Ok(levels) => levels,
///     Err(Error::Unavailable) => return Ok(()), // built without libosd-dev
///     Err(e) => return Err(e.into()),
/// };
/// let refiner = subsurf::Refiner::new(subsurf::Topology::new(&cube)?, 2)?;
/// let ours = refiner.refine_positions(&cube.positions);
/// assert_eq!(levels[2].face_verts, refiner.last().arrays().face_verts);
/// for (a, b) in levels[2].positions.iter().zip(&ours) {
///     assert!((0..3).all(|c| (a[c] - b[c]).abs() < 1e-6));
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn refine_uniform(mesh: &OsdMesh, level: usize) -> Result<Vec<OsdLevel>> {
    let r = OsdRefiner::new(mesh, level)?;
    let all = r.interpolate_all(mesh.positions)?;
    let all_uvs = match (&r.num_fvar, mesh.uvs) {
        (Some(counts), Some((values, _))) => {
            let mut out = vec![[0.0f32; 2]; counts.iter().sum()];
            // SAFETY: `values` holds level 0's fvar values (validated against the indices,
            // and OpenSubdiv's count is the one we passed); `out` holds all levels'.
            check(unsafe {
                ffi::osd_uniform_interpolate_fvar_all(
                    r.raw.as_ptr(),
                    values.as_ptr().cast(),
                    out.as_mut_ptr().cast(),
                )
            })?;
            Some((out, counts.clone()))
        }
        _ => None,
    };
    let mut levels = Vec::with_capacity(level + 1);
    let (mut v0, mut u0) = (0, 0);
    for l in 0..=level {
        let mut lv = r.level_topology(l)?;
        let nv = r.num_vertices(l);
        lv.positions = all[v0..v0 + nv].to_vec();
        v0 += nv;
        if let (Some((values, counts)), Some(uvs)) = (&all_uvs, lv.uvs.as_mut()) {
            uvs.0 = values[u0..u0 + counts[l]].to_vec();
            u0 += counts[l];
        }
        levels.push(lv);
    }
    Ok(levels)
}

/// Refines `mesh` to `level` and projects the last level's vertices to the limit surface.
pub fn limit_stencil_positions(mesh: &OsdMesh, level: usize) -> Result<Vec<[f32; 3]>> {
    let r = OsdRefiner::new(mesh, level)?;
    let last = r.interpolate(mesh.positions)?;
    r.limit(&last)
}

/// A `Far::StencilTable` for the last level of an [`OsdRefiner`] (intermediate levels
/// factorized away): every refined point as a weighted sum of coarse points.
#[derive(Debug)]
pub struct OsdStencils {
    raw: NonNull<ffi::Stencils>,
    num_coarse: usize,
    num_stencils: usize,
}

impl OsdStencils {
    /// Builds the table (`StencilTableFactory::Create`, `generateIntermediateLevels = false`).
    pub fn new(refiner: &OsdRefiner) -> Result<Self> {
        // SAFETY: the refiner's handle is live; the table copies what it needs.
        let ptr = unsafe { ffi::osd_stencils_new(refiner.raw.as_ptr()) };
        let raw = NonNull::new(ptr).ok_or_else(unavailable_or_osd)?;
        // SAFETY: live handle.
        let n = unsafe { ffi::osd_stencils_num(raw.as_ptr()) };
        let s = OsdStencils {
            raw,
            num_coarse: refiner.num_vertices(0),
            num_stencils: n.max(0) as usize,
        };
        if n < 0 {
            return Err(unavailable_or_osd());
        }
        Ok(s)
    }

    /// Number of stencils (points produced by [`OsdStencils::update`]).
    pub fn num_stencils(&self) -> usize {
        self.num_stencils
    }

    /// Applies the stencils to coarse `positions` (`StencilTable::UpdateValues`).
    pub fn update(&self, positions: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
        let mut out = vec![[0.0f32; 3]; self.num_stencils];
        self.update_into(positions, &mut out)?;
        Ok(out)
    }

    /// As [`OsdStencils::update`], into a caller buffer of [`OsdStencils::num_stencils`] points.
    pub fn update_into(&self, positions: &[[f32; 3]], out: &mut [[f32; 3]]) -> Result<()> {
        if positions.len() != self.num_coarse || out.len() != self.num_stencils {
            return Err(Error::Invalid(
                "stencil update buffers have the wrong size".into(),
            ));
        }
        // SAFETY: sizes checked above.
        check(unsafe {
            ffi::osd_stencils_update(
                self.raw.as_ptr(),
                positions.as_ptr().cast(),
                out.as_mut_ptr().cast(),
            )
        })
    }
}

impl Drop for OsdStencils {
    fn drop(&mut self) {
        // SAFETY: the handle came from `osd_stencils_new` and is freed once.
        unsafe { ffi::osd_stencils_free(self.raw.as_ptr()) }
    }
}
