//! What [`crate::GpuLoopLimit`] and its CPU twin share: the `(patch, u, v)` queries of a
//! tessellation plan, the assembly of a kernel output into a [`TriTessellation`], and the
//! twin itself run over a whole [`LoopLimit`] (re-exported from [`crate::loop_limit`]).

use crate::cpu::loop_eval::{loop_eval, pack_queries, LoopInputs, LoopTables, NO_PATCH};
use crate::shared::LoopConfig;
use subsurf::limit::LoopLimit;
use subsurf::limit::{tri_tessellation_plan, TriTessellation, TriTessellationPlan};
use subsurf::Topology;

/// The kernel's queries of `plan`'s samples on `limit`: the patch holding each sample (found
/// with the triangle patch map, as [`LoopLimit::eval`] finds it) and its base-face `(u, v)`
/// in f32; [`NO_PATCH`] for a sample no face reaches. A reached sample without a patch is an
/// internal error, as in [`LoopLimit::tessellate`].
pub fn plan_queries(
    limit: &LoopLimit,
    plan: &TriTessellationPlan,
) -> subsurf::Result<Vec<(u32, f32, f32)>> {
    plan.samples
        .iter()
        .map(|s| match *s {
            None => Ok((NO_PATCH, 0.0, 0.0)),
            Some((f, [u, v])) => limit
                .patch_map
                .find_triangle(f as usize, u, v)
                .map(|p| (p, u as f32, v as f32))
                .ok_or_else(|| {
                    subsurf::Error::Internal(format!("no Loop patch of face {f} holds ({u}, {v})"))
                }),
        })
        .collect()
}

/// The tessellation of `plan` from a kernel output of 6 floats per sample (position, unit
/// normal), widened to f64; samples no face reaches are NaN, as the library leaves them.
pub fn assemble(plan: &TriTessellationPlan, out: &[f32]) -> TriTessellation {
    let mut positions = Vec::with_capacity(plan.samples.len());
    let mut normals = Vec::with_capacity(plan.samples.len());
    for (s, o) in plan.samples.iter().zip(out.chunks_exact(6)) {
        if s.is_some() {
            positions.push([o[0], o[1], o[2]].map(f64::from));
            normals.push([o[3], o[4], o[5]].map(f64::from));
        } else {
            positions.push([f64::NAN; 3]);
            normals.push([0.0; 3]);
        }
    }
    TriTessellation {
        segments: plan.segments,
        positions,
        normals,
        triangles: plan.triangles.clone(),
    }
}

/// The CPU twin of [`crate::GpuLoopLimit::samples`] and [`crate::GpuLoopLimit::eval`]:
/// `stride` (6 or 12) floats per `(patch, u, v)` query.
pub fn loop_eval_cpu(limit: &LoopLimit, queries: &[(u32, f32, f32)], stride: usize) -> Vec<f32> {
    let t = LoopTables::new(limit);
    let q = pack_queries(queries);
    let cfg = LoopConfig {
        item_count: queries.len() as u32,
        grid_width: queries.len() as u32,
        out_stride: stride as u32,
        num_patches: t.num_patches,
    };
    let inp = LoopInputs {
        queries: &q,
        patch_info: &t.patch_info,
        points: &t.points,
    };
    let mut out = vec![0.0; queries.len() * stride];
    loop_eval(&cfg, &inp, &mut out);
    out
}

/// The CPU twin of [`crate::GpuLoopLimit::tessellate`].
pub fn loop_tessellate_cpu(
    limit: &LoopLimit,
    base: &Topology,
    segments: usize,
) -> subsurf::Result<TriTessellation> {
    let plan = tri_tessellation_plan(base, segments)?;
    let queries = plan_queries(limit, &plan)?;
    Ok(assemble(&plan, &loop_eval_cpu(limit, &queries, 6)))
}
