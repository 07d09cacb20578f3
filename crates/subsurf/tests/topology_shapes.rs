//! Topology invariants on every regression shape, at the base level and after refinement.

use std::collections::HashSet;
use std::path::PathBuf;
use subsurf::{Refiner, Scheme, Topology};

fn shapes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    v.sort();
    v
}

/// Connected components of the used vertices (union-find over edges).
fn components(t: &Topology) -> usize {
    let mut parent: Vec<usize> = (0..t.num_vertices()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for ev in t.arrays().edge_verts {
        let (a, b) = (
            find(&mut parent, ev[0] as usize),
            find(&mut parent, ev[1] as usize),
        );
        parent[a] = b;
    }
    let unused: HashSet<u32> = t.unused_vertices().into_iter().collect();
    (0..t.num_vertices())
        .filter(|&v| !unused.contains(&(v as u32)) && find(&mut parent, v) == v)
        .count()
}

#[test]
fn invariants_hold_on_every_shape_and_level() {
    let paths = shapes();
    assert!(paths.len() >= 90);
    for path in paths {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let mesh = subsurf::io::read_path(&path).unwrap();
        let t = Topology::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        t.check_consistency()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        // Edge count against an independent count of distinct vertex pairs (exact where no face
        // repeats an edge and no edge is degenerate, i.e. on manifold shapes).
        if t.is_manifold() {
            let pairs: HashSet<(u32, u32)> = (0..t.num_faces())
                .flat_map(|f| {
                    let fv = t.face_vertices(f);
                    (0..fv.len()).map(move |k| {
                        let (a, b) = (fv[k], fv[(k + 1) % fv.len()]);
                        (a.min(b), a.max(b))
                    })
                })
                .collect();
            assert_eq!(pairs.len(), t.num_edges(), "{name}: edge count");
            // Euler characteristic of a closed orientable surface is even.
            if t.is_closed() {
                let used = t.num_vertices() - t.unused_vertices().len();
                let chi = used as i64 - t.num_edges() as i64 + t.num_faces() as i64;
                let comps = components(&t);
                assert!(
                    chi % 2 == 0 && chi <= 2 * comps as i64,
                    "{name}: chi = {chi}, {comps} components"
                );
            }
        }
        if mesh.options.scheme != Scheme::Loop {
            let r = Refiner::new(t, 2).unwrap();
            for (k, level) in r.levels.iter().enumerate().skip(1) {
                level
                    .check_consistency()
                    .unwrap_or_else(|e| panic!("{name} level {k}: {e}"));
                // Refinement preserves V - E + F (each level is a subdivision of the same surface).
                let chi = |t: &Topology| {
                    t.num_vertices() as i64 - t.num_edges() as i64 + t.num_faces() as i64
                };
                assert_eq!(
                    chi(level),
                    chi(&r.levels[0]),
                    "{name} level {k}: Euler characteristic"
                );
            }
        }
    }
}
