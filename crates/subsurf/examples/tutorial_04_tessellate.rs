//! Tutorial 4: adaptive tessellation — a tolerance or per-edge rates, always watertight.
//!
//! ```text
//! RatePolicy ──rates──▶ EdgeRates ──tessellate_rates──▶ triangles on the limit surface
//! ```
//!
//! A tessellation samples the limit surface with one integer rate per base edge (and an
//! interior rate per face). Every edge's samples are made once and shared by index by both
//! faces, so any mix of rates gives a closed mesh: no cracks, no T-junctions (OpenSubdiv's
//! `Bfr::Tessellation`). A [`RatePolicy`] picks the rates (a chordal tolerance, a longest
//! edge, pixels on screen), or they are set by hand ([`EdgeRates`]).
//!
//! `cargo run -p subsurf --example tutorial_04_tessellate`

use std::collections::HashMap;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::tess::{set_edge_rate, AdaptiveTessellation, EdgeRates, RatePolicy};
use subsurf::{io, Topology};

/// Checks that the triangles of `tess` close up as the base mesh `base` does: each output
/// edge is used by two triangles, once in each direction (consistent orientation), except
/// along the base mesh's boundary, which the output follows edge for edge (a base boundary
/// edge of rate `R` is `R` output edges used once); no triangle repeats a vertex; and the
/// Euler characteristic V - E + F is the base mesh's. A crack or a T-junction would leave
/// extra edges used once. Returns the number of output edges.
fn check_watertight(base: &Topology, tess: &AdaptiveTessellation) -> usize {
    let mut uses: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for t in &tess.triangles {
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[2] != t[0],
            "degenerate {t:?}"
        );
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                e.0 += 1
            } else {
                e.1 += 1
            }
        }
    }
    assert!(uses
        .values()
        .all(|&u| matches!(u, (1, 1) | (1, 0) | (0, 1))));
    let open = uses.values().filter(|&&u| u != (1, 1)).count();
    let boundary: u32 = base
        .boundary_edges()
        .iter()
        .map(|&e| tess.edge_rates[e as usize])
        .sum();
    assert_eq!(
        open, boundary as usize,
        "edges used once off the boundary: a crack"
    );
    let euler = |v: usize, e: usize, f: usize| v as i64 - e as i64 + f as i64;
    assert_eq!(
        euler(tess.positions.len(), uses.len(), tess.triangles.len()),
        euler(base.num_vertices(), base.num_edges(), base.num_faces())
    );
    uses.len()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The pawn: OpenSubdiv's `catmark_pawn`, a surface of revolution (open at its base)
    // with sharp creases, flat parts and tight bends.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/pawn.obj");
    let pawn = io::read_path(path)?;
    let topology = Topology::new(&pawn)?;
    println!(
        "pawn.obj: {} faces, {} boundary edges",
        topology.num_faces(),
        topology.boundary_edges().len()
    );
    let table = PatchTable::build(&topology, &PatchOptions::default())?;
    let surface = LimitSurface::new(table, &pawn.positions);

    // Rates for a chordal tolerance (a fraction of the bounding-box diagonal): flat parts get
    // few samples, bends many. A finer tolerance takes more triangles.
    let mut triangles = 0;
    for tolerance in [1e-2, 1e-3] {
        let rates = RatePolicy::Tolerance(tolerance).rates(&surface, "tutorial")?;
        let tess = surface.tessellate_rates(&rates, "tutorial")?;
        let edges = check_watertight(&topology, &tess);
        let (lo, hi) = rates
            .edges
            .iter()
            .fold((u32::MAX, 0), |(a, b), &r| (a.min(r), b.max(r)));
        println!(
            "tolerance {tolerance:.0e}: edge rates {lo}..={hi}, {} vertices, {edges} edges, {} \
             triangles, watertight",
            tess.positions.len(),
            tess.triangles.len()
        );
        assert!(tess.triangles.len() > triangles);
        triangles = tess.triangles.len();
    }

    // Rates by hand (`EdgeRates`: one per base edge, in `Topology::edge_verts` order): every
    // edge at 4, the first creased edge at 17. The faces on both sides grade their rows to
    // meet it, and the mesh still closes up.
    let mut rates: EdgeRates = RatePolicy::Uniform(4).rates(&surface, "tutorial")?;
    let (v0, v1) = (pawn.creases[0].v0, pawn.creases[0].v1);
    set_edge_rate(
        &mut rates,
        &topology,
        "tutorial",
        [v0.into(), v1.into()],
        17,
    )?;
    let tess = surface.tessellate_rates(&rates, "tutorial")?;
    check_watertight(&topology, &tess);
    // Every sample lies on the limit surface; the normals come with them.
    assert_eq!(tess.normals.len(), tess.positions.len());
    println!(
        "uniform 4, edge {v0}-{v1} at 17: {} triangles, watertight",
        tess.triangles.len()
    );
    Ok(())
}
