//! Crease edits of an uploaded patch table ([`GpuLimit::apply_edit`]): after
//! [`subsurf::limit::PatchTable::set_sharpness`] updated the table in place (its isolation
//! structure kept), only what the edit changed is written: the per-patch words that differ
//! (type, parameter, sharpness), in contiguous runs of `queue.write_buffer`, and the stencils
//! of the refinement levels whose rows changed. The patch map, control indices, end-cap
//! stencils, point array and every sample set stay as they are.

use super::{GpuLimit, Tables};
use crate::cpu::limit_eval::LimitTables;
use crate::error::{GpuError, Result};
use crate::refine::GpuRefiner;
use crate::GpuContext;
use subsurf::limit::PatchTable;
use subsurf::refine::LevelStencils;

/// What [`GpuLimit::apply_edit`] wrote.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EditUpload {
    /// Refinement levels whose stencils were uploaded again.
    pub levels: usize,
    /// Per-patch words written (changed ones, and unchanged ones between close changes).
    pub patch_words: usize,
    /// `write_buffer` calls for them.
    pub writes: usize,
    /// Bytes written in all.
    pub bytes: u64,
}

/// What an upload keeps of a table to tell what an edit changed.
#[derive(Debug, Clone, Default)]
pub(super) struct Uploaded {
    /// A fingerprint of each level's stencils.
    levels: Vec<u64>,
    /// The per-patch words as uploaded.
    patch_info: Vec<u32>,
    /// A fingerprint of what an edit must keep: patch map, control indices, end caps.
    fixed: u64,
}

/// A 64-bit fingerprint of word slices, each prefixed by its length: a multiply-xorshift
/// chain over the words, a few cycles per 8 bytes (the standard library's SipHash, fed weight
/// by weight, took 70% of an edit's host time). It only tells an edit's changes from what was
/// uploaded, as any 64-bit fingerprint does (not cryptographic).
fn fingerprint(parts: &[&[u32]]) -> u64 {
    let mut h: u64 = 0x243F_6A88_85A3_08D3;
    let mut mix = |w: u64| {
        h = (h ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h ^= h >> 29;
    };
    for p in parts {
        mix(p.len() as u64);
        let mut pairs = p.chunks_exact(2);
        for c in &mut pairs {
            mix(u64::from(c[0]) | u64::from(c[1]) << 32);
        }
        if let [last] = pairs.remainder() {
            mix(u64::from(*last));
        }
    }
    h
}

fn level_print(s: &LevelStencils) -> u64 {
    let mut parts: Vec<&[u32]> = Vec::with_capacity(9);
    for t in [&s.face(), &s.vertex(), &s.edge()] {
        parts.extend([t.offsets(), t.indices(), bytemuck::cast_slice(t.weights())]);
    }
    fingerprint(&parts)
}

fn fixed_print(table: &PatchTable, t: &LimitTables) -> u64 {
    let lp = &table.local_points();
    let mut parts: Vec<&[u32]> = vec![&t.patch_map, &t.cvs, &table.level_offsets()];
    parts.extend(table.level_inputs().iter().map(Vec::as_slice));
    parts.extend([
        lp.offsets(),
        lp.indices(),
        bytemuck::cast_slice(lp.weights()),
    ]);
    fingerprint(&parts)
}

impl Uploaded {
    pub(super) fn new(table: &PatchTable, t: &LimitTables) -> Uploaded {
        Uploaded {
            levels: table.level_stencils().iter().map(level_print).collect(),
            patch_info: t.patch_info.clone(),
            fixed: fixed_print(table, t),
        }
    }
}

/// Unchanged words a run of per-patch words may span.
const GAP: usize = 16;

impl GpuLimit {
    /// Applies a crease edit of the table this was uploaded from: `table` is that table
    /// after [`PatchTable::set_sharpness`] updated it in place. Writes only the per-patch
    /// words that changed and the stencils of the levels that changed; positions are then
    /// refreshed by [`Self::update`] and sample sets re-evaluated by [`Self::eval`], as after
    /// any deformation.
    ///
    /// A table whose structure differs (other patches, control points, levels or end caps:
    /// an edit that rebuilt it) is refused with [`GpuError::BufferMismatch`]; upload it with
    /// [`GpuLimit::new`].
    pub fn apply_edit(&mut self, ctx: &GpuContext, table: &PatchTable) -> Result<EditUpload> {
        let t = LimitTables::new(table);
        if table.level_stencils().len() != self.levels.len()
            || t.patch_info.len() != self.uploaded.patch_info.len()
            || fixed_print(table, &t) != self.uploaded.fixed
        {
            return Err(GpuError::BufferMismatch(
                "the edited table's structure differs from the uploaded one (patches, control \
                 points, levels or end caps): upload it anew"
                    .into(),
            ));
        }
        let mut out = EditUpload::default();
        for (d, s) in table.level_stencils().iter().enumerate() {
            let print = level_print(s);
            if print == self.uploaded.levels[d] {
                continue;
            }
            let inputs = table.level_inputs()[d].len();
            let child = (table.level_offsets()[d + 2] - table.level_offsets()[d + 1]) as usize;
            let refiner = GpuRefiner::from_stencils(
                ctx,
                &[inputs, child],
                std::slice::from_ref(s),
                self.limits,
            )?;
            self.levels[d].1 = refiner;
            self.uploaded.levels[d] = print;
            out.levels += 1;
            out.bytes += s.size_bytes() as u64;
        }
        let old = &self.uploaded.patch_info;
        match &mut self.tables {
            Tables::Whole { patch_info, .. } => {
                let mut w = 0;
                while w < old.len() {
                    if old[w] == t.patch_info[w] {
                        w += 1;
                        continue;
                    }
                    // A run ends after `GAP` unchanged words (fewer, larger writes).
                    let start = w;
                    let mut end = w + 1;
                    while w < old.len() && w < end + GAP {
                        if old[w] != t.patch_info[w] {
                            end = w + 1;
                        }
                        w += 1;
                    }
                    w = end;
                    let run = &t.patch_info[start..end];
                    ctx.queue.write_buffer(
                        patch_info,
                        start as u64 * super::WORD,
                        bytemuck::cast_slice(run),
                    );
                    out.writes += 1;
                    out.patch_words += run.len();
                    out.bytes += run.len() as u64 * super::WORD;
                }
            }
            Tables::Chunked { tables, .. } => {
                // Compacted per chunk of samples from the host copy at each evaluation.
                out.patch_words = old
                    .iter()
                    .zip(&t.patch_info)
                    .filter(|(a, b)| a != b)
                    .count();
                tables.patch_info.clone_from(&t.patch_info);
            }
        }
        self.uploaded.patch_info = t.patch_info;
        Ok(out)
    }
}
