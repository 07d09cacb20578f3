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

    /// Axis-aligned bounding box `(min, max)` of the positions; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<([f32; 3], [f32; 3])> {
        bounding_box(&self.positions)
    }
}

/// Axis-aligned bounding box of a point set (NaN coordinates are passed over, as
/// `f32::min` does). Large sets are split across the thread pool (rayon); `min` and `max` pick
/// values, so the parts' boxes merge into the same box.
pub fn bounding_box(points: &[[f32; 3]]) -> Option<([f32; 3], [f32; 3])> {
    /// Points per part.
    const PART: usize = 1 << 15;
    if points.len() <= 2 * PART {
        return bounding_box_serial(points);
    }
    use rayon::prelude::*;
    points
        .par_chunks(PART)
        .filter_map(bounding_box_serial)
        .reduce_with(|(lo, hi), (l, h)| {
            (
                [0, 1, 2].map(|k| lo[k].min(l[k])),
                [0, 1, 2].map(|k| hi[k].max(h[k])),
            )
        })
}

fn bounding_box_serial(points: &[[f32; 3]]) -> Option<([f32; 3], [f32; 3])> {
    let first = *points.first()?;
    let (mut lo, mut hi) = (first, first);
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
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
