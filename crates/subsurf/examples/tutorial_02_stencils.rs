//! Tutorial 2: stencil tables for animation — build once, apply every frame.
//!
//! Refinement is linear in the control points: every refined point is a fixed weighted sum
//! of base points, whatever the positions are. A [`StencilTable`] holds those sums as a
//! sparse matrix (`offsets`, `indices`, `weights`: flat arrays a GPU uploads as they are).
//! An animated mesh builds the table once from its topology, then each frame only applies it
//! to the moving control points (OpenSubdiv's `Far::StencilTable`).
//!
//! `cargo run -p subsurf --example tutorial_02_stencils`

use subsurf::{shapes, Refiner, StencilTable, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let torus = shapes::torus(12, 8, 2.0, 0.5);
    let level = 3;
    // Topology and stencils: built once, from connectivity and tags only.
    let refiner = Refiner::new(Topology::new(&torus)?, level)?;
    // The per-level tables composed into one, straight from base to level 3 ...
    let table: StencilTable = refiner.stencil_table();
    // ... and on to the limit surface: `a.then(b)` is "first a, then b".
    let to_limit: StencilTable = table.then(refiner.limit_table());
    println!(
        "{} base points -> {} refined points: {} stencil entries ({:.1} per row), {} KiB",
        table.num_inputs(),
        table.num_rows(),
        table.num_entries(),
        table.num_entries() as f64 / table.num_rows() as f64,
        table.size_bytes() / 1024
    );

    // Every row is an affine combination (its weights sum to 1), so moving every control
    // point by d moves every refined point by d.
    for r in 0..table.num_rows() {
        let (lo, hi) = (table.offsets()[r] as usize, table.offsets()[r + 1] as usize);
        let sum: f32 = table.weights()[lo..hi].iter().sum();
        assert!((sum - 1.0).abs() < 1e-5, "row {r} sums to {sum}");
    }

    // The animation: the torus twists about z. Per frame, one table application.
    let mut refined = vec![[0.0f32; 3]; table.num_rows()];
    let mut limit = vec![[0.0f32; 3]; to_limit.num_rows()];
    for frame in 0..4 {
        let moved: Vec<[f32; 3]> = torus
            .positions
            .iter()
            .map(|&[x, y, z]| {
                let a = 0.3 * frame as f32 * z; // twist angle grows with height
                let (s, c) = a.sin_cos();
                [c * x - s * y, s * x + c * y, z + 0.1 * frame as f32]
            })
            .collect();
        table.apply(&moved, &mut refined);
        to_limit.apply(&moved, &mut limit);

        // The same points as refining again level by level (up to f32 rounding: the
        // composed table sums the products in another order), and as moving them to the limit.
        let again = refiner.refine_positions(&moved);
        let again_limit = refiner.limit(&again);
        let err = |a: &[[f32; 3]], b: &[[f32; 3]]| {
            a.iter()
                .zip(b)
                .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
                .fold(0.0f32, f32::max)
        };
        let (e, el) = (err(&refined, &again), err(&limit, &again_limit));
        assert!(e < 1e-5 && el < 1e-5, "frame {frame}: {e:e}, {el:e}");
        println!(
            "frame {frame}: refined point 0 at {:?}, limit point 0 at {:?} (max difference \
             to a fresh refinement {e:.1e})",
            refined[0], limit[0]
        );
    }
    Ok(())
}
