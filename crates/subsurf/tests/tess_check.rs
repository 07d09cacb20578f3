//! `--tolerance E` checked on every triangle (`tess::check`): on shapes whose creases,
//! corners and crease ends bend within less than the rate curves' sample spacing (and, on
//! `catmark_cube_creases1`, less than the triangles' first raise), every
//! triangle's edge midpoints and centroid come within the chord budget of the surface the
//! tessellation is drawn from, and within `E` of the true limit surface (an isolation-10
//! reference); the rate curves' estimate alone misses there.

mod limit_common;

use limit_common::{bbox_diagonal, dist, isolated, load_shape};
use subsurf::limit::{LimitSurface, PatchTable};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{chord_errors, plan, RatePolicy};
use subsurf::Topology;

type Uv = (u32, [[f32; 2]; 3]);

/// The worst distance between the flat triangles (corners at `corner(tri, k)`) and
/// `surface(ptex, u, v)` over every edge midpoint and centroid.
fn worst(
    triangles: &[[u32; 3]],
    uv: &[Uv],
    corner: &dyn Fn(usize, usize) -> [f64; 3],
    surface: &dyn Fn(u32, f32, f32) -> [f64; 3],
) -> f64 {
    let mut w = 0.0f64;
    for (n, (_, (ptex, c))) in triangles.iter().zip(uv).enumerate() {
        let x = [0, 1, 2].map(|k| corner(n, k));
        for i in 0..3 {
            let j = (i + 1) % 3;
            let m = surface(*ptex, 0.5 * (c[i][0] + c[j][0]), 0.5 * (c[i][1] + c[j][1]));
            w = w.max(dist([0, 1, 2].map(|q| 0.5 * (x[i][q] + x[j][q])), m));
        }
        let g = surface(
            *ptex,
            (c[0][0] + c[1][0] + c[2][0]) / 3.0,
            (c[0][1] + c[1][1] + c[2][1]) / 3.0,
        );
        w = w.max(dist(
            [0, 1, 2].map(|q| (x[0][q] + x[1][q] + x[2][q]) / 3.0),
            g,
        ));
    }
    w
}

#[test]
fn every_triangle_meets_the_tolerance() {
    for (name, e) in [
        ("catmark_edgeonly", 1e-3f32),
        ("catmark_tent", 1e-3),
        ("catmark_flap", 1e-3),
        ("catmark_square_hedit0", 1e-3),
        ("catmark_cube_creases0", 1e-3),
        ("catmark_fvar_bound0", 1e-3),
        // A corner of three creases of sharpness 5: the miss stays flat until the rates
        // pass the bend's width (about 2^-5 of a face), so a flat miss doubles the rates.
        ("catmark_cube_creases1", 3e-3),
    ] {
        let mesh = load_shape(name);
        let t = Topology::new(&mesh).unwrap();
        let diag = f64::from(bbox_diagonal(&mesh.positions));
        let policy = RatePolicy::Tolerance(e);
        let (s, chords) =
            adaptive_surface(&t, &mesh.positions, &policy, "tolerance", &isolated(4)).unwrap();
        let RatePolicy::Tolerance(budget) = chords else {
            panic!("{chords:?}")
        };
        let budget = f64::from(budget) * diag;
        let own = |ptex: u32, u: f32, v: f32| {
            s.eval_position(ptex as usize, u, v).unwrap().map(f64::from)
        };

        // The rate curves' estimate alone (the plan before the check) misses the budget.
        let rates = chords.rates(&s, "tolerance").unwrap();
        let p = plan(s.table(), &rates, "").unwrap();
        let before = worst(
            &p.triangles,
            &p.triangle_uv,
            &|n, k| {
                let c = p.triangle_uv[n].1[k];
                own(p.triangle_uv[n].0, c[0], c[1])
            },
            &own,
        );
        // `chord_errors` reads the same.
        let per_face = chord_errors(&s, &p, &s.table().ptex_base_faces(), None);
        let most = per_face.iter().copied().fold(0.0, f64::max);
        assert!(
            (most - before).abs() <= 1e-6 * diag,
            "{name}: {most:e} vs {before:e}"
        );

        let a = tessellate_adaptive(&s, &chords, "tolerance", &Cpu).unwrap();
        let (tris, uv) = (&a.tessellation.triangles, &a.triangle_uv);
        // Chords against the surface drawn, each triangle's corners from its own ptex face.
        let after = worst(
            tris,
            uv,
            &|n, k| {
                let c = uv[n].1[k];
                own(uv[n].0, c[0], c[1])
            },
            &own,
        );
        // The promise: output positions against the true limit surface.
        let o10 = PatchTable::build_real(&t, &isolated(10)).unwrap();
        let reference = LimitSurface::<f64>::new(o10, &mesh.positions);
        let truth = |ptex: u32, u: f32, v: f32| {
            reference
                .eval_position(ptex as usize, f64::from(u), f64::from(v))
                .unwrap()
        };
        let whole = worst(
            tris,
            uv,
            &|n, k| a.tessellation.positions[tris[n][k] as usize].map(f64::from),
            &truth,
        ) / diag;
        eprintln!(
            "{name}: chords {:.2e} -> {:.2e} of the budget {:.2e} ({} -> {} triangles), \
             whole {whole:.2e}",
            before / diag,
            after / diag,
            budget / diag,
            p.triangles.len(),
            tris.len()
        );
        assert!(before > budget, "{name}: {before:e} <= {budget:e}");
        assert!(after <= budget, "{name}: {after:e} > {budget:e}");
        assert!(whole <= f64::from(e), "{name}: {whole:e}");
    }
}
