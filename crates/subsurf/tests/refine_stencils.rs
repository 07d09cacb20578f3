//! `Refiner::stencils`, which a Catmull-Clark refiner derives on first use from the per-frame
//! plans it made from the topology, against the stencils the masks form directly
//! (`refine::level_stencils` of each pair of levels): the same tables, entry for entry and bit
//! for bit, on every regression shape (Loop and bilinear refiners keep the masks' tables).

use std::path::PathBuf;
use subsurf::refine::level_stencils;
use subsurf::{Refiner, Topology};

#[test]
fn stencils_from_the_plans_are_the_masks_tables() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let mut cases: Vec<(PathBuf, usize)> =
        subsurf::shapes::regression_shapes(&dir, &["catmark_", "bilinear_", "loop_"])
            .unwrap()
            .into_iter()
            .map(|p| (p, 2))
            .collect();
    assert!(cases.len() > 50);
    cases.push((dir.join("catmark_car.obj"), 3));
    let mut steps = 0;
    for (path, level) in cases {
        let m = subsurf::io::read_path(&path).unwrap();
        if m.options.scheme == subsurf::Scheme::Loop {
            continue;
        }
        let r = Refiner::new(Topology::new(&m).unwrap(), level).unwrap();
        for (k, s) in r.stencils().iter().enumerate() {
            let want = level_stencils(&r.levels[k], &r.levels[k + 1]);
            assert_eq!(s.num_parent_vertices(), want.num_parent_vertices());
            for (got, want, what) in [
                (&s.face(), &want.face(), "face"),
                (&s.vertex(), &want.vertex(), "vertex"),
                (&s.edge(), &want.edge(), "edge"),
            ] {
                assert_eq!(
                    got.offsets(),
                    want.offsets(),
                    "{} step {k} {what}",
                    path.display()
                );
                assert_eq!(
                    got.indices(),
                    want.indices(),
                    "{} step {k} {what}",
                    path.display()
                );
                let bits = |w: &[f32]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(got.weights()),
                    bits(want.weights()),
                    "{} step {k} {what}",
                    path.display()
                );
                assert_eq!(got.num_inputs(), want.num_inputs());
            }
            steps += 1;
        }
    }
    assert!(steps > 100);
}
