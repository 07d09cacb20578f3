//! The watertight mesh of per-edge rates: every ptex face's [`QuadPattern`] joined to its
//! neighbours through shared samples.
//!
//! Every sample has a global key before anything is evaluated: a base vertex, a position
//! `p = 1..R−1` along a base edge of rate `R` (counted from the edge's first vertex), an
//! n-gon's centre, a position along one of its spokes (edge midpoint → centre), or a sample
//! inside one ptex face. Both faces of an edge take its `R − 1` samples by key, so a shared
//! edge is the same vertices from both sides whatever the rates: no crack, no T-junction.
//!
//! A face with `n ≠ 4` corners is `n` quad ptex sub-faces whose outer edges are half base
//! edges and two spokes. Its base edges need an even rate (an odd one is raised by one,
//! [`AdaptivePlan::edge_rates`] reports the rates used) so that the midpoint — a sub-face
//! corner — is a sample; half edges take `R/2`. Spokes take the face's interior rate: the
//! given one, else the mean of its half-edge rates (at least 1).

use rayon::prelude::*;

use super::pattern::QuadPattern;
use crate::error::{MeshError, Result, TessError};
use crate::limit::patch_map::EMPTY;
use crate::limit::{LimitSurface, PatchTable};
use crate::topology::Topology;

/// The highest rate of an edge.
pub const MAX_RATE: u32 = 4096;

/// Rates of a tessellation: one per base edge (`Topology::edge_verts` order) and one
/// interior rate per base face (`0`: derived from its edges).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EdgeRates {
    /// Per base edge, `1..=4096`.
    pub edges: Vec<u32>,
    /// Per base face, `0` (derived) or `1..=4096`; empty means all derived.
    pub faces: Vec<u32>,
}

impl EdgeRates {
    /// The same rate on every edge, interiors derived.
    pub fn uniform(t: &Topology, rate: u32) -> EdgeRates {
        EdgeRates {
            edges: vec![rate; t.num_edges()],
            faces: Vec::new(),
        }
    }

    /// Checks the lengths and ranges against `t`; `origin` names where the rates came from.
    pub fn validate(&self, t: &Topology, origin: &str) -> Result<()> {
        if self.edges.len() != t.num_edges() {
            return Err(MeshError::LengthMismatch {
                what: "edge rates",
                expected: t.num_edges(),
                found: self.edges.len(),
            }
            .into());
        }
        if !self.faces.is_empty() && self.faces.len() != t.num_faces() {
            return Err(MeshError::LengthMismatch {
                what: "face interior rates",
                expected: t.num_faces(),
                found: self.faces.len(),
            }
            .into());
        }
        for (e, &r) in self.edges.iter().enumerate() {
            if !(1..=MAX_RATE).contains(&r) {
                let [v0, v1] = t.edge_verts[e];
                return Err(TessError::RateOutOfRange {
                    origin: origin.to_string(),
                    v0,
                    v1,
                    rate: r.into(),
                }
                .into());
            }
        }
        for (f, &r) in self.faces.iter().enumerate() {
            if r > MAX_RATE {
                let v = t.face_vertices(f);
                return Err(TessError::RateOutOfRange {
                    origin: format!("{origin} (interior of face {f})"),
                    v0: v[0],
                    v1: v[1],
                    rate: r.into(),
                }
                .into());
            }
        }
        Ok(())
    }
}

/// What [`plan`] makes: the samples to evaluate and the triangles joining them, a function
/// of the topology and rates alone.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdaptivePlan {
    /// The edge rates used (odd rates of n-gon edges raised by one).
    pub edge_rates: Vec<u32>,
    /// Per ptex face: its outer and inner rates (`None` for a hole).
    pub ptex_rates: Vec<Option<([u32; 4], [u32; 2])>>,
    /// One `(ptex face, u, v)` per output vertex.
    pub queries: Vec<(u32, f32, f32)>,
    /// Counter-clockwise triangles of vertex indices (those of faces that repeat a vertex and
    /// would repeat a sample are left out).
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: its ptex face and its corners' `(u, v)` there (empty from
    /// [`plan_without_uv`]).
    pub triangle_uv: Vec<(u32, [[f32; 2]; 3])>,
}

/// The rates of ptex face `k` of base face `f`: `(outer, inner)`, with `rates` already made
/// even on n-gon edges.
fn ptex_face_rates(
    t: &Topology,
    rates: &EdgeRates,
    edge: &[u32],
    f: usize,
    k: usize,
) -> ([u32; 4], Option<[u32; 2]>) {
    let fe = t.face_edges(f);
    let given = rates.faces.get(f).copied().unwrap_or(0);
    if fe.len() == 4 {
        let outer = [0, 1, 2, 3].map(|i| edge[fe[i] as usize]);
        let inner = if given > 0 {
            [given, given]
        } else {
            let least = outer.iter().copied().min().unwrap_or(1);
            [
                graded(outer[0], outer[2], least),
                graded(outer[1], outer[3], least),
            ]
        };
        (outer, Some(inner))
    } else {
        let n = fe.len();
        let s = spoke_rate(edge, fe, given);
        let h = |i: usize| edge[fe[i] as usize] / 2;
        ([h(k), s, s, h((k + n - 1) % n)], None)
    }
}

fn spoke_rate(edge: &[u32], fe: &[u32], given: u32) -> u32 {
    if given > 0 {
        return given;
    }
    let sum: u32 = fe.iter().map(|&e| edge[e as usize] / 2).sum();
    let least = fe.iter().map(|&e| edge[e as usize] / 2).min().unwrap_or(1);
    (sum / fe.len() as u32).min(GRADING * least).max(1)
}

/// How much finer than the coarser of two opposite edges a derived interior rate may be.
pub const GRADING: u32 = 4;

/// The derived interior rate between opposite edges of rates `a` and `b` of a face whose
/// coarsest edge has rate `least`: their mean (as OpenSubdiv's `Bfr::Tessellation` infers
/// it), at most [`GRADING`] times `least`, so that the interior grid never lies a thin strip
/// away from a much coarser edge (the transition strips stay free of slivers).
pub fn graded(a: u32, b: u32, least: u32) -> u32 {
    ((a + b) / 2).min(GRADING * least).max(1)
}

/// The edge rates with odd rates raised by one on every edge of a non-quad face.
fn even_where_needed(t: &Topology, edges: &[u32]) -> Vec<u32> {
    let mut out = edges.to_vec();
    for f in 0..t.num_faces() {
        if t.face_size(f) != 4 {
            for &e in t.face_edges(f) {
                let r = &mut out[e as usize];
                *r += *r % 2;
            }
        }
    }
    out
}

struct Keys<'a> {
    t: &'a Topology,
    edge: &'a [u32],
    edge_base: Vec<usize>,
    centre: Vec<usize>,
    spoke_base: Vec<usize>,
    spoke: Vec<u32>,
}

impl Keys<'_> {
    /// Sample `p` from corner `from` of face `f` along its edge `k`.
    fn face_edge(&self, f: usize, k: usize, p: u32) -> usize {
        let e = self.t.face_edges(f)[k] as usize;
        let ev = self.t.edge_verts[e];
        let r = self.edge[e];
        let p = if ev[0] == self.t.face_vertices(f)[k] {
            p
        } else {
            r - p
        };
        if p == 0 {
            ev[0] as usize
        } else if p == r {
            ev[1] as usize
        } else {
            self.edge_base[e] + p as usize - 1
        }
    }

    fn spoke(&self, f: usize, k: usize, q: u32) -> usize {
        let s = self.spoke[f];
        if q == 0 {
            let e = self.t.face_edges(f)[k] as usize;
            self.face_edge(f, k, self.edge[e] / 2)
        } else if q == s {
            self.centre[f]
        } else {
            self.spoke_base[f] + k * (s as usize - 1) + q as usize - 1
        }
    }

    /// Key of boundary sample `i` of edge `j` of ptex face `k` of base face `f`.
    fn boundary(&self, f: usize, k: usize, j: usize, i: u32, outer: &[u32; 4]) -> usize {
        let n = self.t.face_size(f);
        if n == 4 {
            return self.face_edge(f, j, i);
        }
        let prev = (k + n - 1) % n;
        match j {
            0 => self.face_edge(f, k, i),
            1 => self.spoke(f, k, i),
            2 => self.spoke(f, prev, outer[2] - i),
            _ => self.face_edge(f, prev, outer[3] + i),
        }
    }
}

/// The samples and triangles of the tessellation of `table`'s base mesh at `rates` (see the
/// module documentation). Refuses rates out of range (naming `origin`) and a tessellation
/// that would not fit in memory, before building anything.
pub fn plan(table: &PatchTable, rates: &EdgeRates, origin: &str) -> Result<AdaptivePlan> {
    plan_with(table, rates, origin, true)
}

/// [`plan`] without its `triangle_uv` (what drawing the tessellation does not read; the rest
/// is the same).
pub fn plan_without_uv(
    table: &PatchTable,
    rates: &EdgeRates,
    origin: &str,
) -> Result<AdaptivePlan> {
    plan_with(table, rates, origin, false)
}

fn plan_with(
    table: &PatchTable,
    rates: &EdgeRates,
    origin: &str,
    with_uv: bool,
) -> Result<AdaptivePlan> {
    let t = &table.base;
    rates.validate(t, origin)?;
    let edge = even_where_needed(t, &rates.edges);
    let nf = t.num_faces();
    let num_ptex = table.ptex_offsets[nf] as usize;
    // Which base face and corner each ptex face is.
    let mut owner = Vec::with_capacity(num_ptex);
    for f in 0..nf {
        let n = t.face_size(f);
        for k in 0..(if n == 4 { 1 } else { n }) {
            owner.push((f, k));
        }
    }
    let ptex_rates: Vec<Option<([u32; 4], [u32; 2])>> = owner
        .iter()
        .enumerate()
        .map(|(ptex, &(f, k))| {
            (table.patch_map.roots[ptex] != EMPTY).then(|| {
                let (outer, inner) = ptex_face_rates(t, rates, &edge, f, k);
                (
                    outer,
                    inner.unwrap_or_else(|| super::pattern::default_inner(outer)),
                )
            })
        })
        .collect();
    check_memory(&ptex_rates)?;

    // One pattern per distinct pair of rates (faces mostly share a few), built in parallel.
    let mut distinct: Vec<([u32; 4], [u32; 2])> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let pattern_of: Vec<Option<usize>> = ptex_rates
        .iter()
        .map(|r| {
            r.map(|rates| {
                *index.entry(rates).or_insert_with(|| {
                    distinct.push(rates);
                    distinct.len() - 1
                })
            })
        })
        .collect();
    let unique: Vec<QuadPattern> = distinct
        .par_iter()
        .map(|&(outer, inner)| QuadPattern::new(outer, Some(inner)))
        .collect();
    let patterns: Vec<Option<&QuadPattern>> =
        pattern_of.iter().map(|i| i.map(|i| &unique[i])).collect();

    // Global keys.
    let mut next = t.num_vertices();
    let mut edge_base = vec![0; t.num_edges()];
    for (e, &r) in edge.iter().enumerate() {
        edge_base[e] = next;
        next += r as usize - 1;
    }
    let (mut centre, mut spoke_base, mut spoke) = (vec![0; nf], vec![0; nf], vec![0u32; nf]);
    for f in 0..nf {
        let fe = t.face_edges(f);
        if fe.len() != 4 {
            spoke[f] = spoke_rate(&edge, fe, rates.faces.get(f).copied().unwrap_or(0));
            centre[f] = next;
            spoke_base[f] = next + 1;
            next += 1 + fe.len() * (spoke[f] as usize - 1);
        }
    }
    let mut interior_base = vec![0; num_ptex];
    for (ptex, p) in patterns.iter().enumerate() {
        interior_base[ptex] = next;
        if let Some(p) = p {
            next += p.coords.len() - p.num_boundary;
        }
    }
    let keys = Keys {
        t,
        edge: &edge,
        edge_base,
        centre,
        spoke_base,
        spoke,
    };
    let local_keys: Vec<Vec<usize>> = patterns
        .par_iter()
        .enumerate()
        .map(|(ptex, p)| {
            let Some(p) = p else { return Vec::new() };
            let (f, k) = owner[ptex];
            let mut out = Vec::with_capacity(p.coords.len());
            for j in 0..4 {
                for i in 0..p.outer[j] {
                    out.push(keys.boundary(f, k, j, i, &p.outer));
                }
            }
            out.extend(
                (p.num_boundary..p.coords.len()).map(|i| interior_base[ptex] + i - p.num_boundary),
            );
            out
        })
        .collect();

    // The first face to use a key evaluates it.
    const NONE: u32 = u32::MAX;
    let mut remap = vec![NONE; next];
    let num_triangles: usize = patterns.iter().flatten().map(|p| p.triangles.len()).sum();
    let mut queries = Vec::with_capacity(next);
    let mut triangles = Vec::with_capacity(num_triangles);
    let mut triangle_uv = Vec::with_capacity(if with_uv { num_triangles } else { 0 });
    for (ptex, p) in patterns.iter().enumerate() {
        let Some(p) = p else { continue };
        let lk = &local_keys[ptex];
        for (i, &key) in lk.iter().enumerate() {
            if remap[key] == NONE {
                remap[key] = queries.len() as u32;
                let [u, v] = p.coords[i];
                queries.push((ptex as u32, u, v));
            }
        }
        for tri in &p.triangles {
            let out = tri.map(|i| remap[lk[i as usize]]);
            if out[0] == out[1] || out[1] == out[2] || out[0] == out[2] {
                continue; // on a face that repeats a vertex: no area
            }
            triangles.push(out);
            if with_uv {
                triangle_uv.push((ptex as u32, tri.map(|i| p.coords[i as usize])));
            }
        }
    }
    Ok(AdaptivePlan {
        edge_rates: edge,
        ptex_rates,
        queries,
        triangles,
        triangle_uv,
    })
}

/// Refuses a tessellation whose output would pass the memory limit (as an oversize refinement
/// level is refused).
fn check_memory(ptex_rates: &[Option<([u32; 4], [u32; 2])>]) -> Result<()> {
    let mut samples = 0u64;
    for ([a, b, c, d], [u, v]) in ptex_rates.iter().flatten() {
        let boundary = u64::from(a + b + c + d);
        samples = samples.saturating_add(
            boundary + u64::from(u.saturating_sub(1)) * u64::from(v.saturating_sub(1)) + 1,
        );
    }
    check_samples(samples as f64)
}

/// Refuses a tessellation of `samples` samples that would pass the memory limit, with the
/// estimate.
pub(crate) fn check_samples(samples: f64) -> Result<()> {
    // Per sample: a query, a position, a normal, two triangles with their (u, v), keys.
    let bytes = samples * (12 + 24 + 2 * (12 + 28) + 16) as f64;
    crate::util::budget::check(bytes, || {
        format!(
            "a tessellation of {} samples",
            crate::util::budget::count(samples)
        )
    })?;
    Ok(())
}

/// An evaluated adaptive tessellation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdaptiveTessellation {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals (zero where undefined).
    pub normals: Vec<[f32; 3]>,
    /// Counter-clockwise triangles.
    pub triangles: Vec<[u32; 3]>,
    /// The edge rates used.
    pub edge_rates: Vec<u32>,
}

impl AdaptiveTessellation {
    /// A triangle mesh of the tessellation.
    pub fn to_mesh(&self) -> crate::Mesh {
        crate::Mesh {
            positions: self.positions.clone().into(),
            face_counts: vec![3; self.triangles.len()],
            face_indices: self.triangles.iter().flatten().copied().collect(),
            ..Default::default()
        }
    }
}

impl LimitSurface {
    /// Evaluates the [`plan`] of `rates` (`origin` names where they came from in errors).
    pub fn tessellate_rates(
        &self,
        rates: &EdgeRates,
        origin: &str,
    ) -> Result<AdaptiveTessellation> {
        let plan = plan_without_uv(&self.table, rates, origin)?;
        Ok(self.eval_plan(plan))
    }

    /// Evaluates a plan made by [`plan`] for this surface's table.
    pub fn eval_plan(&self, plan: AdaptivePlan) -> AdaptiveTessellation {
        let (positions, normals) = self.eval_queries(&plan.queries);
        AdaptiveTessellation {
            positions,
            normals,
            triangles: plan.triangles,
            edge_rates: plan.edge_rates,
        }
    }

    /// Positions and normals of a plan's queries, as [`Self::eval_plan`] gives them (zero
    /// in a hole).
    pub(crate) fn eval_queries(
        &self,
        queries: &[(u32, f32, f32)],
    ) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
        use crate::limit::eval::BATCH;
        let mut positions = vec![[0.0f32; 3]; queries.len()];
        let mut normals = vec![[0.0f32; 3]; queries.len()];
        (positions.par_chunks_mut(BATCH))
            .zip(normals.par_chunks_mut(BATCH))
            .zip(queries.par_chunks(BATCH))
            .for_each(|((p, n), q)| self.eval_chunk(q, |i, e| (p[i], n[i]) = (e.p, e.n)));
        (positions, normals)
    }
}
