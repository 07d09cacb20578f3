//! The input model: polygons, positions, optional face-varying UVs and sharpness tags.

use crate::options::Options;

/// A semi-sharp or infinitely sharp edge tag: the edge between `v0` and `v1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crease {
    /// First end vertex.
    pub v0: u32,
    /// Second end vertex.
    pub v1: u32,
    /// Sharpness: `>= 10` is infinite; negative values are clamped to 0 when topology is built.
    pub sharpness: f32,
}

/// A sharp vertex tag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// Vertex index.
    pub vertex: u32,
    /// Sharpness: `>= 10` is infinite.
    pub sharpness: f32,
}

/// Face-varying data (UVs) with its own index buffer, parallel to [`Mesh::face_indices`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FaceVarying {
    /// Distinct values.
    pub values: Vec<[f32; 2]>,
    /// One index into `values` per face corner (same length as `Mesh::face_indices`).
    pub indices: Vec<u32>,
}

/// A polygon mesh with tags, as read from a file. Nothing here is validated: build a
/// [`crate::topology::Topology`] to get a checked, connected model.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Number of vertices of each face (each >= 3 in a valid mesh).
    pub face_counts: Vec<u32>,
    /// Vertex indices of all faces, concatenated, counter-clockwise seen from outside.
    pub face_indices: Vec<u32>,
    /// Optional face-varying UVs.
    pub uvs: Option<FaceVarying>,
    /// Edge sharpness tags.
    pub creases: Vec<Crease>,
    /// Vertex sharpness tags.
    pub corners: Vec<Corner>,
    /// Faces tagged as holes (not emitted, yet they shape their neighbours).
    pub holes: Vec<u32>,
    /// Subdivision options.
    pub options: Options,
}

impl Mesh {
    /// Builds a mesh from positions and faces given as slices of indices.
    pub fn from_faces<F: AsRef<[u32]>>(positions: Vec<[f32; 3]>, faces: &[F]) -> Self {
        let mut face_counts = Vec::with_capacity(faces.len());
        let mut face_indices = Vec::new();
        for f in faces {
            face_counts.push(f.as_ref().len() as u32);
            face_indices.extend_from_slice(f.as_ref());
        }
        Mesh {
            positions,
            face_counts,
            face_indices,
            ..Default::default()
        }
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_counts.len()
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// One flag per face: whether it is tagged as a hole (indices past the last face are
    /// passed over).
    pub fn hole_mask(&self) -> Vec<bool> {
        let mut hole = vec![false; self.face_counts.len()];
        for &f in &self.holes {
            if let Some(h) = hole.get_mut(f as usize) {
                *h = true;
            }
        }
        hole
    }

    /// The mesh with its hole faces left out, as a viewer that ignores hole tags should see
    /// it: the other faces (and their UV indices) in their order, every vertex kept (so
    /// per-vertex normals still line up), creases and corners kept, no holes. Hole indices
    /// past the last face are passed over. The mesh itself when it has no holes.
    pub fn without_holes(&self) -> Mesh {
        if self.holes.is_empty() {
            return self.clone();
        }
        let hole = self.hole_mask();
        let mut face_counts = Vec::with_capacity(self.face_counts.len());
        let mut face_indices = Vec::with_capacity(self.face_indices.len());
        let mut uv_indices = self.uvs.as_ref().map(|_| Vec::new());
        let mut start = 0usize;
        for (f, &n) in self.face_counts.iter().enumerate() {
            let end = (start + n as usize).min(self.face_indices.len());
            if !hole[f] {
                face_counts.push(n);
                face_indices.extend_from_slice(&self.face_indices[start.min(end)..end]);
                if let (Some(out), Some(uv)) = (uv_indices.as_mut(), self.uvs.as_ref()) {
                    let e = end.min(uv.indices.len());
                    out.extend_from_slice(&uv.indices[start.min(e)..e]);
                }
            }
            start = end;
        }
        Mesh {
            positions: self.positions.clone(),
            face_counts,
            face_indices,
            uvs: self
                .uvs
                .as_ref()
                .zip(uv_indices)
                .map(|(uv, indices)| FaceVarying {
                    values: uv.values.clone(),
                    indices,
                }),
            creases: self.creases.clone(),
            corners: self.corners.clone(),
            holes: Vec::new(),
            options: self.options,
        }
    }

    /// Axis-aligned bounding box `(min, max)` of the positions; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<([f32; 3], [f32; 3])> {
        bounding_box(&self.positions)
    }
}

/// Axis-aligned bounding box of a point set (NaN coordinates are passed over, as
/// `f32::min` does). Large sets are split across the thread pool (rayon); `min` and `max` pick
/// values, so the parts' boxes merge into the same box.
pub fn bounding_box(points: &[[f32; 3]]) -> Option<Box3> {
    /// Points per part.
    const PART: usize = 1 << 15;
    if points.len() <= 2 * PART {
        return bounding_box_serial(points);
    }
    use rayon::prelude::*;
    points
        .par_chunks(PART)
        .map(bounding_box_serial)
        .reduce(|| None, union_box)
}

/// The box of two point sets from theirs (either may be empty): the same as the box of both
/// together, bit for bit (`min` and `max` pick values and pass NaN over).
pub fn union_box(a: Option<Box3>, b: Option<Box3>) -> Option<Box3> {
    match (a, b) {
        (Some((lo, hi)), Some((l, h))) => Some((
            [0, 1, 2].map(|k| lo[k].min(l[k])),
            [0, 1, 2].map(|k| hi[k].max(h[k])),
        )),
        (a, None) => a,
        (None, b) => b,
    }
}

/// An axis-aligned box: its lowest and highest corners.
pub type Box3 = ([f32; 3], [f32; 3]);

fn bounding_box_serial(points: &[[f32; 3]]) -> Option<Box3> {
    points.first()?;
    // Compare and select (which the compiler turns into packed min and max): a NaN
    // coordinate fails both tests and is passed over; a coordinate that is NaN in every
    // point stays at the infinities and is NaN in the result, as `f32::min` chains give.
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in points {
        for k in 0..3 {
            lo[k] = if p[k] < lo[k] { p[k] } else { lo[k] };
            hi[k] = if p[k] > hi[k] { p[k] } else { hi[k] };
        }
    }
    for k in 0..3 {
        if lo[k] > hi[k] {
            (lo[k], hi[k]) = (f32::NAN, f32::NAN);
        }
    }
    Some((lo, hi))
}

/// Length of the bounding-box diagonal of a point set (0 for an empty set): the scale that
/// relative errors are measured against.
pub fn bbox_diagonal(points: &[[f32; 3]]) -> f32 {
    bounding_box(points).map_or(0.0, |(lo, hi)| {
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f32>().sqrt()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box equals the one `f32::min`/`f32::max` chains give, bit for bit: on sets split
    /// across the pool and not, with NaN coordinates passed over (and a coordinate NaN in every
    /// point NaN in the box), infinities kept, and none for an empty set.
    #[test]
    fn bounding_boxes_equal_min_max_chains() {
        let chain = |points: &[[f32; 3]]| {
            let first = *points.first()?;
            let (mut lo, mut hi) = (first, first);
            for p in points {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            Some((lo, hi))
        };
        let bits = |b: Option<([f32; 3], [f32; 3])>| {
            b.map(|(lo, hi)| (lo.map(f32::to_bits), hi.map(f32::to_bits)))
        };
        let mut x = 12345u32;
        let mut next = move || {
            x = x.wrapping_mul(1664525).wrapping_add(1013904223);
            (x >> 8) as f32 / (1 << 24) as f32 * 200.0 - 100.0
        };
        for n in [0usize, 1, 7, 1000, 200_000] {
            let mut points: Vec<[f32; 3]> = (0..n).map(|_| [next(), next(), next()]).collect();
            if n > 7 {
                points[0][1] = f32::NAN;
                points[n / 2][0] = f32::INFINITY;
                points[n - 1][2] = f32::NAN;
            }
            assert_eq!(
                bits(bounding_box(&points)),
                bits(chain(&points)),
                "{n} points"
            );
            for p in points.iter_mut() {
                p[2] = f32::NAN;
            }
            assert_eq!(
                bits(bounding_box(&points)),
                bits(chain(&points)),
                "{n} points, z NaN"
            );
        }
    }
}
