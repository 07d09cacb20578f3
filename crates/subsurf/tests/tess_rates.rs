//! Rate policies: what each promises, measured on the tessellation it makes, and bad input
//! refused with a typed error naming the value and its origin.

mod limit_common;

use limit_common::{bbox_diagonal, isolated, load_shape};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{
    parse_edge_rates, DeviationOptions, DeviationReference, RatePolicy, ScreenCamera,
};
use subsurf::{Error, TessError, Topology};

fn surface(name: &str) -> LimitSurface {
    let mesh = load_shape(name);
    let t = Topology::new(&mesh).unwrap();
    let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
    LimitSurface::new(table, &mesh.positions)
}

fn dist(a: [f32; 3], b: [f32; 3]) -> f64 {
    (0..3)
        .map(|k| f64::from(a[k] - b[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// `--tolerance E` end to end, as `subsurf limit --tolerance` runs it (isolation chosen per
/// region, rates from the rate curves, every triangle checked): the two-sided geometric
/// deviation of the tessellation from the true limit surface (isolation 10, `f64`) lies
/// between `E/2` and `E`, so the triangles spent buy what was asked and not much more.
#[test]
fn tolerance_reaches_between_half_and_all_of_it() {
    for name in ["catmark_torus", "catmark_pawn"] {
        let mesh = load_shape(name);
        let t = Topology::new(&mesh).unwrap();
        let exact = LimitSurface::<f64>::new(
            PatchTable::build_real(&t, &isolated(10)).unwrap(),
            &mesh.positions,
        );
        let reference = DeviationReference::new(&exact, &DeviationOptions::default());
        for e in [3e-3f32, 1e-3] {
            let policy = RatePolicy::Tolerance(e);
            let (s, chords) = adaptive_surface(
                &t,
                &mesh.positions,
                &policy,
                "--tolerance",
                &PatchOptions::default(),
            )
            .unwrap();
            let a = tessellate_adaptive(&s, &chords, "--tolerance", &Cpu).unwrap();
            let out = &a.tessellation;
            let d = reference.measure(&out.positions, &out.triangles, Some(&a.triangle_uv));
            let reached = d.hausdorff() / f64::from(e);
            eprintln!(
                "{name} E={e}: {} triangles, reached {reached:.2} of E (mesh {:.2e}, surface \
                 {:.2e})",
                out.triangles.len(),
                d.mesh_to_surface,
                d.surface_to_mesh
            );
            assert!((0.5..=1.0).contains(&reached), "{name} E={e}: {d:?}");
        }
    }
}

fn longest_edge(
    out: &subsurf::tess::AdaptiveTessellation,
    map: impl Fn([f32; 3]) -> [f32; 3],
) -> f64 {
    out.triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| {
            dist(
                map(out.positions[a as usize]),
                map(out.positions[b as usize]),
            )
        })
        .fold(0.0, f64::max)
}

/// `--max-edge-length L` and `--pixels P`: no output edge longer than `L` world units, or
/// than `P` pixels under the camera.
#[test]
fn length_policies_bound_every_edge() {
    let s = surface("catmark_pawn");
    let diag = bbox_diagonal(s.points());
    let l = diag / 40.0;
    let out = s
        .tessellate_rates(
            &RatePolicy::MaxEdgeLength(l)
                .rates(&s, "--max-edge-length")
                .unwrap(),
            "",
        )
        .unwrap();
    let longest = longest_edge(&out, |p| p);
    eprintln!(
        "max edge length {l}: longest {longest}, {} triangles",
        out.triangles.len()
    );
    assert!(longest <= f64::from(l), "{longest} > {l}");

    // A camera on +z looking at the origin (an orthographic-like matrix with w = 1).
    let k = 2.0 / diag;
    let camera = ScreenCamera {
        view_proj: [
            [k, 0.0, 0.0, 0.0],
            [0.0, k, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.5, 1.0],
        ],
        width: 800,
        height: 800,
    };
    let pixels = 6.0;
    let policy = RatePolicy::screen(Some(camera), pixels, "--pixels").unwrap();
    let out = s
        .tessellate_rates(&policy.rates(&s, "--pixels").unwrap(), "")
        .unwrap();
    let longest = longest_edge(&out, |p| {
        let q = camera.project(p).unwrap();
        [q[0], q[1], 0.0]
    });
    eprintln!(
        "{pixels} pixels: longest {longest}, {} triangles",
        out.triangles.len()
    );
    assert!(longest <= f64::from(pixels), "{longest} > {pixels}");
}

/// Each bad value is refused before any work with a typed error naming it and its origin.
#[test]
fn bad_rates_and_values_are_typed_errors() {
    let s = surface("catmark_cube");
    let t = &s.table().base();
    #[track_caller]
    fn err(r: subsurf::Result<()>) -> TessError {
        match r {
            Err(Error::Tess(e)) => e,
            other => panic!("expected a TessError, got {other:?}"),
        }
    }
    for bad in [0u32, 4097] {
        let e = err(RatePolicy::Uniform(bad).rates(&s, "--tess").map(|_| ()));
        assert!(matches!(e, TessError::RateOutOfRange { rate, .. } if rate == u64::from(bad)));
        assert!(e.to_string().starts_with("--tess: rate"), "{e}");
    }
    for bad in [0.0f32, -1.0, f32::NAN, f32::INFINITY] {
        let e = err(RatePolicy::Tolerance(bad)
            .rates(&s, "--tolerance")
            .map(|_| ()));
        assert!(
            matches!(
                e,
                TessError::NotPositive {
                    what: "tolerance",
                    ..
                }
            ),
            "{e}"
        );
        let e = err(RatePolicy::MaxEdgeLength(bad)
            .rates(&s, "--max-edge-length")
            .map(|_| ()));
        assert!(matches!(e, TessError::NotPositive { .. }), "{e}");
    }
    let e = err(RatePolicy::screen(None, 4.0, "--pixels").map(|_| ()));
    assert!(matches!(e, TessError::NoCamera { .. }), "{e}");
    // A tolerance whose tessellation would not fit in memory is refused with the estimate
    // (rates of about 3 × 10⁵ on six faces: nearly 10¹² samples), before anything is built.
    match RatePolicy::Tolerance(1e-12).rates(&s, "--tolerance") {
        Err(Error::Mesh(e @ subsurf::MeshError::TooLarge { bytes, .. })) => {
            assert!(bytes > 10_000_000_000_000, "{e}");
            assert!(e.to_string().contains("would need about"), "{e}");
        }
        other => panic!("expected MeshError::TooLarge, got {other:?}"),
    }

    // Edge-rates files: file and line in every error.
    let ok = parse_edge_rates("# rates\n0 1 7\n\n1 3 2 # comment\n", "r.txt", t, 3).unwrap();
    let e01 = t.find_edge(0, 1).unwrap() as usize;
    assert_eq!(ok.edges[e01], 7);
    assert_eq!(
        ok.edges.iter().filter(|&&r| r == 3).count(),
        t.num_edges() - 2
    );
    let apart = (1..t.num_vertices() as u32)
        .find(|&v| t.find_edge(0, v).is_none())
        .unwrap();
    let not_an_edge = format!("0 1 7\n0 {apart} 2\n");
    for (text, line, want) in [
        (not_an_edge.as_str(), 2, "not joined by an edge"),
        ("0 1 7\n0 1\n", 2, "expected `v0 v1 rate`"),
        ("0 1 0\n", 1, "not in 1..=4096"),
        ("0 1 5000\n", 1, "not in 1..=4096"),
        ("0 x 2\n", 1, "not a non-negative integer"),
        ("0 99 2\n", 1, "not joined by an edge"),
    ] {
        let e = err(parse_edge_rates(text, "r.txt", t, 3).map(|_| ()));
        let msg = e.to_string();
        assert!(
            msg.starts_with(&format!("r.txt:{line}: ")) && msg.contains(want),
            "{msg}"
        );
    }
}

/// `--tolerance E` spends no more triangles than the coarsest uniform rate (planned on the
/// same surface) that comes as close to the true limit surface, two-sided: the rates the
/// curves overestimate (the pawn's and `lefthanded`'s thin rims, `pole64`'s fan) are lowered
/// where the check measures the triangles well inside the tolerance.
#[test]
fn tolerance_spends_no_more_than_the_uniform_rate_as_close() {
    for (name, e) in [
        ("catmark_pawn", 3e-3f32),
        ("catmark_pawn", 1e-3),
        ("catmark_lefthanded", 1e-3),
        ("catmark_pole64", 3e-3),
    ] {
        let mesh = load_shape(name);
        let t = Topology::new(&mesh).unwrap();
        let exact = LimitSurface::<f64>::new(
            PatchTable::build_real(&t, &isolated(10)).unwrap(),
            &mesh.positions,
        );
        let reference = DeviationReference::new(&exact, &DeviationOptions::default());
        let (s, chords) = adaptive_surface(
            &t,
            &mesh.positions,
            &RatePolicy::Tolerance(e),
            "--tolerance",
            &PatchOptions::default(),
        )
        .unwrap();
        let a = tessellate_adaptive(&s, &chords, "--tolerance", &Cpu).unwrap();
        let out = &a.tessellation;
        let reached = reference
            .measure(&out.positions, &out.triangles, Some(&a.triangle_uv))
            .hausdorff();
        let uniform = (1..=32u32)
            .find_map(|r| {
                let p =
                    subsurf::tess::plan(s.table(), &subsurf::tess::EdgeRates::uniform(&t, r), "")
                        .unwrap();
                let uv = p.triangle_uv.clone();
                let u = s.eval_plan(p);
                let d = reference.measure(&u.positions, &u.triangles, Some(&uv));
                (d.hausdorff() <= reached).then_some((r, u.triangles.len()))
            })
            .expect("a uniform rate as close");
        eprintln!(
            "{name} E={e}: {} triangles at {reached:.2e}, uniform rate {} as close: {} triangles",
            out.triangles.len(),
            uniform.0,
            uniform.1
        );
        assert!(
            out.triangles.len() <= uniform.1,
            "{name} E={e}: {} triangles, uniform rate {} {}",
            out.triangles.len(),
            uniform.0,
            uniform.1
        );
    }
}
