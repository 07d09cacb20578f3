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

pub mod bezier;
pub mod constants;
pub mod eval;
pub mod grid;
pub mod npy;
pub mod patch_pass;
pub mod quadrangulate;
pub mod ring;
pub mod scalar;
pub mod vertex_pass;

pub use eval::{Grid, Sample, Tessellation};
pub use ring::{check_input, PrepTopology};
pub use scalar::Real;
pub use vertex_pass::VertexData;

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::topology::Topology;
use constants::ValenceTable;
use scalar::{zero3, V3};

/// A p-rep surface: one patch per quad.
#[derive(Debug, Clone)]
pub struct PrepPatches<T> {
    /// Connectivity tables (reusable for new positions with [`PrepPatches::update`]).
    pub topology: PrepTopology,
    /// Vertex-pass outputs.
    pub vertex: VertexData<T>,
    /// Bi-3 coefficients, 16 per face, `g[16 f + 4 i + j]` (i along `v0 → v1`, j along `v0 → v3`).
    pub g: Vec<V3<T>>,
    /// Per face, the block index into `h`, or `u32::MAX` for a B-quad (h = 0).
    pub h_index: Vec<u32>,
    /// Non-zero bi-5 perturbation coefficients, 16 per perturbed face, in
    /// [`patch_pass::H_SLOTS`] order.
    pub h: Vec<V3<T>>,
    consts: ValenceTable<T>,
}

impl<T: Real> PrepPatches<T> {
    /// Builds the p-rep of a closed quad mesh (parallel passes).
    pub fn build(mesh: &Mesh) -> Result<Self> {
        Self::from_topology(&Topology::new(mesh)?, &mesh.positions)
    }

    /// Builds the p-rep from a validated topology and one position per vertex.
    pub fn from_topology(topo: &Topology, positions: &[[f32; 3]]) -> Result<Self> {
        Self::from_prep_topology(PrepTopology::new(topo)?, positions)
    }

    /// Builds the p-rep from prepared ring tables and vertex positions.
    pub fn from_prep_topology(topology: PrepTopology, positions: &[[f32; 3]]) -> Result<Self> {
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

    fn check_len(&self, positions: &[[f32; 3]]) -> Result<()> {
        if positions.len() != self.topology.num_vertices {
            return Err(MeshError::Unsupported {
                construction: "the p-rep",
                requirement: "one position per vertex of the connectivity",
                details: format!(
                    "{} positions for {} vertices",
                    positions.len(),
                    self.topology.num_vertices
                ),
            }
            .into());
        }
        Ok(())
    }

    /// Recomputes every coefficient for new positions (same connectivity), in parallel.
    pub fn update(&mut self, positions: &[[f32; 3]]) -> Result<()> {
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
    pub fn update_sequential(&mut self, positions: &[[f32; 3]]) -> Result<()> {
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
        npy::write_f64(w, &data, &[self.num_faces(), 6, 6, 3])
    }
}
