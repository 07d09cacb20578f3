//! Bad input gives typed errors or `None`, never a panic.

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::shapes::{cube, pole};
use subsurf::{Error, Scheme, Topology};

#[test]
fn unsupported_options_are_errors() {
    let mut m = cube();
    let t = Topology::new(&m).unwrap();
    let o = PatchOptions {
        isolation_level: 11,
        ..Default::default()
    };
    assert!(matches!(
        PatchTable::build(&t, &o),
        Err(Error::Unsupported(_))
    ));
    m.options.scheme = Scheme::Bilinear;
    let t = Topology::new(&m).unwrap();
    assert!(matches!(
        PatchTable::build(&t, &PatchOptions::default()),
        Err(Error::Unsupported(_))
    ));
}

#[test]
fn queries_outside_the_surface_are_none() {
    let m = pole(5);
    let t = Topology::new(&m).unwrap();
    let s = LimitSurface::new(
        PatchTable::build(&t, &PatchOptions::default()).unwrap(),
        &m.positions,
    );
    assert!(s.eval(5, 0.5, 0.5).is_none());
    assert!(s.eval(usize::MAX, 0.5, 0.5).is_none());
    // Parameters are clamped to the face.
    assert_eq!(s.eval(0, -3.0, 2.0), s.eval(0, 0.0, 1.0));
    assert!(s.eval(0, f32::NAN, 0.5).is_none());
    assert!(s.tessellate(1).is_err() && s.tessellate(5000).is_err());
}
