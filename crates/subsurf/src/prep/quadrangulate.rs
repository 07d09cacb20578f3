//! One plain polygon split: every n-gon becomes n quads through its centroid and its edge
//! midpoints (the topology of one Catmull-Clark step, with plain averages as positions).
//! The p-rep needs quads only; this makes any closed polygon mesh acceptable.

use std::collections::HashMap;

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;

/// Splits every face of `mesh` into quads `(v_i, mid(v_i, v_{i+1}), centroid, mid(v_{i-1}, v_i))`.
/// Orientation is preserved. Tags, UVs and holes are dropped.
pub fn quadrangulate(mesh: &Mesh) -> Result<Mesh> {
    let nv = mesh.num_vertices();
    let mut positions = mesh.positions.clone();
    let mut mids: HashMap<(u32, u32), u32> = HashMap::new();
    let mut faces: Vec<[u32; 4]> = Vec::new();
    let mut o = 0usize;
    for (f, &cnt) in mesh.face_counts.iter().enumerate() {
        let cnt = cnt as usize;
        let Some(fv) = mesh.face_indices.get(o..o + cnt) else {
            return Err(MeshError::FaceIndexCountMismatch {
                expected: o + cnt,
                found: mesh.face_indices.len(),
            }
            .into());
        };
        o += cnt;
        if cnt < 3 {
            return Err(MeshError::FaceTooSmall {
                face: f,
                count: cnt as u32,
            }
            .into());
        }
        if let Some((corner, &index)) = fv.iter().enumerate().find(|(_, &v)| v as usize >= nv) {
            return Err(MeshError::VertexIndexOutOfRange {
                face: f,
                corner,
                index,
                count: nv,
            }
            .into());
        }
        let mut c = [0f64; 3];
        for &v in fv {
            for k in 0..3 {
                c[k] += mesh.positions[v as usize][k] as f64;
            }
        }
        let centre = positions.len() as u32;
        positions.push(c.map(|x| (x / cnt as f64) as f32));
        let mut mid = |a: u32, b: u32| -> u32 {
            let key = (a.min(b), a.max(b));
            *mids.entry(key).or_insert_with(|| {
                let (p, q) = (mesh.positions[a as usize], mesh.positions[b as usize]);
                positions.push([0, 1, 2].map(|k| 0.5 * (p[k] + q[k])));
                (positions.len() - 1) as u32
            })
        };
        let m: Vec<u32> = (0..cnt).map(|i| mid(fv[i], fv[(i + 1) % cnt])).collect();
        for i in 0..cnt {
            faces.push([fv[i], m[i], centre, m[(i + cnt - 1) % cnt]]);
        }
    }
    let mut out = Mesh::from_faces(positions, &faces);
    out.options = mesh.options;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed triangle mesh (tetrahedron) becomes a closed quad mesh with V + E + F
    /// vertices and 3F quads, acceptable to the p-rep.
    #[test]
    fn tetrahedron_becomes_closed_quads() {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let m = Mesh::from_faces(p, &[[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]);
        let q = quadrangulate(&m).unwrap();
        assert_eq!(q.num_vertices(), 4 + 6 + 4);
        assert_eq!(q.num_faces(), 12);
        let t = crate::topology::Topology::new(&q).unwrap();
        assert!(crate::prep::check_input(&t).is_ok());
    }
}
