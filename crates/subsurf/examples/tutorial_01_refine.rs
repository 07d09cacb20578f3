//! Tutorial 1: read a mesh, refine it uniformly, write the result as OBJ.
//!
//! The pipeline of every subsurf program starts here:
//!
//! ```text
//! file ──io::read_path──▶ Mesh ──Topology::new──▶ Topology ──Refiner::new──▶ levels + stencils
//! ```
//!
//! A [`Mesh`] is what a file holds (positions, faces, crease tags), unchecked. A [`Topology`]
//! is the validated, connected model (edges, rings, tags). A [`Refiner`] refines the topology
//! once and keeps one stencil table per level; refining positions only applies those tables.
//!
//! `cargo run -p subsurf --example tutorial_01_refine`

use subsurf::{io, Mesh, Refiner, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The car: OpenSubdiv's `catmark_car` regression shape, all quads, with semi-sharp creases.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/car.obj");
    let mesh: Mesh = io::read_path(path)?; // the format is chosen by the extension
    let base = Topology::new(&mesh)?;
    println!(
        "car.obj: {} vertices, {} edges, {} faces, {} crease tags",
        base.num_vertices(),
        base.num_edges(),
        base.num_faces(),
        mesh.creases.len()
    );

    // Two uniform Catmull-Clark steps. `levels[0]` is the base, `levels[k]` k steps down.
    let level = 2;
    let refiner = Refiner::new(base, level)?;

    // Each step adds one vertex per face (its face point) and one per edge (its edge point)
    // after the parent vertices, which keep their indices; every quad splits into four.
    // The Euler characteristic V - E + F is a topological invariant: refinement keeps it.
    let euler =
        |t: &Topology| t.num_vertices() as i64 - t.num_edges() as i64 + t.num_faces() as i64;
    for k in 0..level {
        let (parent, child) = (&refiner.levels[k], &refiner.levels[k + 1]);
        assert_eq!(
            child.num_vertices(),
            parent.num_vertices() + parent.num_faces() + parent.num_edges()
        );
        assert_eq!(child.num_faces(), 4 * parent.num_faces());
        assert_eq!(euler(child), euler(parent));
        println!(
            "level {}: {} vertices, {} faces (V - E + F = {})",
            k + 1,
            child.num_vertices(),
            child.num_faces(),
            euler(child)
        );
    }

    // The vertex data: positions of the last level, from the base positions.
    let positions = refiner.refine_positions(&mesh.positions);
    assert_eq!(positions.len(), refiner.last().num_vertices());

    // A mesh of the last level that keeps the sharpness left there: a crease of sharpness s
    // is s - 1 one level down, and each creased edge is now two. (The car's creases are all
    // of sharpness 6, so 4 at level 2.)
    let refined = refiner.to_tagged_mesh(level, positions)?;
    assert_eq!(refined.creases.len(), mesh.creases.len() << level);
    assert!(mesh.creases.iter().all(|c| c.sharpness == 6.0));
    assert!(refined.creases.iter().all(|c| c.sharpness == 4.0));

    // Write it (OBJ, chosen by the extension) and read it back.
    let out = std::env::temp_dir().join(format!("subsurf_tutorial_01_{}.obj", std::process::id()));
    io::write_path(&out, &refined, None)?;
    let back = io::read_path(&out)?;
    assert_eq!(*back.positions, *refined.positions); // OBJ keeps every f32 bit
    assert_eq!(back.face_indices, refined.face_indices);
    assert_eq!(back.creases.len(), refined.creases.len());
    println!(
        "wrote {} ({} faces, {} crease tags) and read it back",
        out.display(),
        back.num_faces(),
        back.creases.len()
    );
    std::fs::remove_file(&out)?;
    Ok(())
}
