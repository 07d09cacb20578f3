//! CPU twins of [`crate::GpuLimit`]'s evaluation (re-exported from [`crate::limit`]).

use crate::cpu::limit_eval::{limit_eval, pack_queries, LimitInputs, LimitTables};
use crate::shared::LimitConfig;
use subsurf::limit::{LimitPoint, PatchTable, Tessellation};

/// Limit points from a kernel output of `stride` floats per sample.
pub fn unpack_points(out: &[f32], stride: usize) -> Vec<LimitPoint> {
    out.chunks_exact(stride)
        .map(|o| {
            let v = |k: usize| [o[k], o[k + 1], o[k + 2]];
            LimitPoint {
                p: v(0),
                n: v(3),
                du: if stride >= 12 { v(6) } else { [0.0; 3] },
                dv: if stride >= 12 { v(9) } else { [0.0; 3] },
            }
        })
        .collect()
}

/// The CPU twin of [`crate::GpuLimit::update`] followed by [`crate::GpuLimit::eval`]: `stride` floats per
/// query from the flat point array `points` ([`PatchTable::points`]).
pub fn eval_cpu(
    table: &PatchTable,
    points: &[[f32; 3]],
    queries: &[(u32, f32, f32)],
    stride: usize,
) -> Vec<f32> {
    let t = LimitTables::new(table);
    let q = pack_queries(queries);
    let cfg = LimitConfig {
        item_count: queries.len() as u32,
        grid_width: queries.len() as u32,
        out_stride: stride as u32,
        num_roots: t.num_roots,
    };
    let inp = LimitInputs {
        queries: &q,
        patch_map: &t.patch_map,
        patch_info: &t.patch_info,
        cvs: &t.cvs,
        points: points.as_flattened(),
    };
    let mut out = vec![0.0; queries.len() * stride];
    limit_eval(&cfg, &inp, &mut out);
    out
}

/// The CPU twin of a [`crate::GpuTessellation`]: the plan's samples evaluated by the twin.
pub fn tessellate_cpu(
    table: &PatchTable,
    points: &[[f32; 3]],
    samples_per_side: usize,
) -> subsurf::Result<Tessellation> {
    let plan = table.tessellation_plan(samples_per_side)?;
    let out = eval_cpu(table, points, &plan.queries, 6);
    Ok(Tessellation {
        samples_per_side: plan.samples_per_side,
        positions: out.chunks_exact(6).map(|v| [v[0], v[1], v[2]]).collect(),
        normals: out.chunks_exact(6).map(|v| [v[3], v[4], v[5]]).collect(),
        quads: plan.quads,
    })
}
