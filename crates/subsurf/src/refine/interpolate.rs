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
use super::masks::{LevelRows, Scratch};
use super::{check_size, refine_topology, RefineOptions};
use crate::error::{MeshError, Result};
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
    check_size(&base, level)?;
    if data.len() != base.num_vertices() {
        return Err(MeshError::Unsupported {
            construction: "refinement of vertex data",
            requirement: "one value per base vertex",
            details: format!("{} values for {} vertices", data.len(), base.num_vertices()),
        }
        .into());
    }
    let mut cur = base;
    let mut values = data.to_vec();
    for k in 0..level {
        let mut dst = vec![[0.0f32; N]; cur.num_vertices() + cur.num_faces() + cur.num_edges()];
        let child = if k + 1 == level && !options.full_topology_in_last_level {
            let sharpness = ChildSharpnessBuf::new(&cur);
            apply_rows(LevelRows::new(&cur, sharpness.view()), &values, &mut dst);
            refine_face_lists(&cur)
        } else {
            let child = refine_topology(&cur);
            let rows = LevelRows::new(&cur, ChildSharpness::of_child(&cur, &child));
            apply_rows(rows, &values, &mut dst);
            child
        };
        cur = child;
        values = dst;
    }
    Ok((cur, values))
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
        let (mut idx, mut wts) = (Vec::with_capacity(64), Vec::with_capacity(64));
        for (i, o) in out.iter_mut().enumerate() {
            idx.clear();
            wts.clear();
            rows.face(c * CHUNK + i, &mut idx, &mut wts);
            *o = sum(&idx, &wts, src, &[], usize::MAX);
        }
    });
    let fd: &[[f32; N]] = fd;
    vd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let mut s = Scratch::default();
        let (mut idx, mut wts) = (Vec::with_capacity(64), Vec::with_capacity(64));
        for (i, o) in out.iter_mut().enumerate() {
            idx.clear();
            wts.clear();
            rows.vertex(c * CHUNK + i, &mut idx, &mut wts, &mut s);
            *o = sum(&idx, &wts, src, fd, nv);
        }
    });
    ed.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let (mut idx, mut wts) = (Vec::with_capacity(64), Vec::with_capacity(64));
        for (i, o) in out.iter_mut().enumerate() {
            idx.clear();
            wts.clear();
            rows.edge(c * CHUNK + i, &mut idx, &mut wts);
            *o = sum(&idx, &wts, src, fd, nv);
        }
    });
}

/// `Σ w · x[k]` in `f32`, in entry order, where `x[k]` is `src[k]` below `p` and face point
/// `fd[k - p]` from `p` on (as [`super::LevelStencils::apply`] reads its inputs).
#[inline(always)]
fn sum<const N: usize>(
    idx: &[u32],
    wts: &[f32],
    src: &[[f32; N]],
    fd: &[[f32; N]],
    p: usize,
) -> [f32; N] {
    let mut acc = [0.0f32; N];
    for (&k, &w) in idx.iter().zip(wts) {
        let k = k as usize;
        let v = if k < p { &src[k] } else { &fd[k - p] };
        for c in 0..N {
            acc[c] += w * v[c];
        }
    }
    acc
}
