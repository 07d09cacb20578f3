//! Bad input gives typed errors or `None`, never a panic.

use subsurf::limit::patch_map::{PatchMap, EMPTY, LEAF};
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

/// The quadtree descends by quadrant: 0 (low u, low v), 1 (high u), 2 (both), 3 (high v).
#[test]
fn patch_map_quadrants() {
    let map = PatchMap {
        roots: vec![0, LEAF | 7, EMPTY],
        nodes: vec![
            [LEAF, LEAF | 1, 1, EMPTY],
            [LEAF | 2, LEAF | 3, LEAF | 4, LEAF | 5],
        ],
    };
    assert_eq!(map.find(0, 0.1, 0.2), Some(0));
    assert_eq!(map.find(0, 0.6, 0.2), Some(1));
    assert_eq!(map.find(0, 0.1, 0.9), None);
    assert_eq!(map.find(0, 0.6, 0.6), Some(2));
    assert_eq!(map.find(0, 0.8, 0.6), Some(3));
    assert_eq!(map.find(0, 0.8, 0.8), Some(4));
    assert_eq!(map.find(0, 0.6, 0.9), Some(5));
    assert_eq!(map.find(1, 0.3, 0.3), Some(7));
    assert_eq!(map.find(2, 0.3, 0.3), None);
    assert_eq!(map.find(3, 0.3, 0.3), None);
}
