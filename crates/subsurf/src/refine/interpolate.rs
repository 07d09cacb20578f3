//! One-shot refinement: the last level's topology and vertex data, with no stencil table kept.
//!
//! [`super::Refiner`] stores every step's stencils so that new vertex data (an animated mesh)
//! only re-applies them. When the data is refined once, storing the tables only costs: here
//! each row of [`super::LevelStencils`] is evaluated as it is formed, the way OpenSubdiv's
//! `Far::PrimvarRefiner::Interpolate` evaluates its masks, and each parent level is dropped
//! once its child exists. The rows, their order and the order of accumulation are those of
//! [`super::LevelStencils::apply`], so the result is bit-identical to
//! [`super::Refiner::refine_positions`].

use super::last_level::{refine_face_lists, ChildSharpness, ChildSharpnessBuf};
use super::level_tags::{child_level_tags, level_tags, tagged_level_mesh, LevelTags};
use super::masks::{LevelRows, Scratch};
use super::{check_size, refine_topology, RefineOptions};
use crate::error::{Error, MeshError, Result};
use crate::mesh::Mesh;
use crate::topology::Topology;
use rayon::prelude::*;

/// Rows per parallel chunk.
const CHUNK: usize = 4096;

/// Refines `base` uniformly `level` times and carries `data` (one `N`-component value per base
/// vertex) along; returns the last level's topology (full or lean as `options` say, see
/// [`RefineOptions`]) and its vertex data. Equal, bit for bit, to
/// `Refiner::with_options(base, level, options)` followed by `refine_positions(data)` and
/// `last()`, without building or keeping the stencil tables or the intermediate levels.
pub fn refine_once<const N: usize>(
    base: Topology,
    level: usize,
    data: &[[f32; N]],
    options: RefineOptions,
) -> Result<(Topology, Vec<[f32; N]>)> {
    let (t, values, _) = refine_once_with(base, level, data, options, false)?;
    Ok((t, values))
}

/// As [`refine_once`] on positions, returning the last level as a [`Mesh`] to write: all its
/// faces, holes tagged, with the sharpness that remains after `level` steps of decay and the
/// options ([`super::tagged_level_mesh`]), so that the written file refines again as the
/// level itself would. A lean last level's tags come from its parent before it is dropped.
pub fn refine_once_mesh(
    base: Topology,
    level: usize,
    positions: &[[f32; 3]],
    options: RefineOptions,
) -> Result<Mesh> {
    let (t, positions, tags) = refine_once_with(base, level, positions, options, true)?;
    let tags = tags.ok_or_else(|| Error::Internal("refined level without its tags".into()))?;
    Ok(tagged_level_mesh(&t, positions, tags))
}

/// [`refine_once`], with the last level's tags where `tagged` asks for them.
fn refine_once_with<const N: usize>(
    base: Topology,
    level: usize,
    data: &[[f32; N]],
    options: RefineOptions,
    tagged: bool,
) -> Result<(Topology, Vec<[f32; N]>, Option<LevelTags>)> {
    check_size(&base, level)?;
    if data.len() != base.num_vertices() {
        return Err(MeshError::Unsupported {
            construction: "refinement of vertex data",
            requirement: "one value per base vertex",
            details: format!("{} values for {} vertices", data.len(), base.num_vertices()),
        }
        .into());
    }
    if base.options.scheme == crate::options::Scheme::Loop {
        // Loop levels are refined through their tables (see `Refiner::new_loop`).
        let (mut r, sharpness) = super::Refiner::new_loop_keeping_sharpness(base, level, options);
        let values = r.refine_positions(data);
        let tags = match (tagged, sharpness) {
            (false, _) => None,
            (true, None) => Some(level_tags(r.last())?),
            (true, Some(sharpness)) => {
                let p = &r.levels[level - 1];
                Some(child_level_tags(p, sharpness.view(p), r.last()))
            }
        };
        let t = r
            .levels
            .pop()
            .ok_or_else(|| Error::Internal("no base level".into()))?;
        return Ok((t, values, tags));
    }
    let mut tags = None;
    if tagged && level == 0 {
        tags = Some(level_tags(&base)?);
    }
    let mut cur = base;
    let mut values = data.to_vec();
    for k in 0..level {
        let last = k + 1 == level;
        let mut dst = vec![[0.0f32; N]; cur.num_vertices() + cur.num_faces() + cur.num_edges()];
        let child = if last && !options.full_topology_in_last_level {
            let sharpness = ChildSharpnessBuf::new(&cur);
            // Both read only the parent: side by side (`rayon::join`).
            let ((), child) = rayon::join(
                || {
                    apply_rows(
                        LevelRows::new(&cur, sharpness.view(&cur)),
                        &values,
                        &mut dst,
                    )
                },
                || refine_face_lists(&cur),
            );
            if tagged {
                tags = Some(child_level_tags(&cur, sharpness.view(&cur), &child));
            }
            child
        } else {
            let child = refine_topology(&cur);
            let rows = LevelRows::new(&cur, ChildSharpness::of_child(&cur, &child));
            apply_rows(rows, &values, &mut dst);
            if tagged && last {
                tags = Some(level_tags(&child)?);
            }
            child
        };
        cur = child;
        values = dst;
    }
    Ok((cur, values, tags))
}

/// Evaluates one step's rows on `src` into `dst` (`[vertex | face | edge]` points), in
/// parallel chunks: face points first, then the vertex and edge points that read them.
pub(crate) fn apply_rows<const N: usize>(
    rows: LevelRows<'_>,
    src: &[[f32; N]],
    dst: &mut [[f32; N]],
) {
    let p = rows.parent();
    let (nv, nf) = (p.num_vertices(), p.num_faces());
    let (vd, rest) = dst.split_at_mut(nv);
    let (fd, ed) = rest.split_at_mut(nf);
    fd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = [0.0f32; N];
            rows.face(c * CHUNK + i, &mut |k, w| {
                add(&mut acc, w, &src[k as usize])
            });
            *o = acc;
        }
    });
    let fd: &[[f32; N]] = fd;
    // Input `k` of a vertex or edge row: a parent vertex below `nv`, else a face point.
    let x = |k: u32| {
        let k = k as usize;
        if k < nv {
            &src[k]
        } else {
            &fd[k - nv]
        }
    };
    vd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let mut s = Scratch::default();
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = [0.0f32; N];
            rows.vertex(c * CHUNK + i, &mut s, &mut |k, w| add(&mut acc, w, x(k)));
            *o = acc;
        }
    });
    ed.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = [0.0f32; N];
            rows.edge(c * CHUNK + i, &mut |k, w| add(&mut acc, w, x(k)));
            *o = acc;
        }
    });
}

/// `acc += w · x`, component by component in `f32`, in entry order (as
/// [`super::LevelStencils::apply`] accumulates).
#[inline(always)]
fn add<const N: usize>(acc: &mut [f32; N], w: f32, x: &[f32; N]) {
    for c in 0..N {
        acc[c] += w * x[c];
    }
}
