//! Parallel filling of flat tables: a table whose rows have known starts is cut into disjoint
//! slices of whole rows, which threads then fill independently (safe `split_at_mut`).

use std::ops::Range;

/// Rows per parallel chunk for a table of `rows` rows.
pub(crate) fn chunk_rows(rows: usize) -> usize {
    let threads = rayon::current_num_threads().max(1);
    rows.div_ceil(threads * 4).max(4096)
}

/// Chunk boundaries `0 = b_0 < b_1 < … < b_k = rows`.
pub(crate) fn bounds(rows: usize) -> Vec<usize> {
    let chunk = chunk_rows(rows);
    let mut b: Vec<usize> = (0..rows).step_by(chunk).collect();
    b.push(rows);
    b
}

/// The row ranges between consecutive boundaries.
pub(crate) fn ranges(bounds: &[usize]) -> Vec<Range<usize>> {
    bounds.windows(2).map(|w| w[0]..w[1]).collect()
}

/// Cuts `data` into one slice per chunk of rows; row `r` starts at `start(r) - start(0)`.
pub(crate) fn split<'a, T>(
    data: &'a mut [T],
    bounds: &[usize],
    start: impl Fn(usize) -> usize,
) -> Vec<&'a mut [T]> {
    let mut rest = data;
    let mut out = Vec::with_capacity(bounds.len());
    for w in bounds.windows(2) {
        let (a, b) = std::mem::take(&mut rest).split_at_mut(start(w[1]) - start(w[0]));
        out.push(a);
        rest = b;
    }
    out
}

/// As [`split`], for a table the chunks must cover whole (one that is written value by value,
/// [`super::alloc::unwritten`]): panics unless the last row ends at `data.len()`.
pub(crate) fn split_exact<'a, T>(
    data: &'a mut [T],
    bounds: &[usize],
    start: impl Fn(usize) -> usize,
) -> Vec<&'a mut [T]> {
    let (first, last) = (bounds[0], bounds[bounds.len() - 1]);
    assert_eq!(
        start(last) - start(first),
        data.len(),
        "chunks cover the whole table"
    );
    split(data, bounds, start)
}
