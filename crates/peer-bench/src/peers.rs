//! Each peer's setup (topology and whatever tables its per-frame path needs) and its per-frame
//! evaluation of the last level's positions, behind one small trait so that the harness times
//! them alike.

use std::num::NonZeroU8;

use osd_ref::{OsdMesh, OsdRefiner, OsdStencils};
use subsurf::{BoundaryInterpolation, CreaseMethod, Mesh, Refiner, Topology, TriangleSubdivision};

/// A peer refined to one level, ready to evaluate frames.
pub trait Prepared {
    /// Last-level positions of `base` into `out` (sized by [`Prepared::num_outputs`]).
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]);
    /// Number of last-level vertices.
    fn num_outputs(&self) -> usize;
}

/// OpenSubdiv 3.5 (C++): `TopologyRefinerFactory::Create` + `RefineUniform` (full last level);
/// per frame `PrimvarRefiner::Interpolate` on every level.
pub struct Osd(pub OsdRefiner);

impl Osd {
    pub fn setup(mesh: &OsdMesh, level: usize) -> Self {
        Osd(OsdRefiner::with_last_level(mesh, level, true).expect("OpenSubdiv refines"))
    }
}

impl Prepared for Osd {
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]) {
        self.0
            .interpolate_into(base, out)
            .expect("OpenSubdiv interpolates");
    }
    fn num_outputs(&self) -> usize {
        self.0.num_vertices(self.0.max_level())
    }
}

/// OpenSubdiv 3.5's `StencilTableFactory` table (base to last level, built from an [`Osd`]
/// refiner); per frame `StencilTable::UpdateValues`.
pub struct OsdTable(pub OsdStencils);

impl Prepared for OsdTable {
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]) {
        self.0
            .update_into(base, out)
            .expect("OpenSubdiv stencils apply");
    }
    fn num_outputs(&self) -> usize {
        self.0.num_stencils()
    }
}

/// opensubdiv-rs (a Rust port of OpenSubdiv's Far): `TopologyRefinerFactory::create` +
/// `refine_uniform`; per frame `PrimvarRefiner::interpolate` on every level, into buffers
/// kept between frames.
pub struct OsdRs {
    refiner: opensubdiv_rs::far::TopologyRefiner,
    levels: Vec<Vec<[f32; 3]>>,
}

impl OsdRs {
    pub fn setup(mesh: &Mesh, level: usize) -> Self {
        use opensubdiv_rs::far::{TopologyDescriptor, TopologyRefinerFactory, UniformOptions};
        use opensubdiv_rs::sdc;
        let counts: Vec<usize> = mesh.face_counts.iter().map(|&c| c as usize).collect();
        let pairs: Vec<[u32; 2]> = mesh.creases.iter().map(|c| [c.v0, c.v1]).collect();
        let weights: Vec<f32> = mesh.creases.iter().map(|c| c.sharpness).collect();
        let cv: Vec<u32> = mesh.corners.iter().map(|c| c.vertex).collect();
        let cw: Vec<f32> = mesh.corners.iter().map(|c| c.sharpness).collect();
        let desc = TopologyDescriptor::new(mesh.num_vertices(), &counts, &mesh.face_indices)
            .with_creases(&pairs, &weights)
            .with_corners(&cv, &cw)
            .with_holes(&mesh.holes);
        let o = &mesh.options;
        let options = sdc::Options::default()
            .with_vtx_boundary_interpolation(match o.boundary {
                BoundaryInterpolation::None => sdc::VtxBoundaryInterpolation::None,
                BoundaryInterpolation::EdgeOnly => sdc::VtxBoundaryInterpolation::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner => {
                    sdc::VtxBoundaryInterpolation::EdgeAndCorner
                }
            })
            .with_creasing_method(match o.crease_method {
                CreaseMethod::Uniform => sdc::CreasingMethod::Uniform,
                CreaseMethod::Chaikin => sdc::CreasingMethod::Chaikin,
            })
            .with_triangle_subdivision(match o.triangle_subdivision {
                TriangleSubdivision::Catmark => sdc::TriangleSubdivision::Catmark,
                TriangleSubdivision::Smooth => sdc::TriangleSubdivision::Smooth,
            });
        let mut refiner = TopologyRefinerFactory::create(desc, sdc::SchemeType::Catmark, options)
            .expect("opensubdiv-rs accepts the mesh");
        refiner.refine_uniform(UniformOptions::new(level));
        let levels = (1..=level)
            .map(|k| vec![[0.0; 3]; refiner.level(k).num_vertices()])
            .collect();
        OsdRs { refiner, levels }
    }
}

impl Prepared for OsdRs {
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]) {
        let pr = opensubdiv_rs::far::PrimvarRefiner::new(&self.refiner);
        let n = self.levels.len();
        if n == 0 {
            out.copy_from_slice(base);
            return;
        }
        for k in 1..=n {
            let (done, rest) = self.levels.split_at_mut(k - 1);
            let src: &[[f32; 3]] = if k == 1 { base } else { &done[k - 2] };
            if k == n {
                pr.interpolate(k, src, out);
            } else {
                pr.interpolate(k, src, &mut rest[0]);
            }
        }
    }
    fn num_outputs(&self) -> usize {
        self.refiner.level(self.refiner.max_level()).num_vertices()
    }
}

/// subdiv-kernels: `Refiner::new` + `refine_uniform` (topology and one stencil table per level;
/// the input's undirected edge list, which its mesh type requires, is built inside the timed
/// setup); per frame the per-level tables chained (`RefinementResult::interpolate`).
pub struct Kernels(pub subdiv_kernels::RefinementResult);

impl Kernels {
    pub fn setup(mesh: &Mesh, level: usize) -> Self {
        use subdiv_kernels::{
            BoundaryInterpolation as B, CreaseComputationMethod as C, Scheme, SchemeOptions,
            TriangleSubdivisionRule as T, UniformRefine,
        };
        let mut edges = std::collections::HashMap::new();
        let mut edge_vertices = Vec::new();
        let mut start = 0usize;
        for &c in &mesh.face_counts {
            let f = &mesh.face_indices[start..start + c as usize];
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                let key = [a.min(b), a.max(b)];
                edges.entry(key).or_insert_with(|| {
                    edge_vertices.push(key);
                    edge_vertices.len() - 1
                });
            }
            start += c as usize;
        }
        let mut edge_creases = vec![0.0; edge_vertices.len()];
        for c in &mesh.creases {
            if let Some(&e) = edges.get(&[c.v0.min(c.v1), c.v0.max(c.v1)]) {
                edge_creases[e] = c.sharpness;
            }
        }
        let mut vertex_corners = vec![0.0; mesh.num_vertices()];
        for c in &mesh.corners {
            vertex_corners[c.vertex as usize] = c.sharpness;
        }
        let km = subdiv_kernels::topology::Mesh {
            vertex_count: mesh.num_vertices() as u32,
            face_vertex_counts: mesh.face_counts.clone(),
            face_vertex_indices: mesh.face_indices.clone(),
            edge_vertices,
            edge_creases,
            vertex_corners,
        };
        let o = &mesh.options;
        let options = SchemeOptions {
            boundary_interpolation: match o.boundary {
                BoundaryInterpolation::None => B::Natural,
                BoundaryInterpolation::EdgeOnly => B::EdgesOnly,
                BoundaryInterpolation::EdgeAndCorner => B::EdgesAndCorners,
            },
            crease_computation: match o.crease_method {
                CreaseMethod::Uniform => C::Uniform,
                CreaseMethod::Chaikin => C::Chaikin,
            },
            triangle_subdivision_rule: match o.triangle_subdivision {
                TriangleSubdivision::Catmark => T::CatmullClark,
                TriangleSubdivision::Smooth => T::SmoothTriangles,
            },
            ..SchemeOptions::default()
        };
        let r = subdiv_kernels::Refiner::new(km, Scheme::CatmullClark, options)
            .expect("subdiv-kernels accepts the mesh");
        let req = UniformRefine::from(NonZeroU8::new(level as u8).expect("level >= 1"));
        Kernels(r.refine_uniform(&req).expect("subdiv-kernels refines"))
    }
}

impl Prepared for Kernels {
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]) {
        // The crate's tables return fresh buffers; the last one is copied into `out`.
        let last = self.0.interpolate(base);
        out.copy_from_slice(&last);
    }
    fn num_outputs(&self) -> usize {
        self.0.topology.vertex_count as usize
    }
}

/// subsurf: `Topology::new` + `Refiner::new` (full last level, per-step frame plans kept);
/// per frame `Refiner::refine_positions_into`.
pub struct Subsurf {
    pub refiner: Refiner,
    scratch: Vec<[f32; 3]>,
}

impl Subsurf {
    pub fn setup(mesh: &Mesh, level: usize) -> Self {
        let t = Topology::new(mesh).expect("subsurf accepts the mesh");
        Subsurf {
            refiner: Refiner::new(t, level).expect("subsurf refines"),
            scratch: Vec::new(),
        }
    }
}

impl Prepared for Subsurf {
    fn frame(&mut self, base: &[[f32; 3]], out: &mut [[f32; 3]]) {
        self.refiner
            .refine_positions_into(base, out, &mut self.scratch)
            .expect("lengths match");
    }
    fn num_outputs(&self) -> usize {
        self.refiner.last().num_vertices()
    }
}
