//! CPU twin of `shaders/prep_vertex_pass.wgsl`: the p-rep vertex pass over flat buffers
//! (Myles, Yeo & Peters 2008, eqs. (2)–(4); `subsurf::prep::vertex_pass` gives the math).
//!
//! Per vertex `p0` of valence `n` with ring `p1 … p2n`:
//!
//! ```text
//! g00  = l0 p0 + l1 Σ p_{2j+1} + l2 Σ p_{2j+2}          l = (n/(n+5), 4/(n(n+5)), 1/(n(n+5)))
//! e1   = Σ_j (a1_j p_{2j+1} + b1_j p_{2j+2}),  e2 likewise with (a2_j, b2_j)
//! T(k) = g00 + cos_k e1 + sin_k e2,   I(k) = (4 p0 + 2 (p_{2k+1} + p_{2k+3}) + p_{2k+2}) / 9
//! ```
//!
//! The weights come from the flat `valence_consts` table ([`valence_consts`]), the f32
//! constants of `subsurf::prep::kernel::ValenceTable`, and every sum is formed in the
//! order of the library's vertex pass, so the twin reproduces `PrepPatches<f32>` bit for bit.

use crate::shared::PrepConfig;
use subsurf::prep::kernel::ValenceTable;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::PREP_VERTEX_PASS_WORKGROUP_SIZE);

/// Offset of valence `n`'s constants in the flat table: valence `m` holds `4 + 6 m` floats.
pub const fn valence_base(n: usize) -> usize {
    4 * n + 3 * n * n.saturating_sub(1)
}

/// The flat per-valence table for valences `0..=max_valence`: per valence `n`,
/// `[c_n, l0, l1, l2]` then per `j < n`: `[a1_j, b1_j, a2_j, b2_j, cos_j, sin_j]` (zeros for
/// `n < 3`, which no vertex of a checked mesh has).
pub fn valence_consts(max_valence: usize) -> Vec<f32> {
    let table = ValenceTable::<f32>::new(max_valence);
    let mut out = Vec::with_capacity(valence_base(max_valence + 1));
    for n in 0..=max_valence {
        debug_assert_eq!(out.len(), valence_base(n));
        if n < 3 {
            out.extend(std::iter::repeat_n(0.0, 4 + 6 * n));
            continue;
        }
        let c = table.get(n);
        out.extend_from_slice(&[c.c, c.limit[0], c.limit[1], c.limit[2]]);
        for j in 0..n {
            out.extend_from_slice(&[
                c.e1[j][0], c.e1[j][1], c.e2[j][0], c.e2[j][1], c.cos[j], c.sin[j],
            ]);
        }
    }
    out
}

type V = [f32; 3];

#[inline(always)]
fn pos(p: &[f32], i: u32) -> V {
    let i = 3 * i as usize;
    [p[i], p[i + 1], p[i + 2]]
}

#[inline(always)]
fn store(out: &mut [f32], slot: usize, x: V) {
    out[3 * slot..3 * slot + 3].copy_from_slice(&x);
}

#[inline(always)]
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
fn scale(s: f32, a: V) -> V {
    [s * a[0], s * a[1], s * a[2]]
}

/// One invocation (bindings 0..=5 in order): vertex `first_item + local`'s frame and its
/// sectors.
pub fn prep_vertex_pass_invocation(
    local: u32,
    config: &PrepConfig,
    positions: &[f32],
    ring_offsets: &[u32],
    ring_indices: &[u32],
    valence_consts: &[f32],
    vertex_data: &mut [f32],
) {
    if local >= config.item_count {
        return;
    }
    let v = config.first_item + local;
    let nv = config.num_vertices as usize;
    let vi = v as usize;
    let r0 = ring_offsets[vi] as usize;
    let n = (ring_offsets[vi + 1] as usize - r0) / 2;
    let p0 = pos(positions, v);
    if n == 0 {
        store(vertex_data, vi, p0);
        store(vertex_data, nv + vi, [0.0; 3]);
        store(vertex_data, 2 * nv + vi, [0.0; 3]);
        return;
    }
    let cb = valence_base(n);
    let k = valence_consts;
    let (mut se, mut sd, mut e1, mut e2) = ([0.0f32; 3], [0.0f32; 3], [0.0f32; 3], [0.0f32; 3]);
    for j in 0..n {
        let pe = pos(positions, ring_indices[r0 + 2 * j]);
        let pd = pos(positions, ring_indices[r0 + 2 * j + 1]);
        let w = cb + 4 + 6 * j;
        se = add(se, pe);
        sd = add(sd, pd);
        e1 = add(add(e1, scale(k[w], pe)), scale(k[w + 1], pd));
        e2 = add(add(e2, scale(k[w + 2], pe)), scale(k[w + 3], pd));
    }
    let g00 = add(
        add(scale(k[cb + 1], p0), scale(k[cb + 2], se)),
        scale(k[cb + 3], sd),
    );
    store(vertex_data, vi, g00);
    store(vertex_data, nv + vi, e1);
    store(vertex_data, 2 * nv + vi, e2);
    let tangent = 3 * nv;
    let interior = 3 * nv + config.num_sectors as usize;
    let s0 = r0 / 2;
    let ninth = (1.0f64 / 9.0) as f32;
    for s in 0..n {
        let w = cb + 4 + 6 * s;
        let t = add(add(g00, scale(k[w + 4], e1)), scale(k[w + 5], e2));
        store(vertex_data, tangent + s0 + s, t);
        let p1 = pos(positions, ring_indices[r0 + 2 * s]);
        let p2 = pos(positions, ring_indices[r0 + 2 * s + 1]);
        let p3 = pos(positions, ring_indices[r0 + (2 * s + 2) % (2 * n)]);
        let i = scale(ninth, add(add(scale(4.0, p0), scale(2.0, add(p1, p3))), p2));
        store(vertex_data, interior + s0 + s, i);
    }
}

/// Runs every invocation of one dispatch.
pub fn prep_vertex_pass(
    config: &PrepConfig,
    positions: &[f32],
    ring_offsets: &[u32],
    ring_indices: &[u32],
    valence_consts: &[f32],
    vertex_data: &mut [f32],
) {
    for v in 0..config.item_count {
        prep_vertex_pass_invocation(
            v,
            config,
            positions,
            ring_offsets,
            ring_indices,
            valence_consts,
            vertex_data,
        );
    }
}
