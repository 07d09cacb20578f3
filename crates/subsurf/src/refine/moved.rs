//! What a sharpness update of a kept topology changed, at the cost of what it wrote: the
//! values of each element are recorded just before it is first written ([`Before`]) and
//! compared with its values afterwards ([`Moved`]), instead of copying a level's arrays
//! before the update and comparing them whole after.
//!
//! Used by crease edits of a patch table ([`crate::limit::PatchTable::set_sharpness`]).

use super::resharpen::Bits;
use crate::topology::Topology;
use crate::SHARPNESS_INFINITE;

/// The values of elements of one topology before they were written (each element once).
pub(crate) struct Before {
    /// `(edge, sharpness, tags)`.
    edges: Vec<(u32, f32, u8)>,
    /// `(vertex, sharpness, tags, rule)`.
    verts: Vec<(u32, f32, u16, u8)>,
    seen_edges: Bits,
    seen_verts: Bits,
}

/// What changed between the recorded values and the current ones; only recorded elements
/// are compared (the others were not written).
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

impl Before {
    /// Nothing recorded yet, for writes to `t`.
    pub(crate) fn new(t: &Topology) -> Before {
        Before {
            edges: Vec::new(),
            verts: Vec::new(),
            seen_edges: Bits::new(t.num_edges()),
            seen_verts: Bits::new(t.num_vertices()),
        }
    }

    /// Every element of `t` (a whole topology about to be replaced).
    pub(crate) fn all(t: &Topology) -> Before {
        let mut b = Before::new(t);
        (0..t.num_edges()).for_each(|e| b.edge(t, e));
        (0..t.num_vertices()).for_each(|v| b.vertex(t, v));
        b
    }

    /// Records edge `e` of `t`, unless it already is.
    pub(crate) fn edge(&mut self, t: &Topology, e: usize) {
        if !self.seen_edges.get(e as u32) {
            self.seen_edges.set(e as u32);
            self.edges
                .push((e as u32, t.edge_sharpness[e], t.edge_tags[e]));
        }
    }

    /// Records vertex `v` of `t`, unless it already is.
    pub(crate) fn vertex(&mut self, t: &Topology, v: usize) {
        if !self.seen_verts.get(v as u32) {
            self.seen_verts.set(v as u32);
            self.verts.push((
                v as u32,
                t.vert_sharpness[v],
                t.vert_tags[v],
                t.vert_rule[v],
            ));
        }
    }

    /// What changed in `t` since the values were recorded; `None` when nothing did.
    pub(crate) fn moved(&self, t: &Topology) -> Option<Moved> {
        let (nv, ne) = (t.num_vertices(), t.num_edges());
        let mut m = Moved {
            list: Vec::new(),
            vertices: Bits::new(nv),
            sharp_or_rule: Bits::new(nv),
            rule: Bits::new(nv),
            inf: Bits::new(nv),
            edge_sharp: Bits::new(ne),
        };
        let mark = |m: &mut Moved, v: u32| {
            if !m.vertices.get(v) {
                m.vertices.set(v);
                m.list.push(v);
            }
        };
        for &(e, s, tags) in &self.edges {
            let i = e as usize;
            let sharp = s.to_bits() != t.edge_sharpness[i].to_bits();
            if sharp {
                m.edge_sharp.set(e);
            }
            if sharp || tags != t.edge_tags[i] {
                t.edge_verts[i].into_iter().for_each(|v| mark(&mut m, v));
            }
        }
        let inf = |s: f32| s >= SHARPNESS_INFINITE;
        for &(v, s, tags, rule) in &self.verts {
            let i = v as usize;
            let now = t.vert_sharpness[i];
            let sharp = s.to_bits() != now.to_bits();
            let rule = rule != t.vert_rule[i];
            if sharp || rule {
                m.sharp_or_rule.set(v);
            }
            if rule {
                m.rule.set(v);
            }
            if inf(s) != inf(now) {
                m.inf.set(v);
            }
            if sharp || rule || tags != t.vert_tags[i] {
                mark(&mut m, v);
            }
        }
        (!m.list.is_empty()).then_some(m)
    }
}
