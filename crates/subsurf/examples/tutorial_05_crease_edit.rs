//! Tutorial 5: crease edits on a live limit surface — equal to a fresh build.
//!
//! Sharpness (of edges: creases, of vertices: corners) changes the surface without changing
//! the connectivity. Instead of rebuilding the patch table from the edited mesh, a
//! [`SharpnessEdit`] list updates the built table: in place where the isolation structure
//! is kept, else from the first level that changes. Either way the table equals, bit for
//! bit, what [`PatchTable::build`] makes of the edited mesh — what a crease slider needs.
//!
//! `cargo run -p subsurf --example tutorial_05_crease_edit`

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::{shapes, Corner, Crease, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cube = shapes::cube();
    let options = PatchOptions::default();
    // `build_editable` keeps the refined levels, so that even the first edit is in place.
    let table = PatchTable::build_editable(&Topology::new(&cube)?, &options)?;
    let mut surface = LimitSurface::new(table, &cube.positions);

    // A slider on the edge between base vertices 0 and 1 (the first edge of face 0: its
    // midpoint is (u, v) = (0.5, 0)). The sharper the crease, the closer the surface comes to
    // the cage edge's midpoint (0, -1, 1).
    let gap = |s: &LimitSurface| {
        let p = s.eval(0, 0.5, 0.0).expect("face 0").p;
        (p[0].powi(2) + (p[1] + 1.0).powi(2) + (p[2] - 1.0).powi(2)).sqrt()
    };
    let mut last = gap(&surface);
    println!("sharpness 0.0: surface {last:.4} from the cage edge");
    for sharpness in [0.5, 1.0, 2.0, 3.0, 10.0] {
        let edit = SharpnessEdit::Edge {
            v0: 0,
            v1: 1,
            sharpness,
        };
        let outcome = surface.apply_sharpness(&[edit], &cube.positions)?;
        // Where the table changed, its points were made again from the base positions.
        let now = gap(&surface);
        println!("sharpness {sharpness:.1}: surface {now:.4} from the cage edge ({outcome:?})");
        assert!(now < last);
        last = now;
    }

    // A vertex edit: an infinitely sharp corner at vertex 3 (corner (1, 1) of face 0) pulls
    // the surface there towards its control point. (The limit point is the control point
    // itself; the patches around an interior sharp corner approach it as the isolation level
    // rises, as OpenSubdiv's do.)
    let corner_gap = |s: &LimitSurface| {
        let p = s.eval(0, 1.0, 1.0).expect("face 0").p;
        (0..3)
            .map(|c| (p[c] - cube.positions[3][c]).powi(2))
            .sum::<f32>()
            .sqrt()
    };
    let before = corner_gap(&surface);
    surface.apply_sharpness(
        &[SharpnessEdit::Vertex {
            vertex: 3,
            sharpness: 10.0,
        }],
        &cube.positions,
    )?;
    let after = corner_gap(&surface);
    println!("corner 3: surface {before:.4} -> {after:.4} from its control point");
    assert!(after < 0.5 * before);

    // The edited surface against a fresh build of the edited mesh: the same samples, bit
    // for bit.
    let mut edited = cube.clone();
    edited.creases.push(Crease {
        v0: 0,
        v1: 1,
        sharpness: 10.0,
    });
    edited.corners.push(Corner {
        vertex: 3,
        sharpness: 10.0,
    });
    let fresh = PatchTable::build(&Topology::new(&edited)?, &options)?;
    let fresh = LimitSurface::new(fresh, &edited.positions);
    assert_eq!(fresh.table().num_patches(), surface.table().num_patches());
    let (a, b) = (surface.tessellate(9)?, fresh.tessellate(9)?);
    assert_eq!(a.quads, b.quads);
    assert!(a
        .positions
        .iter()
        .zip(&b.positions)
        .all(|(p, q)| p.map(f32::to_bits) == q.map(f32::to_bits)));
    println!(
        "edited table == fresh build: {} patches, {} samples identical",
        surface.table().num_patches(),
        a.positions.len()
    );
    Ok(())
}
