//! Per-edge-rate tessellation: watertight with any mix of rates on every regression shape
//! (exact, combinatorial), and free of slivers and flipped triangles at rate ratios up to 64:1.

mod limit_common;

use std::collections::HashMap;

use limit_common::{load_shape, shape_names};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::tess::{plan, plan_without_uv, EdgeRates};
use subsurf::Topology;

/// A small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u32) -> u32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) % u64::from(n)) as u32
    }
}

fn table(name: &str) -> (subsurf::Mesh, PatchTable) {
    let mesh = load_shape(name);
    let t = Topology::new(&mesh).unwrap();
    let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
    (mesh, table)
}

/// Undirected output edge → number of triangles using it.
fn edge_uses(tris: &[[u32; 3]]) -> HashMap<(u32, u32), usize> {
    let mut m = HashMap::new();
    for tri in tris {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *m.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    m
}

/// Random rates on every edge of every shape: each base edge of rate `R` used by `L` live
/// faces becomes `R` output edges used `L` times, every other output edge is used twice (no
/// crack, no T-junction — either would leave an edge used once), no triangle repeats a
/// vertex, and the Euler characteristic of the live faces is preserved. Shapes with faces
/// that repeat a vertex (the `quadpole` ones) are only planned, not checked.
#[test]
fn random_rates_are_watertight_on_every_shape() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut degenerate_shapes = Vec::new();
    for name in shape_names() {
        let (_, table) = table(&name);
        let t = &table.base();
        let live = |f: u32| !t.face_is_hole(f as usize);
        for round in 0..2 {
            let max = if round == 0 { 6 } else { 40 };
            let rates = EdgeRates {
                edges: (0..t.num_edges()).map(|_| 1 + rng.below(max)).collect(),
                faces: Vec::new(),
            };
            let p = plan(&table, &rates, "test").unwrap();
            // Without the triangles' (u, v): the same plan otherwise.
            let q = plan_without_uv(&table, &rates, "test").unwrap();
            assert!(q.triangle_uv.is_empty() && p.triangle_uv.len() == p.triangles.len());
            assert_eq!(
                (&q.queries, &q.triangles),
                (&p.queries, &p.triangles),
                "{name}"
            );
            assert_eq!(
                (&q.edge_rates, &q.ptex_rates),
                (&p.edge_rates, &p.ptex_rates)
            );
            if !t.degenerate_faces().is_empty() {
                // Faces repeating a vertex (the quad poles) collapse; only the plan is checked.
                degenerate_shapes.push(name.clone());
                continue;
            }
            let uses = edge_uses(&p.triangles);
            let degenerate = p
                .triangles
                .iter()
                .filter(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                .count();
            assert_eq!(degenerate, 0, "{name}: triangles repeating a vertex");
            let mut want: HashMap<usize, usize> = HashMap::new();
            let mut got: HashMap<usize, usize> = HashMap::new();
            let (mut v0, mut e0, mut f0) = (0i64, 0i64, 0i64);
            let mut vert_live = vec![false; t.num_vertices()];
            for e in 0..t.num_edges() {
                let l = t.edge_faces(e).iter().filter(|&&f| live(f)).count();
                if l > 0 {
                    e0 += 1;
                    t.edge_vertices(e)
                        .iter()
                        .for_each(|&v| vert_live[v as usize] = true);
                }
                if l != 2 && l > 0 {
                    *want.entry(l).or_default() += p.edge_rates[e] as usize;
                }
            }
            v0 += vert_live.iter().filter(|&&b| b).count() as i64;
            f0 += (0..t.num_faces() as u32).filter(|&f| live(f)).count() as i64;
            for &c in uses.values() {
                if c != 2 {
                    *got.entry(c).or_default() += 1;
                }
            }
            assert_eq!(got, want, "{name} round {round}: edges by use count");
            let chi = p.queries.len() as i64 - uses.len() as i64 + p.triangles.len() as i64;
            assert_eq!(
                chi,
                v0 - e0 + f0,
                "{name} round {round}: Euler characteristic"
            );
        }
    }
    degenerate_shapes.dedup();
    assert!(degenerate_shapes.len() <= 3, "{degenerate_shapes:?}");
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| f64::from(a[i]) - f64::from(b[i]))
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Rates of 1 and 64 mixed at random on smooth closed shapes: every triangle faces the way
/// the limit surface does (its normal against the surface normal at its centroid and the sum
/// of its vertex normals) and its
/// smallest angle stays above 0.5° — the transition strips do not make slivers.
#[test]
fn mixed_rates_up_to_64_to_1_make_no_slivers_or_flips() {
    let mut rng = Rng(7);
    let mut worst = f64::MAX;
    for name in [
        "catmark_cube",
        "catmark_torus",
        "catmark_pyramid",
        "catmark_smoothtris0",
    ] {
        let (mesh, table) = table(name);
        let t = &table.base();
        let rates = EdgeRates {
            edges: (0..t.num_edges())
                .map(|_| if rng.below(2) == 0 { 1 } else { 64 })
                .collect(),
            faces: Vec::new(),
        };
        let s = LimitSurface::new(table, &mesh.positions);
        let p = plan(s.table(), &rates, "test").unwrap();
        let uv = p.triangle_uv.clone();
        let p_rates = p.ptex_rates.clone();
        let out = s.eval_plan(p);
        for (tri, (ptex, c)) in out.triangles.iter().zip(&uv) {
            let [a, b, c3] = tri.map(|i| out.positions[i as usize]);
            let n = cross(sub(b, a), sub(c3, a));
            let (u, v) = (
                (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            );
            let sn = s.eval(*ptex as usize, u, v).unwrap().n.map(f64::from);
            let vn = tri.map(|i| out.normals[i as usize]);
            let vsum = [0, 1, 2].map(|k| f64::from(vn[0][k] + vn[1][k] + vn[2][k]));
            assert!(
                dot(n, sn) > 0.0 && dot(n, vsum) > 0.0,
                "{name}: flipped triangle {tri:?}, ptex {ptex} at {c:?}, rates {:?}",
                p_rates[*ptex as usize]
            );
            for (p0, p1, p2) in [(a, b, c3), (b, c3, a), (c3, a, b)] {
                let (x, y) = (sub(p1, p0), sub(p2, p0));
                let cos = dot(x, y) / (dot(x, x) * dot(y, y)).sqrt();
                let ang = cos.clamp(-1.0, 1.0).acos().to_degrees();
                worst = worst.min(ang);
            }
        }
    }
    eprintln!("smallest angle at rates 1 and 64: {worst:.2} degrees");
    assert!(worst > 0.5, "smallest angle {worst} degrees");
}
