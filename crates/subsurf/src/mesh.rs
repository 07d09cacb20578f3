//! The input model: polygons, positions, optional face-varying UVs and sharpness tags.

use std::borrow::Cow;

use crate::options::Options;
use crate::real::{Real, VertexData};

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
    /// Vertex positions, at the precision they were given ([`Positions`]).
    pub positions: Positions,
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
    pub fn from_faces<F: AsRef<[u32]>>(positions: impl Into<Positions>, faces: &[F]) -> Self {
        let mut face_counts = Vec::with_capacity(faces.len());
        let mut face_indices = Vec::new();
        for f in faces {
            face_counts.push(f.as_ref().len() as u32);
            face_indices.extend_from_slice(f.as_ref());
        }
        Mesh {
            positions: positions.into(),
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

/// Vertex positions at the precision they were given: the `f32` values every `f32` table and
/// GPU upload reads (dereferencing gives them, `&[[f32; 3]]`), and, for positions given in
/// `f64` (an OBJ file's digits, a PLY `double` property, USD `point3d[]`/`double3[]`, a
/// float64 array), those values themselves, which double-precision paths read without
/// rounding ([`VertexData`] gives them).
///
/// The `f32` values are always the `f64` ones rounded to nearest, so the two never disagree:
/// positions are set through [`Positions::from_f32`], [`Positions::from_f64`] or
/// [`Positions::set`], never through a mutable slice.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Positions {
    f32: Vec<[f32; 3]>,
    f64: Option<Vec<[f64; 3]>>,
}

impl Positions {
    /// Positions given in `f32`.
    pub fn from_f32(values: Vec<[f32; 3]>) -> Positions {
        Positions {
            f32: values,
            f64: None,
        }
    }

    /// Positions given in `f64`, kept as given (their `f32` rounding alongside).
    pub fn from_f64(values: Vec<[f64; 3]>) -> Positions {
        Positions {
            f32: values.iter().map(|p| p.map(|x| x as f32)).collect(),
            f64: Some(values),
        }
    }

    /// Positions read as `f64` from a format without a declared precision (OBJ text): kept in
    /// `f64` if any value differs from its `f32` rounding, in `f32` otherwise (nothing is lost
    /// either way).
    pub fn from_f64_compact(values: Vec<[f64; 3]>) -> Positions {
        if values
            .iter()
            .flatten()
            .all(|&x| (x as f32) as f64 == x || x.is_nan())
        {
            Positions::from_f32(values.iter().map(|p| p.map(|x| x as f32)).collect())
        } else {
            Positions::from_f64(values)
        }
    }

    /// Whether the positions are held in `f64` (given in `f64`, not all exact in `f32`).
    pub fn is_f64(&self) -> bool {
        self.f64.is_some()
    }

    /// The `f32` values (the same as dereferencing).
    pub fn as_f32(&self) -> &[[f32; 3]] {
        &self.f32
    }

    /// The `f32` values, to change in place; positions held in `f64` are narrowed to `f32`
    /// first (the `f64` values are dropped, so that the two never disagree).
    pub fn as_f32_mut(&mut self) -> &mut [[f32; 3]] {
        self.f64 = None;
        &mut self.f32
    }

    /// The `f64` values when held in `f64`.
    pub fn as_f64(&self) -> Option<&[[f64; 3]]> {
        self.f64.as_deref()
    }

    /// Every position in `f64`: the values as given (the `f32` ones widened, exactly, when
    /// they were given in `f32`).
    pub fn to_f64(&self) -> Cow<'_, [[f64; 3]]> {
        match &self.f64 {
            Some(v) => Cow::Borrowed(v),
            None => Cow::Owned(self.f32.iter().map(|p| p.map(f64::from)).collect()),
        }
    }

    /// Position `i` in `f64` (exact).
    pub fn get_f64(&self, i: usize) -> [f64; 3] {
        match &self.f64 {
            Some(v) => v[i],
            None => self.f32[i].map(f64::from),
        }
    }

    /// Sets position `i` (in `f64` when the positions are held in `f64`, rounded to `f32`
    /// otherwise).
    pub fn set(&mut self, i: usize, p: [f64; 3]) {
        self.f32[i] = p.map(|x| x as f32);
        if let Some(v) = &mut self.f64 {
            v[i] = p;
        }
    }

    /// Appends a position (kept in `f64` when the positions are held in `f64`).
    pub fn push(&mut self, p: [f64; 3]) {
        self.f32.push(p.map(|x| x as f32));
        if let Some(v) = &mut self.f64 {
            v.push(p);
        }
    }

    /// Appends `other`'s positions; the result is held in `f64` when either is.
    pub fn append(&mut self, other: &Positions) {
        if self.f64.is_none() && other.f64.is_some() {
            let wide = self.to_f64().into_owned();
            self.f64 = Some(wide);
        }
        if let Some(v) = &mut self.f64 {
            v.extend(other.to_f64().iter());
        }
        self.f32.extend_from_slice(&other.f32);
    }

    /// Every position replaced by `f(position)`, computed in `f64` from the values as given
    /// and kept at the same precision.
    pub fn map(&self, mut f: impl FnMut([f64; 3]) -> [f64; 3]) -> Positions {
        match &self.f64 {
            Some(v) => Positions::from_f64(v.iter().map(|&p| f(p)).collect()),
            None => Positions::from_f32(
                self.f32
                    .iter()
                    .map(|p| f(p.map(f64::from)).map(|x| x as f32))
                    .collect(),
            ),
        }
    }

    /// The positions listed in `order`, at the same precision.
    pub fn select(&self, order: impl IntoIterator<Item = usize> + Clone) -> Positions {
        Positions {
            f32: order.clone().into_iter().map(|i| self.f32[i]).collect(),
            f64: self
                .f64
                .as_ref()
                .map(|v| order.into_iter().map(|i| v[i]).collect()),
        }
    }

    /// The `f32` values, taken out.
    pub fn into_f32(self) -> Vec<[f32; 3]> {
        self.f32
    }
}

impl std::ops::Deref for Positions {
    type Target = [[f32; 3]];
    fn deref(&self) -> &[[f32; 3]] {
        &self.f32
    }
}

/// Compares the `f32` values (what an `f32` table reads).
impl PartialEq<Vec<[f32; 3]>> for Positions {
    fn eq(&self, other: &Vec<[f32; 3]>) -> bool {
        self.f32 == *other
    }
}

impl<const K: usize> PartialEq<[[f32; 3]; K]> for Positions {
    fn eq(&self, other: &[[f32; 3]; K]) -> bool {
        self.f32 == *other
    }
}

impl PartialEq<Positions> for Vec<[f32; 3]> {
    fn eq(&self, other: &Positions) -> bool {
        other == self
    }
}

impl From<Vec<[f32; 3]>> for Positions {
    fn from(values: Vec<[f32; 3]>) -> Positions {
        Positions::from_f32(values)
    }
}

impl FromIterator<[f32; 3]> for Positions {
    fn from_iter<I: IntoIterator<Item = [f32; 3]>>(iter: I) -> Positions {
        Positions::from_f32(iter.into_iter().collect())
    }
}

impl<'a> IntoIterator for &'a Positions {
    type Item = &'a [f32; 3];
    type IntoIter = std::slice::Iter<'a, [f32; 3]>;
    fn into_iter(self) -> Self::IntoIter {
        self.f32.iter()
    }
}

impl VertexData<3> for Positions {
    #[inline]
    fn num_vertices(&self) -> usize {
        self.f32.len()
    }
    #[inline]
    fn vertex<R: Real>(&self, i: usize) -> [R; 3] {
        match &self.f64 {
            Some(v) => v[i].map(R::from_f64),
            None => self.f32[i].map(R::from_f32),
        }
    }
    #[inline]
    fn as_f32(&self) -> Option<&[[f32; 3]]> {
        // The f32 values are exact only when the positions were given in f32.
        self.f64.is_none().then_some(self.f32.as_slice())
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
