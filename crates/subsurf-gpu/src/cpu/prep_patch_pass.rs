//! CPU twin of `shaders/prep_patch_pass.wgsl`: the p-rep patch pass over flat buffers
//! (Myles, Yeo & Peters 2008, §4, eqs. (8), (9)).
//!
//! Per face: the 16 bi-3 coefficients `g` from the vertex data of its corners, and for a
//! perturbed face the 16 non-zero `h` of its four edges. The edge formulas are those of
//! `subsurf::prep::kernel::edge_h`, called here with the inputs read from the flat
//! buffers exactly as the shader reads them; the twin thus reproduces `PrepPatches<f32>`.

use crate::shared::PrepConfig;
use subsurf::prep::kernel::{corner_index, edge_h, EdgeInputs};

use super::prep_vertex_pass::valence_base;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;
/// `h_index` of a face without perturbation (a B-quad).
pub const NO_H: u32 = u32::MAX;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::PREP_PATCH_PASS_WORKGROUP_SIZE);

type V = [f32; 3];

/// Read-only inputs of the patch pass (bindings 1..=6 of the shader, in order).
#[derive(Debug, Clone, Copy)]
pub struct PatchInputs<'a> {
    /// Binding 1: vertex of each face corner (4 F).
    pub face_verts: &'a [u32],
    /// Binding 2: sector number of each face corner (4 F).
    pub corner_sector: &'a [u32],
    /// Binding 3: ring offsets (V + 1); valence `= (r[v+1] - r[v]) / 2`, sector base `r[v] / 2`.
    pub ring_offsets: &'a [u32],
    /// Binding 4: h block of each face, [`NO_H`] for a B-quad (F).
    pub h_index: &'a [u32],
    /// Binding 5: the flat valence table (see `prep_vertex_pass::valence_consts`).
    pub valence_consts: &'a [f32],
    /// Binding 6: the vertex pass's output.
    pub vertex_data: &'a [f32],
}

impl PatchInputs<'_> {
    fn vd(&self, slot: usize) -> V {
        let d = &self.vertex_data[3 * slot..3 * slot + 3];
        [d[0], d[1], d[2]]
    }
    fn valence(&self, v: usize) -> usize {
        (self.ring_offsets[v + 1] - self.ring_offsets[v]) as usize / 2
    }
    fn tangent(&self, c: &PrepConfig, base: usize, x: usize, n: usize) -> V {
        self.vd(3 * c.num_vertices as usize + base + x % n)
    }
    fn interior(&self, c: &PrepConfig, base: usize, x: usize, n: usize) -> V {
        self.vd(3 * c.num_vertices as usize + c.num_sectors as usize + base + x % n)
    }
}

fn store(out: &mut [f32], slot: usize, x: V) {
    out[3 * slot..3 * slot + 3].copy_from_slice(&x);
}

/// One invocation: face `first_item + local`'s `g` and, when perturbed, its `h` (binding 7 =
/// `patch_data`).
pub fn prep_patch_pass_invocation(
    local: u32,
    config: &PrepConfig,
    inp: &PatchInputs<'_>,
    patch_data: &mut [f32],
) {
    if local >= config.item_count {
        return;
    }
    let f = (config.first_item + local) as usize;
    for c in 0..4 {
        let v = inp.face_verts[4 * f + c] as usize;
        let k = inp.corner_sector[4 * f + c] as usize;
        let n = inp.valence(v);
        let base = inp.ring_offsets[v] as usize / 2;
        let local = [
            ((0, 0), inp.vd(v)),
            ((1, 0), inp.tangent(config, base, k, n)),
            ((0, 1), inp.tangent(config, base, k + 1, n)),
            ((1, 1), inp.interior(config, base, k, n)),
        ];
        for ((i, j), x) in local {
            let (a, b) = corner_index(c, i, j, 3);
            store(patch_data, 16 * f + 4 * a + b, x);
        }
    }
    let hi = inp.h_index[f];
    if hi == NO_H {
        return;
    }
    let hb = 16 * config.num_faces as usize + 16 * hi as usize;
    for c in 0..4 {
        let v0 = inp.face_verts[4 * f + c] as usize;
        let v1 = inp.face_verts[4 * f + (c + 1) % 4] as usize;
        let (n0, n1) = (inp.valence(v0), inp.valence(v1));
        let k = inp.corner_sector[4 * f + c] as usize;
        let m = inp.corner_sector[4 * f + (c + 1) % 4] as usize;
        let (b0, b1) = (
            inp.ring_offsets[v0] as usize / 2,
            inp.ring_offsets[v1] as usize / 2,
        );
        let t0 = |x: usize| inp.tangent(config, b0, x, n0);
        let t1 = |x: usize| inp.tangent(config, b1, x, n1);
        let i0 = |x: usize| inp.interior(config, b0, x, n0);
        let i1 = |x: usize| inp.interior(config, b1, x, n1);
        let e = EdgeInputs {
            g00: inp.vd(v0),
            g10: t0(k),
            g20: t1(m + 1),
            g30: inp.vd(v1),
            g01: t0(k + 1),
            g11: i0(k),
            g21: i1(m),
            g31: t1(m),
            gs10: t0(k + n0 - 1),
            gs11: i0(k + n0 - 1),
            gs12: i1(m + 1),
            gs13: t1(m + 2),
        };
        let c0 = inp.valence_consts[valence_base(n0)];
        let c1 = inp.valence_consts[valence_base(n1)];
        let out = edge_h(&e, n0, n1, c0, c1);
        for (s, x) in out.into_iter().enumerate() {
            store(patch_data, hb + 4 * c + s, x);
        }
    }
}

/// Runs every invocation of one dispatch.
pub fn prep_patch_pass(config: &PrepConfig, inp: &PatchInputs<'_>, patch_data: &mut [f32]) {
    for f in 0..config.item_count {
        prep_patch_pass_invocation(f, config, inp, patch_data);
    }
}
