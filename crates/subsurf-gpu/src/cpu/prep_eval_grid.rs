//! CPU twin of `shaders/prep_eval_grid.wgsl`: the p-rep evaluated on `n×n` samples per face
//! into a watertight vertex buffer (position + unit normal, 6 floats per vertex) and an index
//! buffer of ccw triangles (Myles, Yeo & Peters 2008, §4 "pass 2").
//!
//! ```text
//! x(u,v) = Σ_{i,j<4} g_ij B³_i(u) B³_j(v) + Σ_{16 slots} h_ij B⁵_i(u) B⁵_j(v)
//! ```
//!
//! Run once per sub-problem (`crate::prep_chunks`; the whole mesh when it is one). Items of a
//! sub-problem, in its region of the vertex buffer: one sample per owned vertex (its limit
//! point, normal `e1 × e2`), `n − 2` per owned edge, `(n − 2)²` per face; with one
//! sub-problem this is the layout of `PrepPatches::tessellate`. A shared-edge sample is
//! computed once, by the invocation of its edge, from the edge curve
//! `Σ g_i0 B³_i + h20 B⁵_2 + h30 B⁵_3` of the face owning the edge in its canonical direction,
//! and the triangles of both faces index it: the two sides are the same vertex, so the mesh
//! is watertight bit for bit by construction.

use crate::shared::PrepConfig;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;
const NO_H: u32 = u32::MAX;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::PREP_EVAL_GRID_WORKGROUP_SIZE);

type V = [f32; 3];

/// Flat index `i (d+1) + j` of local `(i, j)` at corner `c` (as the shader's `corner_index`).
pub fn corner_index_flat(c: u32, i: u32, j: u32, d: u32) -> u32 {
    let (a, b) = match c {
        0 => (i, j),
        1 => (d - j, i),
        2 => (d - i, d - j),
        _ => (j, d - i),
    };
    a * (d + 1) + b
}

/// Bernstein values and derivatives of degree 3 and 5 at `t`.
#[derive(Debug, Clone, Copy)]
pub struct Basis {
    b3: [f32; 4],
    d3: [f32; 4],
    b5: [f32; 6],
    d5: [f32; 6],
}

impl Basis {
    /// The basis at `t` (same expressions as the shader).
    pub fn new(t: f32) -> Self {
        let s = 1.0 - t;
        let b3 = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
        let (q0, q1, q2) = (s * s, 2.0 * s * t, t * t);
        let d3 = [-3.0 * q0, 3.0 * (q0 - q1), 3.0 * (q1 - q2), 3.0 * q2];
        let (s2, t2) = (s * s, t * t);
        let b5 = [
            s2 * s2 * s,
            5.0 * s2 * s2 * t,
            10.0 * s2 * s * t2,
            10.0 * s2 * t2 * t,
            5.0 * s * t2 * t2,
            t2 * t2 * t,
        ];
        let c = [
            s2 * s2,
            4.0 * s2 * s * t,
            6.0 * s2 * t2,
            4.0 * s * t2 * t,
            t2 * t2,
        ];
        let d5 = [
            -5.0 * c[0],
            5.0 * (c[0] - c[1]),
            5.0 * (c[1] - c[2]),
            5.0 * (c[2] - c[3]),
            5.0 * (c[3] - c[4]),
            5.0 * c[4],
        ];
        Basis { b3, d3, b5, d5 }
    }
}

/// Read-only inputs of the vertex entry (bindings 1..=5 of the shader, in order).
#[derive(Debug, Clone, Copy)]
pub struct EvalInputs<'a> {
    /// Binding 1: the `n` parameters `t_i = i / (n − 1)`.
    pub params: &'a [f32],
    /// Binding 2: face corner `4 f + c` whose edge runs in the canonical direction (E).
    pub edge_corner: &'a [u32],
    /// Binding 3: h block of each face (F).
    pub h_index: &'a [u32],
    /// Binding 4: vertex pass output.
    pub vertex_data: &'a [f32],
    /// Binding 5: patch pass output.
    pub patch_data: &'a [f32],
}

fn get(buf: &[f32], slot: u32) -> V {
    let i = 3 * slot as usize;
    [buf[i], buf[i + 1], buf[i + 2]]
}

fn axpy(acc: V, s: f32, a: V) -> V {
    [acc[0] + s * a[0], acc[1] + s * a[1], acc[2] + s * a[2]]
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalized(a: V) -> V {
    let l2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    if l2 > 0.0 {
        let s = 1.0 / l2.sqrt();
        [s * a[0], s * a[1], s * a[2]]
    } else {
        a
    }
}

/// Flat `i 6 + j` of slot `s` of a compact h block.
fn h_slot(s: u32) -> u32 {
    let m = s % 4;
    corner_index_flat(s / 4, 2 + m % 2, m / 2, 5)
}

/// `(x, ∂x/∂u, ∂x/∂v)` of face `f`.
fn eval_patch(cfg: &PrepConfig, inp: &EvalInputs<'_>, f: u32, bu: &Basis, bv: &Basis) -> [V; 3] {
    let (mut p, mut du, mut dv) = ([0.0f32; 3], [0.0f32; 3], [0.0f32; 3]);
    // The bi-3 part relative to g00 (its weights sum to 1; h is a perturbation).
    let x0 = get(inp.patch_data, 16 * f);
    for i in 0..4 {
        for j in 0..4 {
            let xk = get(inp.patch_data, 16 * f + 4 * i as u32 + j as u32);
            let x: V = std::array::from_fn(|c| xk[c] - x0[c]);
            p = axpy(p, bu.b3[i] * bv.b3[j], x);
            du = axpy(du, bu.d3[i] * bv.b3[j], x);
            dv = axpy(dv, bu.b3[i] * bv.d3[j], x);
        }
    }
    let hi = inp.h_index[f as usize];
    if hi != NO_H {
        let hb = 16 * cfg.num_faces + 16 * hi;
        for s in 0..16 {
            let ij = h_slot(s);
            let (i, j) = ((ij / 6) as usize, (ij % 6) as usize);
            let x = get(inp.patch_data, hb + s);
            p = axpy(p, bu.b5[i] * bv.b5[j], x);
            du = axpy(du, bu.d5[i] * bv.b5[j], x);
            dv = axpy(dv, bu.b5[i] * bv.d5[j], x);
        }
    }
    p = axpy(p, 1.0, x0);
    [p, du, dv]
}

/// One invocation of entry `main`: output vertex `first_item + local`, written at
/// `out_shift + 6 local` of binding 6 (`out_vertices`).
pub fn prep_eval_grid_invocation(
    local: u32,
    cfg: &PrepConfig,
    inp: &EvalInputs<'_>,
    out_vertices: &mut [f32],
) {
    if local >= cfg.item_count {
        return;
    }
    let item = cfg.first_item + local;
    let n = cfg.samples;
    let m = n - 2;
    let (nv, ne) = (cfg.owned_vertices, cfg.num_edges);
    let (p, nrm) = if item < nv {
        let e1 = get(inp.vertex_data, cfg.num_vertices + item);
        let e2 = get(inp.vertex_data, 2 * cfg.num_vertices + item);
        (get(inp.vertex_data, item), normalized(cross(e1, e2)))
    } else if item < nv + ne * m {
        let e = (item - nv) / m;
        let s = (item - nv) % m + 1;
        let corner = inp.edge_corner[e as usize];
        let (f, c) = (corner / 4, corner % 4);
        let b = Basis::new(inp.params[s as usize]);
        let mut p = [0.0f32; 3];
        for i in 0..4 {
            p = axpy(
                p,
                b.b3[i as usize],
                get(inp.patch_data, 16 * f + corner_index_flat(c, i, 0, 3)),
            );
        }
        let hi = inp.h_index[f as usize];
        if hi != NO_H {
            let hb = 16 * cfg.num_faces + 16 * hi;
            p = axpy(p, b.b5[2], get(inp.patch_data, hb + 4 * c));
            p = axpy(p, b.b5[3], get(inp.patch_data, hb + 4 * c + 1));
        }
        let uv = corner_index_flat(c, s, 0, n - 1);
        let bu = Basis::new(inp.params[(uv / n) as usize]);
        let bv = Basis::new(inp.params[(uv % n) as usize]);
        let [_, du, dv] = eval_patch(cfg, inp, f, &bu, &bv);
        (p, normalized(cross(du, dv)))
    } else {
        let q = item - nv - ne * m;
        let f = q / (m * m);
        let r = q % (m * m);
        let (j, i) = (r / m + 1, r % m + 1);
        let bu = Basis::new(inp.params[i as usize]);
        let bv = Basis::new(inp.params[j as usize]);
        let [p, du, dv] = eval_patch(cfg, inp, f, &bu, &bv);
        (p, normalized(cross(du, dv)))
    };
    let o = (cfg.out_shift + 6 * local) as usize;
    out_vertices[o..o + 3].copy_from_slice(&p);
    out_vertices[o + 3..o + 6].copy_from_slice(&nrm);
}

/// Slot in the vertex buffer of grid sample `(i, j)` of face `f` (binding 7 =
/// `corner_slots`: per face 4 corner-vertex slots, then 4 first-edge-sample slots with bit 31
/// set when the face runs along the edge's canonical direction).
pub fn grid_vertex(cfg: &PrepConfig, corner_slots: &[u32], f: u32, i: u32, j: u32) -> u32 {
    let n = cfg.samples;
    let (last, m) = (n - 1, n - 2);
    let slot = |k: u32| corner_slots[(8 * f + k) as usize];
    match (i, j) {
        (0, 0) => return slot(0),
        (x, 0) if x == last => return slot(1),
        (x, y) if x == last && y == last => return slot(2),
        (0, y) if y == last => return slot(3),
        _ => {}
    }
    let edge = if j == 0 {
        Some((0, i))
    } else if i == last {
        Some((1, j))
    } else if j == last {
        Some((2, last - i))
    } else if i == 0 {
        Some((3, last - j))
    } else {
        None
    };
    match edge {
        Some((c, s)) => {
            let w = slot(4 + c);
            let k = if w & FORWARD != 0 { s - 1 } else { m - s };
            (w & !FORWARD) + k
        }
        None => cfg.face_slot_base + f * m * m + (j - 1) * m + (i - 1),
    }
}

/// Bit 31 of an edge entry of `corner_slots`: the face runs along the edge's direction.
pub const FORWARD: u32 = 1 << 31;

/// One invocation of entry `indices`: the two triangles of grid cell `first_item + local`,
/// written at `out_shift + 6 local` of binding 9 (`out_indices`).
pub fn prep_grid_indices_invocation(
    local: u32,
    cfg: &PrepConfig,
    corner_slots: &[u32],
    out_indices: &mut [u32],
) {
    if local >= cfg.item_count {
        return;
    }
    let item = cfg.first_item + local;
    let cells = cfg.samples - 1;
    let f = item / (cells * cells);
    let r = item % (cells * cells);
    let (j, i) = (r / cells, r % cells);
    let g = |i, j| grid_vertex(cfg, corner_slots, f, i, j);
    let (a, b, c, d) = (g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
    let o = (cfg.out_shift + 6 * local) as usize;
    out_indices[o..o + 6].copy_from_slice(&[a, b, c, a, c, d]);
}

/// The parameters `t_i = i / (n − 1)` in f32 (as `PrepPatches::tessellate` computes them).
pub fn grid_params(n: usize) -> Vec<f32> {
    let d = (n - 1) as f32;
    (0..n).map(|i| i as f32 / d).collect()
}
