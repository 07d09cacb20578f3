//! Stencils of one refinement level and of the limit, built from the scheme's masks.
//!
//! Face points are folded into the edge and vertex rows (a face point is the average of its
//! face's vertices), so each row refers to parent vertices only and one sparse table maps a
//! level's vertex data to the next level's.

use super::alloc::{init, unwritten, written};
use super::last_level::ChildSharpness;
use super::level::child_end_at_vertex;
use super::stencil::{RowBuilder, StencilTable};
use crate::options::{Scheme, TriangleSubdivision};
use crate::real::Real;
use crate::rules::catmark::{edge_mask, limit_mask, vertex_mask, VertexMask, VertexNeighbourhood};
use crate::topology::tags::rule;
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// Builds a table of `rows` rows over `num_inputs` inputs, in parallel chunks.
pub(crate) fn build_rows<W: Real, F>(rows: usize, num_inputs: usize, row: F) -> StencilTable<W>
where
    F: Fn(usize, &mut RowBuilder, &mut Scratch<W>) + Sync,
{
    let threads = rayon::current_num_threads().max(1);
    let chunk = rows.div_ceil(threads * 4).max(1024);
    let parts: Vec<(Vec<u32>, Vec<u32>, Vec<W>)> = (0..rows.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut b = RowBuilder::new(num_inputs);
            let mut scratch = Scratch::default();
            let range = c * chunk..((c + 1) * chunk).min(rows);
            let mut counts = Vec::with_capacity(range.len());
            let mut idx = Vec::with_capacity(range.len() * 8);
            let mut wts = Vec::with_capacity(range.len() * 8);
            for r in range {
                row(r, &mut b, &mut scratch);
                counts.push(b.len() as u32);
                b.drain_into(&mut idx, &mut wts);
            }
            (counts, idx, wts)
        })
        .collect();
    let total: usize = parts.iter().map(|p| p.1.len()).sum();
    let mut t = StencilTable {
        offsets: Vec::with_capacity(rows + 1),
        indices: Vec::with_capacity(total),
        weights: Vec::with_capacity(total),
        num_inputs,
    };
    t.offsets.push(0);
    let mut acc = 0u32;
    for (counts, idx, wts) in parts {
        for c in counts {
            acc += c;
            t.offsets.push(acc);
        }
        t.indices.extend_from_slice(&idx);
        t.weights.extend_from_slice(&wts);
    }
    t
}

/// Per-thread scratch buffers.
#[derive(Debug, Default)]
pub(crate) struct Scratch<W = f32> {
    pub(crate) mask: VertexMask<W>,
    pub(crate) child_mask: VertexMask<W>,
    pub(crate) pe: Vec<f32>,
    pub(crate) ce: Vec<f32>,
    /// Face-varying values around a vertex.
    pub(crate) values: Vec<u32>,
}

impl<W: Real> Scratch<W> {
    /// The vertex-point mask of parent vertex `v` (edges in ring order), from the sharpness and
    /// rules of the parent level `p` and the child level `c`.
    pub(crate) fn vertex_mask_at(
        &mut self,
        p: &Topology,
        c: &Topology,
        v: usize,
    ) -> &VertexMask<W> {
        self.vertex_mask_with(p, ChildSharpness::of_child(p, c), v)
    }

    /// [`Scratch::vertex_mask_at`] with the child's sharpness given as [`ChildSharpness`].
    pub(crate) fn vertex_mask_with(
        &mut self,
        p: &Topology,
        c: ChildSharpness<'_>,
        v: usize,
    ) -> &VertexMask<W> {
        let pe = p.vertex_edges(v);
        self.pe.clear();
        self.pe
            .extend(pe.iter().map(|&e| p.edge_sharpness[e as usize]));
        self.ce.clear();
        self.ce.extend(
            (0..pe.len())
                .map(|i| c.edge(2 * pe[i] as usize + child_end_at_vertex(p, pe, i, v) as usize)),
        );
        let h = VertexNeighbourhood {
            num_faces: p.vertex_faces(v).len(),
            parent_sharpness: p.vert_sharpness[v],
            child_sharpness: c.vertex(v),
            parent_edges: &self.pe,
            child_edges: &self.ce,
            parent_rule: p.vert_rule[v],
            child_rule: c.rule(v),
        };
        vertex_mask(
            &h,
            p.options.crease_method,
            &mut self.mask,
            &mut self.child_mask,
        );
        &self.mask
    }
}

/// Builds a table whose rows are written directly (no merging of repeated inputs).
///
/// Rows are sized first (`rows.len(r)` where the size is known without forming the row, else
/// the row is formed once to count it), then written in parallel, entry by entry, into
/// disjoint slices of tables allocated once at their exact size, unwritten
/// ([`super::alloc::unwritten`]): each row's slices are zeroed just before it is written.
#[allow(unsafe_code)]
fn build_direct<W: Real>(rows: usize, num_inputs: usize, kind: RowKind<'_>) -> StencilTable<W> {
    let b = par::bounds(rows);
    let mut offsets = unwritten(rows + 1, u32::MAX);
    offsets[0].write(0);
    par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut offsets[1..], &b, |r| r))
        .for_each(|(r, out)| {
            let mut scratch = Scratch::<W>::default();
            let base = r.start;
            for i in r {
                out[i - base].write(match kind.len(i) {
                    Some(n) => n as u32,
                    None => {
                        let mut n = 0u32;
                        kind.row(i, &mut scratch, &mut |_, _: W| n += 1);
                        n
                    }
                });
            }
        });
    // SAFETY: the first value above, the rest by the chunks, which cover them.
    let mut offsets = unsafe { written(offsets) };
    let mut acc = 0u32;
    for o in &mut offsets[1..] {
        acc += *o;
        *o = acc;
    }
    let total = acc as usize;
    let mut indices = unwritten(total, u32::MAX);
    let mut weights = unwritten(total, W::ZERO);
    let start = |r: usize| offsets[r] as usize;
    par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut indices, &b, start))
        .zip(par::split_exact(&mut weights, &b, start))
        .for_each(|((r, io), wo)| {
            let mut scratch = Scratch::default();
            let base = start(r.start);
            for i in r {
                let (a, b) = (start(i) - base, start(i + 1) - base);
                let (io, wo) = (init(&mut io[a..b], 0), init(&mut wo[a..b], W::ZERO));
                let mut k = 0;
                kind.row(i, &mut scratch, &mut |x, w| {
                    io[k] = x;
                    wo[k] = w;
                    k += 1;
                });
            }
        });
    // SAFETY: the chunks cover both tables and every row's values are written (`init`).
    let (indices, weights) = unsafe { (written(indices), written(weights)) };
    StencilTable {
        offsets,
        indices,
        weights,
        num_inputs,
    }
}

/// The face-point table: row `f` is the vertices of face `f` in order, each of weight
/// `1 / n` ([`LevelRows::face`]), so its offsets and indices are the parent's face lists,
/// copied rather than formed row by row.
#[allow(unsafe_code)]
pub(super) fn face_table<W: Real>(p: &Topology) -> StencilTable<W> {
    let nf = p.num_faces();
    let b = par::bounds(nf);
    let mut weights = unwritten(p.num_corners(), W::ZERO);
    let start = |f: usize| p.face_offsets[f] as usize;
    par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut weights, &b, start))
        .for_each(|(r, wo)| {
            let base = start(r.start);
            for f in r {
                let (s, e) = (start(f), start(f + 1));
                init(
                    &mut wo[s - base..e - base],
                    W::ONE / W::from_f64((e - s) as f64),
                );
            }
        });
    // SAFETY: the chunks cover the table, each face writing its corners' values.
    let weights = unsafe { written(weights) };
    StencilTable {
        offsets: p.face_offsets.clone(),
        indices: p.face_verts.clone(),
        weights,
        num_inputs: p.num_vertices(),
    }
}

/// The vertex or edge table of a step, as rows to build.
#[derive(Debug, Clone, Copy)]
enum RowKind<'a> {
    Vertex(LevelRows<'a>),
    Edge(LevelRows<'a>),
}

impl RowKind<'_> {
    #[inline]
    fn len(&self, i: usize) -> Option<usize> {
        match self {
            RowKind::Vertex(r) => r.vertex_len(i),
            RowKind::Edge(r) => r.edge_len(i),
        }
    }

    #[inline]
    fn row<W: Real>(&self, i: usize, s: &mut Scratch<W>, add: &mut impl FnMut(u32, W)) {
        match self {
            RowKind::Vertex(r) => r.vertex(i, s, add),
            RowKind::Edge(r) => r.edge(i, add),
        }
    }
}

/// The stencils of one refinement step, in three tables evaluated in order:
///
/// 1. `face`: one row per parent face (its face point), over the parent vertices;
/// 2. `vertex`: one row per parent vertex (its child), and
/// 3. `edge`: one row per parent edge (its edge point), both over an input space made of the
///    parent vertices `0..P` followed by the face points just computed (`P + f` is the face
///    point of parent face `f`).
///
/// Child vertex data is laid out `[vertex rows | face rows | edge rows]`, OpenSubdiv's order.
///
/// Weights are `W` (`f32` by default, `f64` for `level_stencils_real`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LevelStencils<W = f32> {
    /// Number of parent vertices `P`.
    pub(crate) num_parent_vertices: usize,
    /// Face points over parent vertices.
    pub(crate) face: StencilTable<W>,
    /// Children of vertices over parent vertices and face points.
    pub(crate) vertex: StencilTable<W>,
    /// Edge points over parent vertices and face points.
    pub(crate) edge: StencilTable<W>,
}

impl<W> LevelStencils<W> {
    /// The same stencils with every weight replaced by `f(weight)`
    /// ([`StencilTable::map_weights`]).
    pub fn map_weights<V>(&self, f: impl Fn(&W) -> V) -> LevelStencils<V> {
        LevelStencils {
            num_parent_vertices: self.num_parent_vertices,
            face: self.face.map_weights(&f),
            vertex: self.vertex.map_weights(&f),
            edge: self.edge.map_weights(&f),
        }
    }

    /// Number of parent vertices `P`.
    pub fn num_parent_vertices(&self) -> usize {
        self.num_parent_vertices
    }

    /// Face points over parent vertices.
    pub fn face(&self) -> &StencilTable<W> {
        &self.face
    }

    /// Children of vertices over parent vertices and face points.
    pub fn vertex(&self) -> &StencilTable<W> {
        &self.vertex
    }

    /// Edge points over parent vertices and face points.
    pub fn edge(&self) -> &StencilTable<W> {
        &self.edge
    }
}

impl<W> LevelStencils<W> {
    /// Number of child vertices.
    pub fn num_rows(&self) -> usize {
        self.face.num_rows() + self.vertex.num_rows() + self.edge.num_rows()
    }

    /// Number of stored entries over the three tables.
    pub fn num_entries(&self) -> usize {
        self.face.num_entries() + self.vertex.num_entries() + self.edge.num_entries()
    }

    /// Bytes held by the three tables.
    pub fn size_bytes(&self) -> usize {
        self.face.size_bytes() + self.vertex.size_bytes() + self.edge.size_bytes()
    }
}

impl<W: Real> LevelStencils<W> {
    /// One refinement step of `N`-component values in `W` (face points, then the children
    /// of vertices and the edge points over the parents and face points), each row the plain
    /// weighted sum, in parallel: the double-precision path of [`super::Refiner::refine_f64`].
    pub(crate) fn apply_real<const N: usize>(&self, src: &[[W; N]]) -> Vec<[W; N]> {
        let p = self.num_parent_vertices;
        let faces = rows(&self.face, |k| src[k]);
        let input = |k: usize| if k < p { src[k] } else { faces[k - p] };
        let mut out = rows(&self.vertex, input);
        let edges = rows(&self.edge, input);
        out.extend_from_slice(&faces);
        out.extend_from_slice(&edges);
        out
    }
}

/// Every row of `t` as the plain weighted sum of its inputs, input `k` read as `x(k)`, in
/// parallel: the double-precision path ([`LevelStencils::apply_real`],
/// [`super::Refiner::limit_f64`]).
pub(crate) fn rows<W: Real, const N: usize>(
    t: &StencilTable<W>,
    x: impl Fn(usize) -> [W; N] + Sync,
) -> Vec<[W; N]> {
    use rayon::prelude::*;
    (0..t.num_rows())
        .into_par_iter()
        .with_min_len(1024)
        .map(|r| {
            let mut acc = [W::ZERO; N];
            for j in t.offsets[r] as usize..t.offsets[r + 1] as usize {
                let (v, w) = (x(t.indices[j] as usize), t.weights[j]);
                for c in 0..N {
                    acc[c] += w * v[c];
                }
            }
            acc
        })
        .collect()
}

impl LevelStencils {
    /// Applies one refinement step to `N`-component values, in parallel.
    pub fn apply<const N: usize>(&self, src: &[[f32; N]], dst: &mut [[f32; N]]) {
        self.apply_with(src, dst, true)
    }

    /// Applies one refinement step on the calling thread only.
    pub fn apply_serial<const N: usize>(&self, src: &[[f32; N]], dst: &mut [[f32; N]]) {
        self.apply_with(src, dst, false)
    }

    fn apply_with<const N: usize>(&self, src: &[[f32; N]], dst: &mut [[f32; N]], parallel: bool) {
        assert_eq!(dst.len(), self.num_rows(), "destination length");
        let nv = self.vertex.num_rows();
        let nf = self.face.num_rows();
        let (vd, rest) = dst.split_at_mut(nv);
        let (fd, ed) = rest.split_at_mut(nf);
        if parallel {
            self.face.apply(src, fd);
        } else {
            self.face.apply_serial(src, fd);
        }
        let fd: &[[f32; N]] = fd;
        // A Loop step has no face points: every input is a parent vertex.
        let p = self.num_parent_vertices;
        self.vertex.apply_split(src, fd, p, vd, parallel);
        self.edge.apply_split(src, fd, p, ed, parallel);
    }

    /// The same step as one table over the parent vertices only (face points expanded and
    /// repeated inputs merged), rows in child order.
    pub fn to_table(&self) -> StencilTable {
        let p = self.num_parent_vertices;
        let (nv, nf) = (self.vertex.num_rows(), self.face.num_rows());
        build_rows(self.num_rows(), p, |r, b, _| {
            let (t, i) = if r < nv {
                (&self.vertex, r)
            } else if r < nv + nf {
                (&self.face, r - nv)
            } else {
                (&self.edge, r - nv - nf)
            };
            for j in t.offsets[i] as usize..t.offsets[i + 1] as usize {
                let (k, w) = (t.indices[j] as usize, t.weights[j] as f64);
                if k < p {
                    b.add_f64(k as u32, w);
                } else {
                    let f = &self.face;
                    for q in f.offsets[k - p] as usize..f.offsets[k - p + 1] as usize {
                        b.add_f64(f.indices[q], w * f.weights[q] as f64);
                    }
                }
            }
        })
    }
}

/// The stencils mapping parent vertex data to child vertex data (see [`LevelStencils`]).
pub fn level_stencils(p: &Topology, c: &Topology) -> LevelStencils {
    level_stencils_real(p, c)
}

/// [`level_stencils`] with weights of any [`Real`] type (`f64`: the masks evaluated in double
/// precision, as OpenSubdiv's `PrimvarRefinerReal<double>`; `f32` gives the same bits as
/// [`level_stencils`]).
pub fn level_stencils_real<W: Real>(p: &Topology, c: &Topology) -> LevelStencils<W> {
    level_stencils_with(p, ChildSharpness::of_child(p, c))
}

/// [`level_stencils`] with only the child's sharpness and rules, not its topology.
pub(crate) fn level_stencils_with<W: Real>(
    p: &Topology,
    c: ChildSharpness<'_>,
) -> LevelStencils<W> {
    let rows = LevelRows::new(p, c);
    let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
    let inputs = nv + nf;
    LevelStencils {
        num_parent_vertices: nv,
        face: face_table(p),
        vertex: build_direct(nv, inputs, RowKind::Vertex(rows)),
        edge: build_direct(ne, inputs, RowKind::Edge(rows)),
    }
}

/// The rows of one refinement step's stencils (see [`LevelStencils`]), formed one at a time
/// from the parent's topology and the child's sharpness: what [`level_stencils_with`] stores,
/// and what [`super::refine_once`] evaluates as it forms them. Each row is handed entry by
/// entry, in table order, to a sink `add(input, weight)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LevelRows<'a> {
    p: &'a Topology,
    c: ChildSharpness<'a>,
    bilinear: bool,
}

impl<'a> LevelRows<'a> {
    pub(crate) fn new(p: &'a Topology, c: ChildSharpness<'a>) -> Self {
        LevelRows {
            p,
            c,
            bilinear: p.options.scheme == Scheme::Bilinear,
        }
    }

    /// The parent level.
    pub(crate) fn parent(&self) -> &'a Topology {
        self.p
    }

    /// Input index of the face point of parent face `f`.
    #[inline]
    fn fp(&self, f: u32) -> u32 {
        self.p.num_vertices() as u32 + f
    }

    /// Face point of face `f`: the average of its vertices.
    #[inline]
    pub(crate) fn face<W: Real>(&self, f: usize, add: &mut impl FnMut(u32, W)) {
        let fv = self.p.face_vertices(f);
        let w = W::ONE / W::from_f64(fv.len() as f64);
        for &v in fv {
            add(v, w);
        }
    }

    /// The valence `n` of vertex `v` where its child follows the smooth rule (a smooth or
    /// dart vertex whose rings close, as many faces as edges): its row is then its `n` face
    /// points and its `n` neighbours, `1/n²` each, and itself, `(n - 2)/n`.
    #[inline]
    pub(crate) fn smooth_valence(&self, v: usize) -> Option<usize> {
        let p = self.p;
        let (pr, n) = (p.vert_rule[v], p.vertex_faces(v).len());
        (!self.bilinear && (pr == rule::SMOOTH || pr == rule::DART) && n == p.valence(v))
            .then_some(n)
    }

    /// Whether the edge point of edge `e` is the smooth two-face point: its two face points,
    /// then its two ends, `1/4` each (a smooth edge with two faces, neither a triangle under
    /// the smooth triangle rule, which weighs them otherwise).
    #[inline]
    pub(crate) fn quarter_edge(&self, e: usize) -> bool {
        let p = self.p;
        let faces = p.edge_faces(e);
        let tri = |i: usize| p.face_size(faces[i] as usize) == 3;
        !self.bilinear
            && p.edge_sharpness[e] <= 0.0
            && faces.len() == 2
            && !(p.options.triangle_subdivision == TriangleSubdivision::Smooth
                && (tri(0) || tri(1)))
    }

    /// Length of the row of vertex `v` where it is known without forming it.
    #[inline]
    pub(crate) fn vertex_len(&self, v: usize) -> Option<usize> {
        if self.bilinear {
            Some(1)
        } else {
            self.smooth_valence(v).map(|n| 2 * n + 1)
        }
    }

    /// The row of the child of vertex `v`.
    #[inline]
    pub(crate) fn vertex<W: Real>(
        &self,
        v: usize,
        s: &mut Scratch<W>,
        add: &mut impl FnMut(u32, W),
    ) {
        let p = self.p;
        if self.bilinear {
            add(v as u32, W::ONE);
            return;
        }
        let pe = p.vertex_edges(v);
        let faces = p.vertex_faces(v);
        if let Some(n) = self.smooth_valence(v) {
            // Smooth rule (Catmull & Clark 1978): (n-2)/n v + 1/n^2 (edges + faces).
            let w = W::ONE / W::from_f64((n * n) as f64);
            for &f in faces {
                add(self.fp(f), w);
            }
            for &e in pe {
                add(p.other_vertex(e as usize, v as u32), w);
            }
            let nw = W::from_f64(n as f64);
            add(v as u32, (nw - W::from_f64(2.0)) / nw);
            return;
        }
        let mask = s.vertex_mask_with(p, self.c, v);
        for (&f, &w) in faces.iter().zip(&mask.faces) {
            if w != W::ZERO {
                add(self.fp(f), w);
            }
        }
        for (&e, &w) in pe.iter().zip(&mask.edges) {
            if w != W::ZERO {
                add(p.other_vertex(e as usize, v as u32), w);
            }
        }
        add(v as u32, mask.vertex);
    }

    /// Length of the row of edge `e` where it is known without forming it.
    #[inline]
    pub(crate) fn edge_len(&self, e: usize) -> Option<usize> {
        if self.bilinear {
            Some(2)
        } else if self.p.edge_sharpness[e] <= 0.0 {
            Some(self.p.edge_faces(e).len() + 2)
        } else {
            None
        }
    }

    /// The row of the edge point of edge `e`.
    #[inline]
    pub(crate) fn edge<W: Real>(&self, e: usize, add: &mut impl FnMut(u32, W)) {
        let p = self.p;
        let ev = p.edge_verts[e];
        if self.bilinear {
            add(ev[0], W::from_f64(0.5));
            add(ev[1], W::from_f64(0.5));
            return;
        }
        let faces = p.edge_faces(e);
        let sharpness = p.edge_sharpness[e];
        // The mask reads the triangles only under the smooth triangle rule with two faces,
        // and the child's rule only where the edge is sharp: neither is looked up otherwise.
        let tri_rule = p.options.triangle_subdivision;
        let tri = if tri_rule == TriangleSubdivision::Smooth && faces.len() == 2 {
            [
                p.face_size(faces[0] as usize) == 3,
                p.face_size(faces[1] as usize) == 3,
            ]
        } else {
            [false; 2]
        };
        let child_rule = if sharpness <= 0.0 {
            rule::SMOOTH
        } else {
            let (nv, nf) = (p.num_vertices(), p.num_faces());
            self.c.rule(nv + nf + e)
        };
        let m = edge_mask::<W>(sharpness, child_rule, faces.len(), tri, tri_rule);
        if m.face != W::ZERO {
            for &f in faces {
                add(self.fp(f), m.face);
            }
        }
        add(ev[0], m.vertex);
        add(ev[1], m.vertex);
    }
}

/// Stencils moving each vertex of `t` to its limit position (OpenSubdiv
/// `PrimvarRefiner::Limit`): the smooth, crease or corner limit mask of its rule.
pub fn limit_stencils(t: &Topology) -> StencilTable {
    limit_stencils_real(t)
}

/// [`limit_stencils`] with weights of any [`Real`] type (`f64`: the limit masks in double
/// precision).
pub(crate) fn limit_stencils_real<W: Real>(t: &Topology) -> StencilTable<W> {
    let bilinear = t.options.scheme == Scheme::Bilinear;
    build_rows(
        t.num_vertices(),
        t.num_vertices(),
        |v, b, s: &mut Scratch<W>| {
            let edges = t.vertex_edges(v);
            if edges.is_empty() || bilinear {
                b.add(v as u32, W::ONE);
                return;
            }
            s.pe.clear();
            s.pe.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
            let faces = t.vertex_faces(v);
            limit_mask(t.vert_rule[v], &s.pe, faces.len(), &mut s.mask);
            for (i, (&f, &k)) in faces.iter().zip(t.vertex_faces_local(v)).enumerate() {
                if let Some(&w) = s.mask.faces.get(i) {
                    let fv = t.face_vertices(f as usize);
                    b.add(fv[(k as usize + 2) % fv.len()], w);
                }
            }
            for (i, &e) in edges.iter().enumerate() {
                if let Some(&w) = s.mask.edges.get(i) {
                    b.add(t.other_vertex(e as usize, v as u32), w);
                }
            }
            b.add(v as u32, s.mask.vertex);
        },
    )
}
