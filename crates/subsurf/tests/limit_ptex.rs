//! Ptex layout of n-gons: sub-face `k` has `(0,0)` at corner `k`, `(1,0)` at the midpoint of
//! edge `k → k+1`, `(1,1)` at the face centre and `(0,1)` at the midpoint of edge `k−1 → k`,
//! as the level-1 child faces of `refine` are laid out. (Shapes without semi-sharp features,
//! where the level-1 limit masks give exact limit points.)

mod limit_common;

use limit_common::{bbox_diagonal, load_shape};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::{Refiner, Topology};

#[test]
fn ngon_subfaces_follow_the_child_face_layout() {
    for name in ["catmark_pyramid", "catmark_smoothtris0"] {
        let mesh = load_shape(name);
        let t = Topology::new(&mesh).unwrap();
        let s = LimitSurface::new(
            PatchTable::build(&t, &PatchOptions::default()).unwrap(),
            &mesh.positions,
        );
        // Exact limit positions of the level-1 vertices.
        let r = Refiner::new(t.clone(), 1).unwrap();
        let limit = r.limit(&r.refine_positions(&mesh.positions));
        let (nv, nf) = (t.num_vertices(), t.num_faces());
        let diag = bbox_diagonal(&mesh.positions);
        let mut checked = 0;
        for f in 0..nf {
            let n = t.face_size(f);
            if n == 4 {
                continue;
            }
            let fv = t.face_vertices(f);
            let fe = t.face_edges(f);
            for k in 0..n {
                let ptex = s.table().ptex_offsets()[f] as usize + k;
                let prev = (k + n - 1) % n;
                let c1 = &r.levels[1];
                // The child face of corner k has exactly these corners, in this order.
                let child = c1.face_vertices(t.arrays().face_offsets[f] as usize + k);
                let want = [
                    fv[k] as usize,
                    nv + nf + fe[k] as usize,
                    nv + f,
                    nv + nf + fe[prev] as usize,
                ];
                assert_eq!(child, want.map(|x| x as u32), "{name} face {f} corner {k}");
                for (&(u, v), &vert) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                    .iter()
                    .zip(&want)
                {
                    let p = s.eval(ptex, u, v).unwrap().p;
                    let q = limit[vert];
                    let d = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f32>().sqrt();
                    assert!(
                        d < 1e-5 * diag,
                        "{name} face {f} sub-face {k} ({u},{v}): {d}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 0, "{name} has no n-gon");
    }
}
