//! Fan triangulation of polygons with smooth vertex normals.
//!
//! A vertex normal is the normalized sum of the unit normals of the incident faces; a face
//! normal is Newell's normal of the polygon (Newell 1972, as in Sutherland, Sproull and
//! Schumacker 1974), which is robust for non-planar quads.

/// Newell's normal of a polygon (twice its vector area).
pub fn newell(positions: &[[f32; 3]], poly: &[u32]) -> [f32; 3] {
    let mut n = [0.0f32; 3];
    for (k, &a) in poly.iter().enumerate() {
        let p = positions[a as usize];
        let q = positions[poly[(k + 1) % poly.len()] as usize];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}

/// `n` scaled to unit length; zero when `n` is zero or not finite.
pub fn unit(n: [f32; 3]) -> [f32; 3] {
    crate::util::vec3::unit(n, 0.0).unwrap_or([0.0; 3])
}

/// Triangles of polygons (fans from the first corner) with one class each.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fans {
    /// Smooth unit vertex normals (zero for vertices used by no polygon).
    pub normals: Vec<[f32; 3]>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// The class of each triangle (its polygon's).
    pub classes: Vec<u8>,
    /// For each triangle, the offsets of its corners in the polygons' corner list (the order
    /// of `faces`), to carry face-varying data along.
    pub corners: Vec<[u32; 3]>,
}

/// Triangulates polygons (fans from the first corner) and computes smooth vertex normals.
/// `faces` yields each polygon's vertex indices and its class; every index must be below
/// `positions.len()`.
pub fn triangulate<'a>(
    positions: &[[f32; 3]],
    faces: impl Iterator<Item = (&'a [u32], u8)>,
) -> Fans {
    let mut out = Fans {
        normals: vec![[0.0f32; 3]; positions.len()],
        ..Default::default()
    };
    let mut corner = 0u32;
    for (poly, c) in faces {
        let n = unit(newell(positions, poly));
        for &v in poly {
            let m = &mut out.normals[v as usize];
            m[0] += n[0];
            m[1] += n[1];
            m[2] += n[2];
        }
        for k in 1..poly.len().saturating_sub(1) {
            out.triangles.push([poly[0], poly[k], poly[k + 1]]);
            out.classes.push(c);
            let k = k as u32;
            out.corners.push([corner, corner + k, corner + k + 1]);
        }
        corner += poly.len() as u32;
    }
    for n in &mut out.normals {
        *n = unit(*n);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_normals_point_along_the_diagonals() {
        let mesh = crate::shapes::cube();
        let mut s = 0usize;
        let faces: Vec<(&[u32], u8)> = mesh
            .face_counts
            .iter()
            .map(|&n| {
                let r = &mesh.face_indices[s..s + n as usize];
                s += n as usize;
                (r, 0u8)
            })
            .collect();
        let f = triangulate(&mesh.positions, faces.into_iter());
        assert_eq!(f.triangles.len(), 6 * 2);
        assert_eq!(f.corners[1], [0, 2, 3]);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
        for (p, n) in mesh.positions.iter().zip(&f.normals) {
            // Three unit face normals summed: the outward corner diagonal.
            let d = unit([p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
            let dot = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            assert!(dot > 0.9999, "{p:?} {n:?}");
        }
    }
}
