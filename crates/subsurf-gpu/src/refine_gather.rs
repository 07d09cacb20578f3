//! Refinement of a level whose vertex buffers exceed one storage binding.
//!
//! A chunk of a level table's rows reads a few hundred inputs scattered over the parent
//! level and the child's face points. Its distinct inputs are gathered, window by window of
//! the level buffers (each window an aligned binding of at most the limit), into a scratch
//! buffer by unit-weight `refine_level` dispatches (`1.0 · x` is exact); the chunk's rows
//! then read the scratch with their inputs renumbered, and write the child level through a
//! window starting at the aligned vertex at or before their first row. Each row sums the
//! same weights times the same values in the same order as the unsplit dispatch, so the
//! results are the same bits.

/// One gather of a chunk: `rel[i]` of `window` (of the parent level, or of the child level
/// when `child`) to scratch row `first + i`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Gather {
    pub child: bool,
    pub window: usize,
    pub first: u32,
    pub rel: Vec<u32>,
}

/// The gathers of a chunk of table rows and its indices renumbered into the scratch.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct GatherPlan {
    pub gathers: Vec<Gather>,
    pub local: Vec<u32>,
    /// Scratch rows used.
    pub inputs: usize,
}

/// Plans the gathers of a chunk whose table reads `indices` (input `k < num_parent`: parent
/// vertex `k`, otherwise child vertex `k`), with windows of `window` vertices.
pub(crate) fn plan_gather(indices: &[u32], num_parent: usize, window: usize) -> GatherPlan {
    let mut distinct = indices.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    let local = indices
        .iter()
        .map(|k| distinct.binary_search(k).expect("every index is listed") as u32)
        .collect();
    let key = |k: u32| {
        let k = k as usize;
        (k >= num_parent, k / window)
    };
    let mut gathers: Vec<Gather> = Vec::new();
    for (i, &k) in distinct.iter().enumerate() {
        let (child, w) = key(k);
        let rel = (k as usize - w * window) as u32;
        match gathers.last_mut() {
            Some(g) if g.child == child && g.window == w => g.rel.push(rel),
            _ => gathers.push(Gather {
                child,
                window: w,
                first: i as u32,
                rel: vec![rel],
            }),
        }
    }
    GatherPlan {
        gathers,
        local,
        inputs: distinct.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gathering by the plan and reading through the renumbered indices gives back every
    /// input, and no gather crosses a window or a level.
    #[test]
    fn gathers_reproduce_every_input() {
        let (np, window) = (1000usize, 128usize);
        let indices: Vec<u32> = (0..2500u32).map(|i| (i * 7919 + 13) % 1900).collect();
        let plan = plan_gather(&indices, np, window);
        let source = |child: bool, w: usize, r: u32| {
            let k = w * window + r as usize;
            assert!(r < window as u32);
            assert_eq!(child, k >= np);
            k as u32
        };
        let mut scratch = vec![u32::MAX; plan.inputs];
        for g in &plan.gathers {
            for (i, &r) in g.rel.iter().enumerate() {
                scratch[g.first as usize + i] = source(g.child, g.window, r);
            }
        }
        for (&k, &l) in indices.iter().zip(&plan.local) {
            assert_eq!(scratch[l as usize], k);
        }
        assert!(plan.inputs < indices.len() && plan.gathers.len() <= 1900 / window + 2);
    }
}
