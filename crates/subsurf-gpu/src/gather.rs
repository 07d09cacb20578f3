//! Stencil rows whose source exceeds one storage binding: gathered inputs.
//!
//! A chunk of stencil rows reads a few hundred inputs scattered over a source buffer (for
//! `refine_level`, the parent level and the child's face points). Its distinct inputs are
//! gathered, window by window of the source (each window an aligned binding of at most the
//! limit), into a scratch buffer by unit-weight dispatches (`1.0 · x` is exact); the chunk's
//! rows then read the scratch with their inputs renumbered. Each row sums the same weights
//! times the same values in the same order as an unsplit dispatch, so the results are the
//! same bits. Used by `GpuRefiner` (levels over one binding) and `StencilKernel` (sources
//! over one binding).

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
/// vertex `k`, otherwise child vertex `k`), with windows of `window` vertices; each gather's
/// first scratch row is a multiple of `pad` (for destinations bound at aligned offsets).
pub(crate) fn plan_gather(
    indices: &[u32],
    num_parent: usize,
    window: usize,
    pad: usize,
) -> GatherPlan {
    let mut distinct = indices.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    let key = |k: u32| {
        let k = k as usize;
        (k >= num_parent, k / window)
    };
    let mut gathers: Vec<Gather> = Vec::new();
    // Scratch row of each distinct input.
    let mut row = Vec::with_capacity(distinct.len());
    let mut next = 0usize;
    for &k in &distinct {
        let (child, w) = key(k);
        let rel = (k as usize - w * window) as u32;
        match gathers.last_mut() {
            Some(g) if g.child == child && g.window == w => g.rel.push(rel),
            _ => {
                next = next.div_ceil(pad) * pad;
                gathers.push(Gather {
                    child,
                    window: w,
                    first: next as u32,
                    rel: vec![rel],
                })
            }
        }
        row.push(next as u32);
        next += 1;
    }
    let local = indices
        .iter()
        .map(|k| row[distinct.binary_search(k).expect("every index is listed")])
        .collect();
    GatherPlan {
        gathers,
        local,
        inputs: next,
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
        let plan = plan_gather(&indices, np, window, 1);
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
        // Padded: every gather starts at a multiple of the padding, rows still unique.
        let padded = plan_gather(&indices, np, window, 64);
        assert!(padded.gathers.iter().all(|g| g.first % 64 == 0));
        assert_eq!(padded.gathers.len(), plan.gathers.len());
        let mut scratch = vec![u32::MAX; padded.inputs];
        for g in &padded.gathers {
            for (i, &r) in g.rel.iter().enumerate() {
                assert_eq!(scratch[g.first as usize + i], u32::MAX);
                scratch[g.first as usize + i] = source(g.child, g.window, r);
            }
        }
        for (&k, &l) in indices.iter().zip(&padded.local) {
            assert_eq!(scratch[l as usize], k);
        }
    }
}
