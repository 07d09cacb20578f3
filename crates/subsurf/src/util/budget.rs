//! The memory budget: an allocation-heavy construction is estimated before anything is
//! allocated, and one that would not fit is refused with [`MeshError::TooLarge`] and its true
//! estimate instead of failing an allocation (or being killed for memory).
//!
//! The limit is 80% of the memory the system reports available (`MemAvailable` in
//! `/proc/meminfo`), read only once an estimate reaches 64 MiB; without that file there is
//! none. The estimates themselves live with what they estimate (a refinement level, a patch
//! table level, a tessellation).

use crate::error::MeshError;

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
    used: u64,
    /// The most bytes allowed (for [`Budget::of_available_memory`], read once the total
    /// reaches 64 MiB; no limit until then).
    limit: u64,
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

    /// Bytes counted so far.
    pub fn used(&self) -> u64 {
        self.used
    }

    /// The most bytes allowed (`u64::MAX` while the available memory is still unread).
    pub fn limit(&self) -> u64 {
        self.limit
    }

    /// Counts `bytes` more, or refuses them (`what` names the step) when the total would pass
    /// the limit; nothing is counted on a refusal.
    pub fn add(&mut self, bytes: u64, what: impl FnOnce() -> String) -> Result<(), MeshError> {
        let bytes = self.used.saturating_add(bytes);
        if self.unread && bytes >= CHECKED_BYTES {
            (self.limit, self.unread) = (memory_limit(bytes), false);
        }
        if bytes > self.limit {
            return Err(too_large(what(), bytes as f64, self.limit));
        }
        self.used = bytes;
        Ok(())
    }
}

/// Refuses a single allocation-heavy step (`what` names it) estimated at `bytes` when it would
/// pass the memory limit, with the estimate; `bytes` is a float so that a size past 2^64 is
/// reported as it is.
pub fn check(bytes: f64, what: impl FnOnce() -> String) -> Result<(), MeshError> {
    let limit = memory_limit(saturate(bytes));
    if bytes > limit as f64 {
        return Err(too_large(what(), bytes, limit));
    }
    Ok(())
}

/// The refusal of `what`, estimated at `bytes`, against a memory limit of `limit` bytes.
pub(crate) fn too_large(what: String, bytes: f64, limit: u64) -> MeshError {
    MeshError::TooLarge {
        what,
        bytes: saturate(bytes),
        human: human(bytes),
        limit_human: format!("{} (80% of available memory)", human(limit as f64)),
    }
}

/// Memory available for new allocations, from `/proc/meminfo` where present.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// `bytes` in binary units. Takes a float so that an estimate past `u64::MAX` is shown as
/// it is (with "more than 2^64 bytes") instead of wrapping or saturating.
pub fn human(bytes: f64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB", "ZiB", "YiB"];
    let mut v = bytes;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < units.len() {
        v /= 1024.0;
        u += 1;
    }
    let shown = if v >= 1e4 {
        format!("{v:.3e} {}", units[u])
    } else {
        format!("{v:.1} {}", units[u])
    };
    if bytes >= 18_446_744_073_709_551_616.0 {
        format!("{shown}, more than 2^64 bytes")
    } else {
        format!("{shown}, {} bytes", bytes as u64)
    }
}

/// A count that may pass `u64::MAX` as a message shows it: whole below 10^15, else in
/// scientific notation (`1.845e19`), never saturated.
pub fn count(n: f64) -> String {
    if n < 1e15 {
        format!("{}", n.round() as u64)
    } else {
        format!("{n:.3e}")
    }
}

/// An estimate in bytes as stored in [`MeshError::TooLarge`]: the float rounded, saturated at
/// `u64::MAX` (the message carries the true size through [`human`]).
pub(crate) fn saturate(bytes: f64) -> u64 {
    if bytes >= u64::MAX as f64 {
        u64::MAX
    } else {
        bytes as u64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_past_2_64_are_not_wrapped() {
        assert_eq!(human(1536.0), "1.5 KiB, 1536 bytes");
        // 2^70 bytes is 1 ZiB: shown as such, not as 16 EiB or a wrapped count.
        let z = human(2f64.powi(70));
        assert!(
            z.starts_with("1.0 ZiB") && z.ends_with("more than 2^64 bytes"),
            "{z}"
        );
        // Past the last unit the mantissa grows in scientific notation.
        let big = human(2f64.powi(100));
        assert!(big.starts_with("1.049e6 YiB"), "{big}");
        assert_eq!(saturate(2f64.powi(100)), u64::MAX);
        assert_eq!(saturate(1e6), 1_000_000);
        assert_eq!(count(1234.0), "1234");
        assert_eq!(count(2f64.powi(80)), "1.209e24");
    }
}
