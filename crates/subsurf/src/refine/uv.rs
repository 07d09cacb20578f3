//! Face-varying data (UVs) under linear interpolation (OpenSubdiv `FVAR_LINEAR_ALL`): each child
//! face corner gets the bilinear average of its parent face's values, so seams stay seams.

use crate::topology::Topology;

/// Refines per-corner values of `parent` (one per face corner) to per-corner values of its
/// child level, with the child face layout of [`super::refine_topology`].
pub fn refine_uvs_linear(parent: &Topology, corner_values: &[[f32; 2]]) -> Vec<[f32; 2]> {
    let mut out = vec![[0.0f32; 2]; 4 * parent.num_corners()];
    for f in 0..parent.num_faces() {
        let (s, n) = (parent.face_offsets[f] as usize, parent.face_size(f));
        let vals = &corner_values[s..s + n];
        let mut centre = [0.0f32; 2];
        for v in vals {
            centre[0] += v[0] / n as f32;
            centre[1] += v[1] / n as f32;
        }
        let mid = |a: [f32; 2], b: [f32; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        for j in 0..n {
            let jp = (j + n - 1) % n;
            let jn = (j + 1) % n;
            let slots = [
                vals[j],
                mid(vals[j], vals[jn]),
                centre,
                mid(vals[jp], vals[j]),
            ];
            let c = 4 * (s + j);
            for (slot, v) in slots.iter().enumerate() {
                let p = if n == 4 { (j + slot) & 3 } else { slot };
                out[c + p] = *v;
            }
        }
    }
    out
}
