//! Positions at the precision they were read: OBJ digits, PLY `double` properties and USD
//! `point3d[]` come back bit for bit after a write, `f32` files stay `f32`, and the
//! double-precision refinement reads the file's values, not their `f32` rounding.

mod common;

use subsurf::io::{self, usd::UsdFormat, Format, WriteOptions};
use subsurf::{Mesh, Positions};

/// A mesh whose coordinates need every bit of `f64`: the car's faces with positions that
/// are no `f32` value (a third of a unit apart, a million units from the origin).
fn wide_mesh() -> Mesh {
    let car = io::read_path(common::shape_path("catmark_car")).unwrap();
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let wide = car.positions.map(|p| {
        [
            1e6 + p[0] + next() / 3.0,
            -2.5e5 + p[1] + next() / 7.0,
            p[2] * std::f64::consts::PI + next() * 1e-9,
        ]
    });
    Mesh {
        positions: wide,
        ..car
    }
}

fn f64_bits(m: &Mesh) -> Vec<u64> {
    m.positions
        .to_f64()
        .iter()
        .flatten()
        .map(|x| x.to_bits())
        .collect()
}

fn write(mesh: &Mesh, format: Format, options: WriteOptions) -> Vec<u8> {
    let mut bytes = Vec::new();
    io::write_to_with(&mut bytes, format, mesh, None, options).unwrap();
    bytes
}

#[test]
fn f64_positions_round_trip_bit_for_bit_through_obj_ply_and_usd() {
    let mesh = wide_mesh();
    assert!(mesh.positions.is_f64());
    // The f32 rounding alone would move these points by up to 3e-2.
    let lost = mesh
        .positions
        .to_f64()
        .iter()
        .zip(mesh.positions.iter())
        .map(|(a, b)| {
            (0..3)
                .map(|k| (a[k] - b[k] as f64).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    assert!(lost > 1e-3, "{lost}");
    let f64_out = WriteOptions {
        f64: true,
        ..Default::default()
    };
    let formats = [
        (Format::Obj, WriteOptions::default()),
        (Format::Ply, WriteOptions::default()),
        (Format::Usd(UsdFormat::Usda), f64_out),
        (Format::Usd(UsdFormat::Usdc), f64_out),
        (Format::Usd(UsdFormat::Usdz), f64_out),
    ];
    for (format, options) in formats {
        let bytes = write(&mesh, format, options);
        let back = io::read_bytes(&bytes, format).unwrap();
        assert!(back.positions.is_f64(), "{format:?}");
        assert_eq!(f64_bits(&back), f64_bits(&mesh), "{format:?}");
        assert_eq!(back.face_indices, mesh.face_indices, "{format:?}");
    }
    // USD without the option writes the schema's point3f[]: the f32 rounding.
    let bytes = write(&mesh, Format::Usd(UsdFormat::Usdc), WriteOptions::default());
    let back = io::read_bytes(&bytes, Format::Usd(UsdFormat::Usdc)).unwrap();
    assert!(!back.positions.is_f64());
    assert_eq!(*back.positions, *mesh.positions);
}

#[test]
fn f32_files_stay_f32_and_obj_keeps_only_what_f32_cannot_hold() {
    // Every coordinate of the grid is an f32 value: nothing is kept in f64.
    let cube = io::obj::read("v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 -0.25\nf 1 2 3 4\n").unwrap();
    assert!(!cube.positions.is_f64());
    let ply = io::read_bytes(
        &write(&cube, Format::Ply, WriteOptions::default()),
        Format::Ply,
    );
    assert!(!ply.unwrap().positions.is_f64());
    // One digit more than f32 holds: kept in f64, the f32 values its rounding.
    let text = "v 0.1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.30000000000000004\nf 1 2 3 4\n";
    let m = io::obj::read(text).unwrap();
    assert_eq!(m.positions.as_f64().unwrap()[0][0], 0.1);
    assert_eq!(m.positions.as_f64().unwrap()[3][2], 0.30000000000000004);
    assert_eq!(m.positions[0][0], 0.1f32);
    let back = io::obj::read(
        std::str::from_utf8(&write(&m, Format::Obj, WriteOptions::default())).unwrap(),
    )
    .unwrap();
    assert_eq!(back.positions, m.positions);
    // A mesh given in f32 is written in f32 digits.
    let f32_mesh = Mesh {
        positions: Positions::from_f32(vec![[0.1, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]),
        face_counts: vec![3],
        face_indices: vec![0, 1, 2],
        ..Default::default()
    };
    let obj = String::from_utf8(write(&f32_mesh, Format::Obj, WriteOptions::default())).unwrap();
    assert!(obj.contains("v 0.1 0 0\n"), "{obj}");
}

/// `refine_mesh_f64` reads the file's values: on the wide mesh, the f32 path's rounding (up
/// to 3e-2 at a million units) is gone, and refining the f32 rounding instead differs.
#[test]
fn double_precision_refinement_reads_the_values_as_given() {
    let mesh = wide_mesh();
    let a = subsurf::surface::refine_mesh_f64(&mesh, 1, false, None).unwrap();
    assert!(a.positions.is_f64());
    let narrowed = Mesh {
        positions: mesh.positions.to_vec().into(),
        ..mesh.clone()
    };
    let b = subsurf::surface::refine_mesh_f64(&narrowed, 1, false, None).unwrap();
    let gap = a
        .positions
        .to_f64()
        .iter()
        .zip(b.positions.to_f64().iter())
        .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(gap > 1e-3, "{gap}");
}
