//! glTF reader: subsurf's own `.glb` files read back identically, files from other writers
//! (trimesh, pygltflib: `gltf_gen.py`) read into the cage and transforms they describe, and
//! malformed files give typed errors, never panics.
//!
//! The other-writer test needs `python3` with numpy, trimesh and pygltflib: it fails when
//! `CI=true` and they are missing, and is skipped with a loud message otherwise.

mod common;

use serde_json::Value;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use subsurf::io::gltf::{self as gltf_read, ReadOptions};
use subsurf::io::{gltf as glb, obj};
use subsurf::{Error, Mesh};

const FLAT: ReadOptions = ReadOptions { flatten: true };
const KEEP: ReadOptions = ReadOptions { flatten: false };

/// Per-corner positions and UVs of a mesh's triangles (faces fanned, holes left out, faces
/// with two corners at one position dropped), as the writer emits them.
fn corners(mesh: &Mesh) -> Vec<([f32; 3], Option<[f32; 2]>)> {
    let mut out = vec![];
    let mut start = 0;
    for (f, &n) in mesh.face_counts.iter().enumerate() {
        let c: Vec<usize> = (start..start + n as usize).collect();
        start += n as usize;
        if mesh.holes.contains(&(f as u32)) {
            continue;
        }
        for k in 1..c.len() - 1 {
            let tri = [c[0], c[k], c[k + 1]];
            let p = tri.map(|i| mesh.positions[mesh.face_indices[i] as usize]);
            if p[0] == p[1] || p[1] == p[2] || p[0] == p[2] {
                continue;
            }
            for (i, q) in tri.into_iter().zip(p) {
                let uv = mesh.uvs.as_ref().map(|u| u.values[u.indices[i] as usize]);
                out.push((q, uv));
            }
        }
    }
    out
}

/// Undirected edges with their face counts; panics unless every edge has exactly two faces
/// that use it in opposite directions. Returns the number of edges.
fn closed_oriented_edges(mesh: &Mesh) -> usize {
    let mut directed = HashSet::new();
    let mut start = 0;
    for &n in &mesh.face_counts {
        let f = &mesh.face_indices[start..start + n as usize];
        start += n as usize;
        for k in 0..f.len() {
            let e = (f[k], f[(k + 1) % f.len()]);
            assert!(directed.insert(e), "directed edge {e:?} used twice");
        }
    }
    for &(a, b) in &directed {
        assert!(directed.contains(&(b, a)), "edge ({a}, {b}) is a boundary");
    }
    directed.len() / 2
}

#[test]
fn subsurf_glb_reads_back_identically() {
    let mut checked = 0;
    for row in common::index() {
        let name = row.get("name");
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        let mut bytes = vec![];
        if glb::write(&mesh, None, &mut bytes).is_err() {
            continue; // Only holes: nothing to write.
        }
        let back = gltf_read::read(&bytes, None, &KEEP).unwrap_or_else(|e| panic!("{name}: {e}"));
        let back_mesh = back.mesh;
        assert!(back_mesh.face_counts.iter().all(|&n| n == 3), "{name}");
        let (want, got) = (corners(&mesh), corners(&back_mesh));
        assert_eq!(want.len(), got.len(), "{name}");
        for (k, (w, g)) in want.iter().zip(&got).enumerate() {
            assert_eq!(w.0, g.0, "{name}: corner {k} position");
            assert_eq!(w.1.is_some(), g.1.is_some(), "{name}: corner {k} UV");
            if let (Some(a), Some(b)) = (w.1, g.1) {
                // The writer stores 1 - v: one f32 rounding each way.
                let tol = 2.0 * f32::EPSILON * a[1].abs().max(1.0);
                assert!(
                    a[0] == b[0] && (a[1] - b[1]).abs() <= tol,
                    "{name}: corner {k} UV {a:?} read back as {b:?}"
                );
            }
        }
        // Welded: one vertex per distinct position used by a face.
        let used: HashSet<[u32; 3]> = want.iter().map(|c| c.0.map(f32::to_bits)).collect();
        assert_eq!(back_mesh.positions.len(), used.len(), "{name}");
        // Without UVs, positions keep their order when all are used and distinct.
        if mesh.uvs.is_none() && used.len() == mesh.positions.len() {
            assert_eq!(*back_mesh.positions, *mesh.positions, "{name}");
        }
        checked += 1;
    }
    assert!(checked > 20, "only {checked} shapes checked");
}

#[test]
fn read_path_and_read_from_know_glb_and_gltf() {
    let mut mesh = obj::read_file(common::shape_path("catmark_cube")).unwrap();
    mesh.uvs = None;
    let dir = std::env::temp_dir().join(format!("subsurf-gltf-read-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube.glb");
    subsurf::io::write_path(&path, &mesh, None).unwrap();
    let back = subsurf::io::read_path(&path).unwrap();
    assert_eq!(*back.positions, *mesh.positions);
    assert_eq!(back.face_indices.len(), 36);
    let bytes = std::fs::read(&path).unwrap();
    let from = subsurf::io::read_from(&bytes[..], subsurf::io::Format::Glb).unwrap();
    assert_eq!(from, back);
    // .gltf is read, never written (and no empty file is left behind).
    let gltf = dir.join("cube.gltf");
    assert!(matches!(
        subsurf::io::write_path(&gltf, &mesh, None),
        Err(Error::Unsupported(_))
    ));
    assert!(!gltf.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

fn python_with(modules: &str) -> bool {
    let ok = std::process::Command::new("python3")
        .args(["-c", &format!("import {modules}")])
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    if !ok {
        let msg = format!("io_gltf_read: python3 with {modules} is not available");
        if std::env::var("CI").as_deref() == Ok("true") {
            panic!("{msg} (required when CI=true)");
        }
        eprintln!(
            "\n*** SKIPPED: {msg}; pip install trimesh pygltflib numpy to run this check ***\n"
        );
    }
    ok
}

/// `(position, uv)` per corner, rounded, with each triangle rotated to start at its smallest
/// corner (orientation kept), triangles sorted.
fn canonical(pos: &[[f64; 3]], uvs: Option<&[[f64; 2]]>) -> Vec<Vec<i64>> {
    let key = |i: usize| {
        let mut k: Vec<i64> = pos[i].iter().map(|x| (x * 1e4).round() as i64).collect();
        if let Some(uv) = uvs {
            k.extend(uv[i].iter().map(|x| (x * 1e4).round() as i64));
        }
        k
    };
    let mut tris: Vec<Vec<i64>> = (0..pos.len() / 3)
        .map(|t| {
            let c: Vec<Vec<i64>> = (0..3).map(|k| key(3 * t + k)).collect();
            let s = (0..3).min_by_key(|&k| c[k].clone()).unwrap();
            (0..3).flat_map(|k| c[(s + k) % 3].clone()).collect()
        })
        .collect();
    tris.sort();
    tris
}

fn mesh_corners(mesh: &Mesh) -> (Vec<[f64; 3]>, Option<Vec<[f64; 2]>>) {
    let pos = mesh
        .face_indices
        .iter()
        .map(|&v| mesh.positions[v as usize].map(f64::from))
        .collect();
    let uv = mesh.uvs.as_ref().map(|u| {
        u.indices
            .iter()
            .map(|&i| u.values[i as usize].map(f64::from))
            .collect()
    });
    (pos, uv)
}

fn json_rows<const N: usize>(v: &Value) -> Vec<[f64; N]> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let a = r.as_array().unwrap();
            std::array::from_fn(|k| a[k].as_f64().unwrap())
        })
        .collect()
}

#[test]
fn files_from_trimesh_and_pygltflib_read_correctly() {
    if !python_with("numpy, trimesh, pygltflib") {
        return;
    }
    let dir = std::env::temp_dir().join(format!("subsurf-gltf-gen-{}", std::process::id()));
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gltf_gen.py");
    let st = std::process::Command::new("python3")
        .arg(&script)
        .arg(&dir)
        .status()
        .unwrap();
    assert!(st.success(), "gltf_gen.py failed");
    let expected: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let expected = expected.as_object().unwrap();
    assert_eq!(expected.len(), 5);
    for (name, want) in expected {
        let read =
            gltf_read::read_file(dir.join(name), &FLAT).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mesh = &read.mesh;
        let wpos = json_rows::<3>(&want["positions"]);
        let wuv = want.get("uvs").map(json_rows::<2>);
        let (gpos, guv) = mesh_corners(mesh);
        assert_eq!(wuv.is_some(), guv.is_some(), "{name}: UVs");
        assert_eq!(
            canonical(&wpos, wuv.as_deref()),
            canonical(&gpos, guv.as_deref()),
            "{name}: triangles (positions, UVs) differ"
        );
        // Welded into closed, consistently oriented cubes: chi = V - E + F = 2 per cube.
        let cubes = wpos.len() / 36;
        let e = closed_oriented_edges(mesh);
        assert_eq!(mesh.positions.len(), 8 * cubes, "{name}: welded vertices");
        let chi = mesh.positions.len() as i64 - e as i64 + mesh.face_counts.len() as i64;
        assert_eq!(chi, 2 * cubes as i64, "{name}: Euler characteristic");
        // The UV seams stay: a cube with one chart per face has 24 UV values.
        if let Some(uv) = &mesh.uvs {
            assert_eq!(uv.values.len(), 24, "{name}: UV values");
        }
        // The points primitive of the pygltflib file is skipped with a note.
        if name.starts_with("pg_") {
            assert!(
                read.notes.iter().any(|n| n.contains("points")),
                "{name}: {:?}",
                read.notes
            );
        }
    }
    // Kept transforms: one mesh, read in its own coordinates.
    let kept = gltf_read::read_file(dir.join("pg_cube.glb"), &KEEP).unwrap();
    assert!(
        kept.notes.iter().any(|n| n.contains("not applied")),
        "{:?}",
        kept.notes
    );
    let local = json_rows::<3>(&expected["pg_cube.glb"]["local"]);
    assert_eq!(
        canonical(&local, None),
        canonical(&mesh_corners(&kept.mesh).0, None)
    );
    // Several meshes under different transforms cannot be kept: the error asks for flatten.
    match gltf_read::read_file(dir.join("tm_scene.glb"), &KEEP) {
        Err(Error::Unsupported(m)) => assert!(m.contains("flatten"), "{m}"),
        other => panic!("tm_scene.glb kept: {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A GLB file from a JSON document and a BIN chunk.
fn glb_from(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let total = (28 + j.len() + b.len()) as u32;
    let mut out = b"glTF".to_vec();
    for x in [2, total, j.len() as u32, 0x4E4F_534A] {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&j);
    for x in [b.len() as u32, 0x004E_4942] {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&b);
    out
}

/// subsurf's cube with UVs as GLB, split into JSON and BIN.
fn cube_parts() -> (Vec<u8>, Value, Vec<u8>) {
    let mesh = obj::read_file(common::shape_path("bilinear_cube")).unwrap();
    assert!(mesh.uvs.is_some());
    let mut bytes = vec![];
    glb::write(&mesh, None, &mut bytes).unwrap();
    let jl = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&bytes[20..20 + jl]).unwrap();
    let bin = bytes[28 + jl..].to_vec();
    (bytes, json, bin)
}

fn gltf_err(bytes: &[u8]) -> (String, String) {
    match gltf_read::read(bytes, None, &FLAT) {
        Err(Error::Gltf { location, reason }) => (location, reason),
        other => panic!("expected a glTF error, got {other:?}"),
    }
}

#[test]
fn malformed_files_give_typed_errors() {
    let (bytes, json, bin) = cube_parts();
    assert!(gltf_read::read(&glb_from(&json, &bin), None, &FLAT).is_ok());
    // Truncated: the header's length is past the end.
    let (loc, _) = gltf_err(&bytes[..bytes.len() - 1]);
    assert_eq!(loc, "GLB header");
    // A bad accessor offset.
    let mut j = json.clone();
    j["accessors"][0]["byteOffset"] = 1_000_000.into();
    let (loc, reason) = gltf_err(&glb_from(&j, &bin));
    assert!(
        loc.contains("primitives[0]") && loc.contains("accessors[0]"),
        "{loc}: {reason}"
    );
    // A buffer view past its buffer.
    let mut j = json.clone();
    j["bufferViews"][1]["byteLength"] = 1_000_000.into();
    let (loc, _) = gltf_err(&glb_from(&j, &bin));
    assert!(loc.contains("bufferViews[1]"), "{loc}");
    // An index out of range.
    let ia = json["meshes"][0]["primitives"][0]["indices"]
        .as_u64()
        .unwrap() as usize;
    let view = json["accessors"][ia]["bufferView"].as_u64().unwrap() as usize;
    let off = json["bufferViews"][view]["byteOffset"].as_u64().unwrap() as usize;
    let mut b = bin.clone();
    b[off..off + 4].copy_from_slice(&9999u32.to_le_bytes());
    let (loc, reason) = gltf_err(&glb_from(&json, &b));
    assert!(
        loc.contains("primitives[0]") && reason.contains("9999"),
        "{loc}: {reason}"
    );
    // Wrong component types: positions as shorts, indices as floats.
    let mut j = json.clone();
    j["accessors"][0]["componentType"] = 5123.into();
    let (loc, reason) = gltf_err(&glb_from(&j, &bin));
    assert!(
        loc.contains("accessors[0]") && reason.contains("componentType"),
        "{loc}: {reason}"
    );
    let mut j = json.clone();
    j["accessors"][ia]["componentType"] = 5126.into();
    let (loc, _) = gltf_err(&glb_from(&j, &bin));
    assert!(loc.contains(&format!("accessors[{ia}]")), "{loc}");
    // Wrong type, unknown mode, a node cycle, a required extension.
    let mut j = json.clone();
    j["accessors"][0]["type"] = "VEC2".into();
    gltf_err(&glb_from(&j, &bin));
    let mut j = json.clone();
    j["meshes"][0]["primitives"][0]["mode"] = 9.into();
    let (loc, _) = gltf_err(&glb_from(&j, &bin));
    assert_eq!(loc, "meshes[0].primitives[0]");
    let mut j = json.clone();
    j["nodes"][0]["children"] = serde_json::json!([0]);
    let (loc, _) = gltf_err(&glb_from(&j, &bin));
    assert_eq!(loc, "nodes[0]");
    let mut j = json.clone();
    j["extensionsRequired"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    assert!(matches!(
        gltf_read::read(&glb_from(&j, &bin), None, &FLAT),
        Err(Error::Unsupported(m)) if m.contains("draco")
    ));
    // An external buffer without a folder to read it from.
    let mut j = json.clone();
    j["buffers"][0]["uri"] = "cube.bin".into();
    let (loc, _) = gltf_err(&glb_from(&j, &bin));
    assert_eq!(loc, "buffers[0]");
}

#[test]
fn truncations_and_bit_flips_never_panic() {
    let (bytes, _, _) = cube_parts();
    let mut outcomes: HashMap<bool, usize> = HashMap::new();
    for n in 0..bytes.len() {
        let r = gltf_read::read(&bytes[..n], None, &FLAT);
        *outcomes.entry(r.is_ok()).or_default() += 1;
    }
    assert_eq!(outcomes.get(&true), None, "a truncated file was accepted");
    let mut ok = 0;
    for i in 0..bytes.len() {
        for bit in [0, 3, 7] {
            let mut b = bytes.clone();
            b[i] ^= 1 << bit;
            if let Ok(r) = gltf_read::read(&b, None, &FLAT) {
                // Whatever is accepted is a mesh with in-range indices.
                let n = r.mesh.positions.len() as u32;
                assert!(r.mesh.face_indices.iter().all(|&v| v < n));
                ok += 1;
            }
        }
    }
    // Flips in float data and JSON whitespace are harmless; most header flips are not.
    assert!(
        ok > 0 && ok < 3 * bytes.len(),
        "{ok} flipped files accepted"
    );
}

#[test]
fn sparse_accessors_substitute_their_values() {
    let (_, mut json, mut bin) = cube_parts();
    let base = bin.len();
    bin.extend_from_slice(&[0, 0, 0, 0]); // u8 index 0, padded.
    for x in [5.0f32, 6.0, 7.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    let views = json["bufferViews"].as_array_mut().unwrap();
    views.push(serde_json::json!({"buffer": 0, "byteOffset": base, "byteLength": 1}));
    views.push(serde_json::json!({"buffer": 0, "byteOffset": base + 4, "byteLength": 12}));
    let (iv, vv) = (views.len() - 2, views.len() - 1);
    json["buffers"][0]["byteLength"] = bin.len().into();
    json["accessors"][0]["sparse"] = serde_json::json!({
        "count": 1,
        "indices": {"bufferView": iv, "componentType": 5121},
        "values": {"bufferView": vv}
    });
    let plain = gltf_read::read(&cube_parts().0, None, &KEEP).unwrap().mesh;
    let sparse = gltf_read::read(&glb_from(&json, &bin), None, &KEEP)
        .unwrap()
        .mesh;
    assert_eq!(sparse.face_indices.len(), plain.face_indices.len());
    assert!(sparse.positions.contains(&[5.0, 6.0, 7.0]));
    // Corner by corner (same triangles, same order), only glTF vertex 0's corners moved.
    let (a, b) = (mesh_corners(&plain).0, mesh_corners(&sparse).0);
    let moved: Vec<usize> = (0..a.len()).filter(|&k| a[k] != b[k]).collect();
    assert!(!moved.is_empty());
    for &k in &moved {
        assert_eq!(b[k], [5.0, 6.0, 7.0]);
        assert_eq!(a[k], a[moved[0]]);
    }
    // A sparse index past the accessor's count is an error.
    json["accessors"][0]["sparse"]["count"] = 1.into();
    bin[base] = 200;
    let (loc, _) = gltf_err(&glb_from(&json, &bin));
    assert!(loc.contains("sparse.indices"), "{loc}");
}
