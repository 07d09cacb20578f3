//! What a sharpness update of a kept topology changed, at the cost of what it wrote: a writer
//! reads an element's values just before it writes them and notes the element in [`Moved`]
//! when the new values differ, instead of copying a level's arrays before the update and
//! comparing them whole after. An element written more than once is noted if any write
//! changed it (at worst more work downstream, never a change missed).
//!
//! Used by crease edits of a patch table ([`crate::limit::PatchTable::set_sharpness`]).

use super::resharpen::Bits;
use crate::topology::Topology;
use crate::SHARPNESS_INFINITE;

/// The values of an edge a sharpness update may change: sharpness and tags.
pub(crate) type EdgeValues = (f32, u8);
/// The values of a vertex a sharpness update may change: sharpness, tags and rule.
pub(crate) type VertexValues = (f32, u16, u8);

/// Edge `e`'s values in `t`.
pub(crate) fn edge_values(t: &Topology, e: usize) -> EdgeValues {
    (t.edge_sharpness[e], t.edge_tags[e])
}

/// Vertex `v`'s values in `t`.
pub(crate) fn vertex_values(t: &Topology, v: usize) -> VertexValues {
    (t.vert_sharpness[v], t.vert_tags[v], t.vert_rule[v])
}

/// What changed in a topology.
pub(crate) struct Moved {
    /// The vertices that changed themselves (sharpness, tags or rule) or by an edge of
    /// theirs (sharpness or tags), each once.
    pub list: Vec<u32>,
    /// The same vertices, as a set.
    pub vertices: Bits,
    /// Vertices whose sharpness or rule changed.
    pub sharp_or_rule: Bits,
    /// Vertices whose rule changed.
    pub rule: Bits,
    /// Vertices that became or stopped being infinitely sharp.
    pub inf: Bits,
    /// Edges whose sharpness changed.
    pub edge_sharp: Bits,
}

impl Moved {
    /// Nothing changed yet in `t`.
    pub(crate) fn new(t: &Topology) -> Moved {
        let (nv, ne) = (t.num_vertices(), t.num_edges());
        Moved {
            list: Vec::new(),
            vertices: Bits::new(nv),
            sharp_or_rule: Bits::new(nv),
            rule: Bits::new(nv),
            inf: Bits::new(nv),
            edge_sharp: Bits::new(ne),
        }
    }

    /// What differs between `old` and `new`, two states of one topology; `None` when
    /// nothing does.
    pub(crate) fn between(old: &Topology, new: &Topology) -> Option<Moved> {
        let mut m = Moved::new(new);
        (0..new.num_edges()).for_each(|e| m.edge(new, e, edge_values(old, e)));
        (0..new.num_vertices()).for_each(|v| m.vertex(new, v, vertex_values(old, v)));
        m.any()
    }

    /// `None` when nothing changed.
    pub(crate) fn any(self) -> Option<Moved> {
        (!self.list.is_empty()).then_some(self)
    }

    fn mark(&mut self, v: u32) {
        if !self.vertices.get(v) {
            self.vertices.set(v);
            self.list.push(v);
        }
    }

    /// Notes edge `e` of `t` if its values differ from `old`, its values before a write.
    pub(crate) fn edge(&mut self, t: &Topology, e: usize, (s, tags): EdgeValues) {
        let sharp = s.to_bits() != t.edge_sharpness[e].to_bits();
        if sharp {
            self.edge_sharp.set(e as u32);
        }
        if sharp || tags != t.edge_tags[e] {
            t.edge_verts[e].into_iter().for_each(|v| self.mark(v));
        }
    }

    /// Notes vertex `v` of `t` if its values differ from `old`, its values before a write.
    pub(crate) fn vertex(&mut self, t: &Topology, v: usize, (s, tags, rule): VertexValues) {
        let now = t.vert_sharpness[v];
        let sharp = s.to_bits() != now.to_bits();
        let rule = rule != t.vert_rule[v];
        let id = v as u32;
        if sharp || rule {
            self.sharp_or_rule.set(id);
        }
        if rule {
            self.rule.set(id);
        }
        let inf = |s: f32| s >= SHARPNESS_INFINITE;
        if inf(s) != inf(now) {
            self.inf.set(id);
        }
        if sharp || rule || tags != t.vert_tags[v] {
            self.mark(id);
        }
    }
}
