//! glTF binary export read back by the `gltf` crate: counts, bounds, normals, UVs, indices.

mod common;

use subsurf::io::{gltf as glb, obj};
use subsurf::Mesh;

fn read_back(bytes: &[u8]) -> (gltf::Gltf, Vec<u8>) {
    let g = gltf::Gltf::from_slice(bytes).expect("gltf crate accepts the file");
    let blob = g.blob.clone().expect("BIN chunk");
    (g, blob)
}

/// Number of triangles a fan triangulation of the non-hole faces gives.
fn triangles(mesh: &Mesh) -> usize {
    mesh.face_counts
        .iter()
        .enumerate()
        .filter(|(f, _)| !mesh.holes.contains(&(*f as u32)))
        .map(|(_, &n)| n as usize - 2)
        .sum()
}

#[test]
fn every_shape_reads_back_with_counts_and_bounds() {
    for row in common::index() {
        let name = row.get("name");
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        if mesh.face_counts.len() == mesh.holes.len() {
            continue;
        }
        let mut bytes = vec![];
        glb::write(&mesh, None, &mut bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (g, blob) = read_back(&bytes);
        let gmesh = g.meshes().next().expect("one mesh");
        let prim = gmesh.primitives().next().expect("one primitive");
        assert_eq!(prim.mode(), gltf::mesh::Mode::Triangles);
        let reader = prim.reader(|_| Some(&blob[..]));
        let pos: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert_eq!(idx.len(), 3 * triangles(&mesh), "{name}");
        assert!(idx.iter().all(|&i| (i as usize) < pos.len()), "{name}");
        // Every emitted vertex is one of the mesh's positions; without UVs, exactly them.
        if mesh.uvs.is_none() {
            assert_eq!(pos, mesh.positions, "{name}");
        } else {
            let known: std::collections::HashSet<[u32; 3]> =
                mesh.positions.iter().map(|p| p.map(f32::to_bits)).collect();
            assert!(
                pos.iter().all(|p| known.contains(&p.map(f32::to_bits))),
                "{name}"
            );
        }
        // The accessor's bounds are the exact bounds of the data.
        let acc = prim.get(&gltf::Semantic::Positions).unwrap();
        let (lo, hi) = (acc.min().unwrap(), acc.max().unwrap());
        let (blo, bhi) = subsurf::mesh::bounding_box(&pos).unwrap();
        for k in 0..3 {
            assert_eq!(lo[k].as_f64().unwrap() as f32, blo[k], "{name}");
            assert_eq!(hi[k].as_f64().unwrap() as f32, bhi[k], "{name}");
        }
        // Triangles follow the faces: the first triangle is the first face's first three
        // corners (when the first face is not a hole).
        if !mesh.holes.contains(&0) && mesh.uvs.is_none() {
            assert_eq!(idx[..3], mesh.face_indices[..3], "{name}");
        }
    }
}

#[test]
fn normals_and_uvs_are_attributes() {
    let mesh = obj::read_file(common::shape_path("bilinear_cube")).unwrap();
    let uv = mesh.uvs.clone().expect("shape with UVs");
    let normals: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt().max(1e-12);
            [p[0] / l, p[1] / l, p[2] / l]
        })
        .collect();
    let mut bytes = vec![];
    glb::write(&mesh, Some(&normals), &mut bytes).unwrap();
    let (g, blob) = read_back(&bytes);
    let prim = g.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|_| Some(&blob[..]));
    let pos: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let nrm: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
    let tex: Vec<[f32; 2]> = reader.read_tex_coords(0).unwrap().into_f32().collect();
    let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!((nrm.len(), tex.len()), (pos.len(), pos.len()));
    // Walk the faces: each corner's emitted vertex carries that corner's position, normal
    // and (flipped) UV.
    let mut t = 0;
    let mut start = 0;
    for (f, &n) in mesh.face_counts.iter().enumerate() {
        let n = n as usize;
        if !mesh.holes.contains(&(f as u32)) {
            for k in 1..n - 1 {
                for (j, c) in [0, k, k + 1].into_iter().enumerate() {
                    let e = idx[3 * t + j] as usize;
                    let v = mesh.face_indices[start + c] as usize;
                    let w = uv.values[uv.indices[start + c] as usize];
                    assert_eq!(pos[e], mesh.positions[v]);
                    assert_eq!(nrm[e], normals[v]);
                    assert_eq!(tex[e], [w[0], 1.0 - w[1]]);
                }
                t += 1;
            }
        }
        start += n;
    }
    assert_eq!(3 * t, idx.len());
}

#[test]
fn write_path_picks_glb_by_extension() {
    let dir = std::env::temp_dir().join(format!("subsurf-gltf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube.GLB");
    let mesh = subsurf::shapes::cube();
    subsurf::io::write_path(&path, &mesh, None).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let (g, _) = read_back(&bytes);
    assert_eq!(g.meshes().count(), 1);
    // And reads back (tests/io_gltf_read.rs checks the reader in depth).
    assert_eq!(
        subsurf::io::read_path(&path).unwrap().positions,
        mesh.positions
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
