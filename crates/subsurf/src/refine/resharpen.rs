//! New sharpness on a refined level whose topology is kept: the child level's sharpness, tags
//! and rules recomputed from a parent whose sharpness changed (the values
//! [`super::refine_topology`] gives, by the same functions), and the stencils of the step
//! re-formed only in the rows whose inputs changed.
//!
//! Used by crease edits of a patch table ([`crate::limit::PatchTable::set_sharpness`]).

use super::last_level::ChildSharpness;
use super::level::{child_end_at_vertex, child_half, edge_point_tags, vertex_child_tags};
use super::masks::{LevelRows, LevelStencils, Scratch};
use super::moved::{edge_values, vertex_values, Moved};
use super::stencil::StencilTable;
use crate::real::Real;
use crate::topology::tags;
use crate::topology::Topology;

/// The sharpness bits of a vertex tag (the others follow from the topology alone).
const SHARP_BITS: u16 =
    tags::V_SEMI_SHARP | tags::V_INF_SHARP | tags::V_SEMI_SHARP_EDGES | tags::V_INF_SHARP_EDGES;

/// Recomputes the sharpness, tags and rules of `c`, the refinement of `p` by
/// [`super::refine_topology`], after the vertices `changed` of `p` (and the edges at them)
/// took new sharpness (same topology): the children of the edges at those vertices, the
/// vertices' children and those edges' edge points (no other child element reads a changed
/// value). Visits the changed vertices' edges only; every element of `c` whose values it
/// changes is noted in `moved`, and no other value of `c` changes. Returns the edges of `p`
/// it visited: the changed vertices' edges, each once.
pub(crate) fn resharpen_at(
    p: &Topology,
    c: &mut Topology,
    changed: &[u32],
    moved: &mut Moved,
) -> Vec<u32> {
    let nc = p.num_corners();
    let edges = unique(
        changed
            .iter()
            .flat_map(|&v| p.vertex_edges(v as usize).iter().copied()),
        p.num_edges(),
    );
    let mut around = Vec::new();
    for &e in &edges {
        for end in 0..2 {
            let i = nc + 2 * e as usize + end;
            let old = edge_values(c, i);
            (c.edge_sharpness[i], c.edge_tags[i]) = child_half(p, e as usize, end, &mut around);
            moved.edge(c, i, old);
        }
    }
    for &v in changed {
        let old = vertex_values(c, v as usize);
        child_vertex(p, c, v as usize);
        moved.vertex(c, v as usize, old);
    }
    let points = p.num_vertices() + super::last_level::face_points(p);
    for &e in &edges {
        let i = points + e as usize;
        let old = vertex_values(c, i);
        edge_point(p, c, e as usize);
        moved.vertex(c, i, old);
    }
    edges
}

/// The distinct values of `ids` (each below `n`) in the order they first occur: one bit per
/// possible value ([`Bits`]) instead of a sort (each element the edit visits is worked on
/// once; the order of the work does not change its result).
pub(crate) fn unique(ids: impl IntoIterator<Item = u32>, n: usize) -> Vec<u32> {
    let mut seen = Bits::new(n);
    ids.into_iter()
        .filter(|&id| {
            let new = !seen.get(id);
            seen.set(id);
            new
        })
        .collect()
}

/// A set of element indices below a bound, one bit each; listed in increasing order.
pub(crate) struct Bits(Vec<u64>);

impl Bits {
    pub(crate) fn new(n: usize) -> Bits {
        Bits(vec![0; n.div_ceil(64)])
    }

    pub(crate) fn of(ids: impl IntoIterator<Item = u32>, n: usize) -> Bits {
        let mut b = Bits::new(n);
        for id in ids {
            b.set(id);
        }
        b
    }

    pub(crate) fn set(&mut self, id: u32) {
        self.0[id as usize / 64] |= 1 << (id % 64);
    }

    pub(crate) fn get(&self, id: u32) -> bool {
        self.0[id as usize / 64] & (1 << (id % 64)) != 0
    }

    /// The members, increasing.
    pub(crate) fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.0.iter().enumerate().flat_map(|(w, &word)| {
            let mut rest = word;
            std::iter::from_fn(move || {
                (rest != 0).then(|| {
                    let b = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    64 * w + b
                })
            })
        })
    }
}

/// Sharpness, tags and rule of the child of parent vertex `v`, from its child edges.
fn child_vertex(p: &Topology, c: &mut Topology, v: usize) {
    let nc = p.num_corners();
    let s = crate::rules::crease::decrement(p.vert_sharpness[v]);
    c.vert_sharpness[v] = s;
    let pe = p.vertex_edges(v);
    let (mut inf, mut semi) = (0usize, 0usize);
    for (i, &e) in pe.iter().enumerate() {
        let ce = nc + 2 * e as usize + child_end_at_vertex(p, pe, i, v) as usize;
        let et = c.edge_tags[ce];
        inf += (et & tags::E_INF_SHARP != 0) as usize;
        semi += (et & tags::E_SEMI_SHARP != 0) as usize;
    }
    let (t, rl) = vertex_child_tags(p, v, s, inf, semi);
    c.vert_tags[v] = t | (c.vert_tags[v] & tags::V_INCIDENT_HOLE);
    c.vert_rule[v] = rl;
}

/// Tags and rule of the edge point of parent edge `e`, from its child edges.
fn edge_point(p: &Topology, c: &mut Topology, e: usize) {
    let nc = p.num_corners();
    let (t0, t1) = (c.edge_tags[nc + 2 * e], c.edge_tags[nc + 2 * e + 1]);
    let (t, rl) = edge_point_tags(p.edge_tags[e], t0, t1);
    let i = p.num_vertices() + super::last_level::face_points(p) + e;
    c.vert_tags[i] = (c.vert_tags[i] & !SHARP_BITS) | t;
    c.vert_rule[i] = rl;
}

/// Rows of one table formed again: which rows (increasing), and row `rows[k]` as row `k` of
/// `table`.
#[derive(Debug, Default)]
pub(crate) struct Formed<W> {
    rows: Vec<u32>,
    table: StencilTable<W>,
}

/// The vertex and edge rows of one step formed again ([`form_rows`]), to be written into the
/// step's stencils by [`Restenciled::apply`].
#[derive(Debug, Default)]
pub(crate) struct Restenciled<W> {
    vertex: Formed<W>,
    edge: Formed<W>,
}

/// Forms the vertex rows `dirty_vertex` and edge rows `dirty_edge` (increasing) of the step
/// from `p` to `c` again, as [`super::level_stencils_real`] forms them. Nothing is written:
/// the rows are kept for [`Restenciled::apply`], so that they can be formed before it is
/// known whether they will be used.
pub(crate) fn form_rows<W: Real>(
    p: &Topology,
    c: &Topology,
    dirty_vertex: Vec<u32>,
    dirty_edge: Vec<u32>,
) -> Restenciled<W> {
    let rows = LevelRows::new(p, ChildSharpness::of_child(p, c));
    let mut scratch = Scratch::<W>::default();
    Restenciled {
        vertex: form(dirty_vertex, |i, add| {
            rows.vertex(i, &mut scratch, &mut &mut *add)
        }),
        edge: form(dirty_edge, |i, add| rows.edge(i, &mut &mut *add)),
    }
}

impl<W: Real> Restenciled<W> {
    /// Writes the rows into `s`, the step's stencils before the change: in place where every
    /// row keeps its length, else by splicing the table.
    pub(crate) fn apply(&self, s: &mut LevelStencils<W>) {
        self.vertex.apply(&mut s.vertex);
        self.edge.apply(&mut s.edge);
    }
}

/// Rows `rows` (increasing) formed by `row(i, add)`.
fn form<W: Real>(rows: Vec<u32>, mut row: impl FnMut(usize, &mut dyn FnMut(u32, W))) -> Formed<W> {
    let mut table = StencilTable {
        offsets: Vec::with_capacity(rows.len() + 1),
        ..Default::default()
    };
    table.offsets.push(0);
    for &r in &rows {
        row(r as usize, &mut |x, w| {
            table.indices.push(x);
            table.weights.push(w);
        });
        table.offsets.push(table.indices.len() as u32);
    }
    Formed { rows, table }
}

impl<W: Real> Formed<W> {
    /// Row `k` formed: its entries' range in [`Formed::table`].
    fn range(&self, k: usize) -> std::ops::Range<usize> {
        self.table.offsets[k] as usize..self.table.offsets[k + 1] as usize
    }

    /// Writes the rows into `t`: in place where every row keeps its length, else `t` with
    /// the rows replaced and the runs of other rows between them copied.
    fn apply(&self, t: &mut StencilTable<W>) {
        let old = |r: u32| t.offsets[r as usize] as usize..t.offsets[r as usize + 1] as usize;
        if (self.rows.iter().enumerate()).all(|(k, &r)| old(r).len() == self.range(k).len()) {
            for (k, &r) in self.rows.iter().enumerate() {
                let (a, b) = (old(r), self.range(k));
                t.indices[a.clone()].copy_from_slice(&self.table.indices[b.clone()]);
                t.weights[a].copy_from_slice(&self.table.weights[b]);
            }
            return;
        }
        let mut out = StencilTable {
            offsets: Vec::with_capacity(t.offsets.len()),
            indices: Vec::with_capacity(t.indices.len() + self.table.indices.len()),
            weights: Vec::with_capacity(t.weights.len() + self.table.indices.len()),
            num_inputs: t.num_inputs,
        };
        out.offsets.push(0);
        let n = t.num_rows();
        let (mut r, mut k) = (0, 0);
        while r < n {
            if self.rows.get(k).is_some_and(|&d| d as usize == r) {
                let b = self.range(k);
                out.indices
                    .extend_from_slice(&self.table.indices[b.clone()]);
                out.weights.extend_from_slice(&self.table.weights[b]);
                out.offsets.push(out.indices.len() as u32);
                (k, r) = (k + 1, r + 1);
                continue;
            }
            let start = r;
            r = self.rows.get(k).map_or(n, |&d| d as usize);
            let (a, b) = (t.offsets[start] as usize, t.offsets[r] as usize);
            let shift = out.indices.len() as i64 - a as i64;
            out.indices.extend_from_slice(&t.indices[a..b]);
            out.weights.extend_from_slice(&t.weights[a..b]);
            out.offsets.extend(
                t.offsets[start + 1..=r]
                    .iter()
                    .map(|&o| (o as i64 + shift) as u32),
            );
        }
        *t = out;
    }
}

#[cfg(test)]
mod tests {
    use super::{unique, Bits};

    /// `unique` keeps each value once, where it first occurs, and `Bits` lists a set in
    /// increasing order: both against sorting and deduplicating, on values across word
    /// boundaries (0, 63, 64, the last).
    #[test]
    fn unique_and_bits_match_sort_and_dedup() {
        let n = 200usize;
        let ids: Vec<u32> = (0..500u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 7) % n as u32)
            .chain([0, 63, 64, 199, 63])
            .collect();
        let mut want = ids.clone();
        want.sort_unstable();
        want.dedup();
        let got = unique(ids.iter().copied(), n);
        let mut sorted = got.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, want);
        let first: Vec<u32> = ids
            .iter()
            .enumerate()
            .filter(|&(i, x)| !ids[..i].contains(x))
            .map(|(_, &x)| x)
            .collect();
        assert_eq!(got, first);
        let b = Bits::of(ids.iter().copied(), n);
        let listed: Vec<u32> = b.iter().map(|i| i as u32).collect();
        assert_eq!(listed, want);
        assert!((0..n as u32).all(|i| b.get(i) == want.contains(&i)));
    }
}
