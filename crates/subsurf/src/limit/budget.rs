//! The memory budget of a sparse construction: each level is estimated from the sub-mesh it
//! refines, before it is allocated, and a construction whose levels would not fit is refused
//! with [`MeshError::TooLarge`] instead of failing an allocation.
//!
//! One refinement step of a sub-mesh with `V` vertices, `E` edges, `F` faces and `C` face
//! corners makes `F' = C` quads, `E' = 2 E + C` edges and `V' = V + E + F` vertices. Their
//! bytes are counted from the arrays that hold them:
//!
//! ```text
//! topology   61 F' + 37 E' + 14 V'   face/edge/vertex relations, sharpness, tags, rules
//! stencils   60 V'                   about 7 (index, weight) entries per row, offsets
//! flags       5 F' +  1 E' +  6 V'   feature tags, exactness, refinement marks, child links
//! patches    90 F'                   at most one patch per face: 16 indices, parameters
//! ```
//!
//! The limit is 80% of the memory the system reports available (`MemAvailable` in
//! `/proc/meminfo`), the one [`crate::refine::Refiner::new`] and the tessellations apply, read
//! only once an estimate reaches 64 MiB; without that file there is none.

use crate::error::MeshError;
use crate::topology::Topology;

/// Estimates below this many bytes are not checked against the available memory: reading it
/// (`/proc/meminfo`) takes 20–30 µs here, a tenth of a small mesh's whole refinement, and every
/// construction, refinement and tessellation would pay it.
const CHECKED_BYTES: u64 = 64 << 20;

/// The most bytes a construction estimated at `bytes` may take: 80% of the available memory,
/// read only for estimates of 64 MiB and more (no limit below, and none where the system does
/// not report it).
pub(crate) fn memory_limit(bytes: u64) -> u64 {
    if bytes < CHECKED_BYTES {
        return u64::MAX;
    }
    available_memory().map_or(u64::MAX, |m| m / 10 * 8)
}

/// The running total of a construction's levels against a limit.
#[derive(Debug, Clone)]
pub struct Budget {
    /// Bytes of the levels counted so far.
    pub used: u64,
    /// The most bytes allowed (for [`Budget::of_available_memory`], read once the total
    /// reaches 64 MiB; no limit until then).
    pub limit: u64,
    /// Whether `limit` is still to be read from the available memory.
    unread: bool,
}

impl Budget {
    /// A budget of 80% of the available memory, read once the total reaches 64 MiB.
    pub fn of_available_memory() -> Budget {
        Budget {
            used: 0,
            limit: u64::MAX,
            unread: true,
        }
    }

    /// A budget of `limit` bytes.
    pub fn with_limit(limit: u64) -> Budget {
        Budget {
            used: 0,
            limit,
            unread: false,
        }
    }

    /// Counts the level that refining `sub` makes, or refuses it (`what` names the step)
    /// when the total would pass the limit.
    pub fn refine(
        &mut self,
        sub: &Topology,
        what: impl FnOnce() -> String,
    ) -> Result<(), MeshError> {
        let bytes = self.used.saturating_add(child_level_bytes(sub));
        if self.unread && bytes >= CHECKED_BYTES {
            (self.limit, self.unread) = (memory_limit(bytes), false);
        }
        if bytes > self.limit {
            return Err(MeshError::TooLarge {
                what: what(),
                bytes,
                human: human(bytes),
                limit_human: format!("{} (80% of available memory)", human(self.limit)),
            });
        }
        self.used = bytes;
        Ok(())
    }
}

/// Estimated bytes of the level one refinement step of `sub` makes (module documentation).
pub fn child_level_bytes(sub: &Topology) -> u64 {
    let c = sub.num_corners() as u64;
    let (v, e, f) = (
        sub.num_vertices() as u64,
        sub.num_edges() as u64,
        sub.num_faces() as u64,
    );
    let (f1, e1, v1) = (c, 2 * e + c, v + e + f);
    (61 + 5 + 90) * f1 + (37 + 1) * e1 + (14 + 60 + 6) * v1
}

/// Memory available for new allocations, from `/proc/meminfo` where present.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// `bytes` in binary units.
pub fn human(bytes: u64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = bytes as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < units.len() {
        v /= 1024.0;
        u += 1;
    }
    format!("{v:.1} {}", units[u])
}
