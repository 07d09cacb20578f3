//! The p-rep: conversion of a closed quad mesh to a G1 surface of bi-3 patches with sparse
//! bi-5 perturbations (Myles, Yeo & Peters 2008, "GPU conversion of quad meshes to smooth
//! surfaces"). Formulas, index conventions and corrections follow the checked specification
//! (`prep.md`): equation numbers below are the paper's.
//!
//! Passes, one file each, all pure functions over flat tables:
//!
//! ```text
//! Topology ──ring──▶ PrepTopology (rings, sectors, edges; built once per connectivity)
//! positions ──vertex_pass──▶ VertexData (limit point, e1, e2 per vertex; T(k), I(k) per sector)
//!           ──patch_pass──▶ g (16 per face), h (16 per non-B-quad)
//!           ──eval──▶ points / normals / watertight tessellation     ──bezier──▶ bi-5 b (36 per face)
//! ```
//!
//! The surface interpolates the Catmull-Clark limit points and tangent planes at the mesh
//! vertices, is C1 where all valences are 4 (it is then the bicubic B-spline) and G1
//! everywhere else. Only closed, oriented 2-manifold quad meshes are covered: see
//! [`check_input`] and [`quadrangulate`] for other polygons.

pub(crate) mod bezier;
pub(crate) mod constants;
pub(crate) mod eval;
pub(crate) mod grid;
pub(crate) mod npy;
pub(crate) mod patch_pass;
pub(crate) mod quadrangulate;
pub(crate) mod ring;
pub(crate) mod vertex_pass;

pub use bezier::face_bezier;
pub use eval::{Grid, Sample, Tessellation};
pub use npy::write_npy;
pub use quadrangulate::quadrangulate;

/// The per-element functions of the p-rep's passes (the paper's equations, with the
/// corrections of the checked specification), for a backend that runs the passes itself —
/// the wgpu backend's CPU twins call these — and for checks of single formulas.
pub mod kernel {
    #[doc(inline)]
    pub use crate::prep::constants::{c_n, Valence, ValenceTable};
    #[doc(inline)]
    pub use crate::prep::eval::{eval_patch, Basis};
    #[doc(inline)]
    pub use crate::prep::patch_pass::{corner_index, edge_h, EdgeInputs, H_SLOTS};
    #[doc(inline)]
    pub use crate::prep::vertex_pass::{frame_from_ring, interior_coeff, tangent_coeff};
}
pub(crate) use crate::real::Real;
pub use ring::{check_input, PrepTopology};
pub use vertex_pass::VertexData;

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::topology::Topology;
use crate::util::vec3::{zero3, V3};
use constants::ValenceTable;

/// A p-rep surface: one patch per quad.
///
/// # Example
///
/// The cube (valence 3 everywhere): every patch carries a bi-5 perturbation, the surface
/// interpolates the Catmull-Clark limit points, its tessellation is closed, and its Bezier
/// form starts at the same corners; on a torus (valence 4 everywhere) no patch is perturbed
/// and the surface is the bicubic B-spline limit surface itself:
///
/// ```
/// use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
/// use subsurf::prep::PrepPatches;
/// use subsurf::{shapes, Mesh, Topology};
///
/// let limit = |mesh: &Mesh| -> subsurf::Result<LimitSurface> {
///     let table = PatchTable::build(&Topology::new(mesh)?, &PatchOptions::default())?;
///     Ok(LimitSurface::new(table, &mesh.positions))
/// };
/// let close = |a: [f64; 3], b: [f32; 3]| (0..3).all(|c| (a[c] - b[c] as f64).abs() < 1e-5);
///
/// let cube = shapes::cube();
/// let prep = PrepPatches::<f64>::build(&cube)?;
/// assert_eq!(prep.num_faces(), 6);
/// assert!((0..6).all(|f| prep.face_h(f).is_some()));
/// let cc = limit(&cube)?;
/// for f in 0..6 {
///     let corner = prep.eval(f, 0.0, 0.0).position; // at the face's first vertex
///     assert!(close(corner, cc.eval(f, 0.0, 0.0).expect("face").p));
/// }
///
/// // Watertight: 8 + 12·2 + 6·2² shared vertices, 108 triangles, Euler characteristic 2.
/// let t = prep.tessellate(4);
/// assert_eq!((t.positions.len(), t.triangles.len()), (56, 108));
/// assert_eq!(t.positions.len() as i64 - 3 * 108 / 2 + 108, 2);
///
/// // Bezier form: 6×6 bi-5 control points per face, the first one at the patch corner.
/// let b = prep.to_bezier();
/// assert_eq!(b.len(), 36 * 6);
/// assert!((0..6).all(|f| b[36 * f] == prep.eval(f, 0.0, 0.0).position));
/// let mut npy = Vec::new();
/// prep.write_bezier_npy(&mut npy)?; // shape (6, 6, 6, 3), little-endian f64
/// assert!(npy.starts_with(b"\x93NUMPY"));
/// let last = f64::from_le_bytes(npy[npy.len() - 8..].try_into().expect("8 bytes"));
/// assert_eq!(last, b[36 * 6 - 1][2]);
///
/// let torus = shapes::torus(8, 6, 2.0, 0.5);
/// let prep = PrepPatches::<f64>::build(&torus)?;
/// let cc = limit(&torus)?;
/// for f in [0, 17, 47] {
///     assert!(prep.face_h(f).is_none());
///     for (u, v) in [(0.3, 0.6), (1.0, 0.5)] {
///         assert!(close(prep.eval(f, u, v).position, cc.eval(f, u as f32, v as f32).expect("face").p));
///     }
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct PrepPatches<T> {
    /// Connectivity tables (reusable for new positions with [`PrepPatches::update`]).
    pub(crate) topology: PrepTopology,
    /// Vertex-pass outputs.
    pub(crate) vertex: VertexData<T>,
    /// Bi-3 coefficients, 16 per face, `g[16 f + 4 i + j]` (i along `v0 → v1`, j along `v0 → v3`).
    pub(crate) g: Vec<V3<T>>,
    /// Per face, the block index into `h`, or `u32::MAX` for a B-quad (h = 0).
    pub(crate) h_index: Vec<u32>,
    /// Non-zero bi-5 perturbation coefficients, 16 per perturbed face, in
    /// [`patch_pass::H_SLOTS`] order.
    pub(crate) h: Vec<V3<T>>,
    consts: ValenceTable<T>,
}

impl<T> PrepPatches<T> {
    /// Connectivity tables (reusable for new positions with [`PrepPatches::update`]).
    pub fn topology(&self) -> &PrepTopology {
        &self.topology
    }

    /// Vertex-pass outputs.
    pub fn vertex(&self) -> &VertexData<T> {
        &self.vertex
    }

    /// Bi-3 coefficients, 16 per face, `g[16 f + 4 i + j]` (i along `v0 → v1`, j along `v0 → v3`).
    pub fn g(&self) -> &[V3<T>] {
        &self.g
    }

    /// Per face, the block index into `h`, or `u32::MAX` for a B-quad (h = 0).
    pub fn h_index(&self) -> &[u32] {
        &self.h_index
    }

    /// Non-zero bi-5 perturbation coefficients, 16 per perturbed face, in
    /// [`patch_pass::H_SLOTS`] order.
    pub fn h(&self) -> &[V3<T>] {
        &self.h
    }

    /// The perturbation coefficients, to change in place (for instance zeroed, which leaves
    /// the C0 bicubic surface of `g` alone: a negative control of a G1 measure).
    pub fn h_mut(&mut self) -> &mut [V3<T>] {
        &mut self.h
    }
}

impl<T: Real> PrepPatches<T> {
    /// Builds the p-rep of a closed quad mesh (parallel passes).
    pub fn build(mesh: &Mesh) -> Result<Self> {
        Self::from_topology(&Topology::new(mesh)?, &mesh.positions)
    }

    /// Builds the p-rep from a validated topology and one position per vertex.
    pub fn from_topology(
        topo: &Topology,
        positions: &(impl crate::real::VertexData<3> + Sync + ?Sized),
    ) -> Result<Self> {
        Self::from_prep_topology(PrepTopology::new(topo)?, positions)
    }

    /// Builds the p-rep from prepared ring tables and vertex positions.
    pub fn from_prep_topology(
        topology: PrepTopology,
        positions: &(impl crate::real::VertexData<3> + Sync + ?Sized),
    ) -> Result<Self> {
        let mut p = Self::allocate(topology);
        p.update(positions)?;
        Ok(p)
    }

    fn allocate(topology: PrepTopology) -> Self {
        let consts = ValenceTable::new(topology.max_valence);
        PrepPatches {
            vertex: VertexData::new(&topology),
            g: vec![zero3(); 16 * topology.num_faces()],
            h_index: topology.h_index.clone(),
            h: vec![zero3(); 16 * topology.perturbed_faces.len()],
            consts,
            topology,
        }
    }

    fn check_len(
        &self,
        positions: &(impl crate::real::VertexData<3> + Sync + ?Sized),
    ) -> Result<()> {
        if positions.num_vertices() != self.topology.num_vertices {
            return Err(MeshError::Unsupported {
                construction: "the p-rep",
                requirement: "one position per vertex of the connectivity",
                details: format!(
                    "{} positions for {} vertices",
                    positions.num_vertices(),
                    self.topology.num_vertices
                ),
            }
            .into());
        }
        Ok(())
    }

    /// Recomputes every coefficient for new positions (same connectivity), in parallel.
    pub fn update(
        &mut self,
        positions: &(impl crate::real::VertexData<3> + Sync + ?Sized),
    ) -> Result<()> {
        self.check_len(positions)?;
        vertex_pass::vertex_pass(&self.topology, &self.consts, positions, &mut self.vertex);
        patch_pass::patch_pass(
            &self.topology,
            &self.consts,
            &self.vertex,
            &mut self.g,
            &mut self.h,
        );
        Ok(())
    }

    /// Sequential reference of [`Self::update`].
    pub fn update_sequential(
        &mut self,
        positions: &(impl crate::real::VertexData<3> + Sync + ?Sized),
    ) -> Result<()> {
        self.check_len(positions)?;
        vertex_pass::vertex_pass_seq(&self.topology, &self.consts, positions, &mut self.vertex);
        patch_pass::patch_pass_seq(
            &self.topology,
            &self.consts,
            &self.vertex,
            &mut self.g,
            &mut self.h,
        );
        Ok(())
    }

    /// Builds with the sequential reference passes.
    pub fn build_sequential(mesh: &Mesh) -> Result<Self> {
        let mut p = Self::allocate(PrepTopology::new(&Topology::new(mesh)?)?);
        p.update_sequential(&mesh.positions)?;
        Ok(p)
    }

    /// Number of patches (faces).
    pub fn num_faces(&self) -> usize {
        self.topology.num_faces()
    }

    /// Bi-5 Bézier control points, 36 per face (`b[36 f + 6 i + j]`, eq. (10)).
    pub fn to_bezier(&self) -> Vec<V3<T>> {
        let mut out = Vec::with_capacity(36 * self.num_faces());
        for f in 0..self.num_faces() {
            out.extend_from_slice(&bezier::face_bezier(self.face_g(f), self.face_h(f)));
        }
        out
    }

    /// Writes the bi-5 control points as an `.npy` array of shape `(faces, 6, 6, 3)`, `<f8`.
    pub fn write_bezier_npy<W: std::io::Write>(&self, w: W) -> std::io::Result<()> {
        let data: Vec<f64> = self
            .to_bezier()
            .iter()
            .flat_map(|p| p.map(|x| x.to_f64()))
            .collect();
        npy::write_npy(w, &data, &[self.num_faces(), 6, 6, 3])
    }
}
