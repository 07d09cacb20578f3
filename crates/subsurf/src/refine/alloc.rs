//! Large refinement tables allocated so that their first touch can map 2 MiB pages.
//!
//! Much of a refinement step's time is the kernel handing out fresh pages: each table is new,
//! and every 4 KiB page is faulted in and zero-filled on its first write. Linux maps
//! transparent huge pages (2 MiB, one fault for 512 small ones) into a region the process has
//! advised with `madvise(MADV_HUGEPAGE)` when the system's policy is `madvise` (a common
//! default, `/sys/kernel/mm/transparent_hugepage/enabled`), and into any region under
//! `always`. A huge page needs a whole, aligned 2 MiB window of one mapping with nothing in it
//! touched yet. A window across two tables never qualifies (the allocator writes a block's
//! header just before its data), so only the whole windows inside one table are advised.
//!
//! [`zeroed`], [`empty`] and [`unwritten`] allocate a table and advise those windows before
//! anything writes them (elsewhere than Linux, or for tables under [`ADVISE_MIN`] bytes, they
//! only allocate). A zero table costs no extra pass on fresh memory (the allocator does not
//! write a large zeroed allocation), but on memory the allocator reuses it is cleared in one
//! serial sweep; tables whose builder writes every value take [`unwritten`] instead.

use std::mem::MaybeUninit;

/// Size of a transparent huge page on the platforms advised (x86-64 and aarch64 with 4 KiB
/// base pages).
const HUGE_PAGE: usize = 2 << 20;

/// Smallest table (in bytes) advised: a smaller one holds no whole huge page.
pub(crate) const ADVISE_MIN: usize = HUGE_PAGE;

/// A table of `len` copies of `zero`, the pages it spans advised for transparent huge pages
/// before first touch where large enough. `zero` is a value of all zero bits (`0`, `0.0`,
/// `false`, arrays of those): the allocator then hands out memory it has not written.
pub(crate) fn zeroed<T: Clone>(len: usize, zero: T) -> Vec<T> {
    let v = vec![zero; len];
    advise_huge(&v);
    v
}

/// An empty table with room for `len` values, advised as [`zeroed`], for a builder that
/// pushes (or `extend`s) every value in order: nothing is written twice.
pub(crate) fn empty<T>(len: usize) -> Vec<T> {
    let mut v = Vec::with_capacity(len);
    advise_huge(v.spare_capacity_mut());
    v
}

/// A table of `len` values for a builder that writes every one exactly once, allocated
/// without writing anything. [`zeroed`]'s zero pass is free only on fresh pages: on memory the
/// allocator reuses (a long-running process, a setup repeated) `calloc` clears it in one
/// serial sweep, 17% of a warm car level-4 `Refiner::new` on the development machine.
/// Advised as [`zeroed`]. In debug builds every value starts as `poison`, so a value that a
/// builder missed reads back as `poison` (an index out of range, a wrong tag) in the tests
/// rather than as undefined memory; [`written`] turns the table into a `Vec`.
pub(crate) fn unwritten<T: Copy>(len: usize, poison: T) -> Box<[MaybeUninit<T>]> {
    let mut t = Box::new_uninit_slice(len);
    advise_huge(&t);
    if cfg!(debug_assertions) {
        for x in t.iter_mut() {
            x.write(poison);
        }
    }
    t
}

/// The table `t` of [`unwritten`] once its builder has written every value.
///
/// # Safety
/// Every element of `t` has been written.
#[allow(unsafe_code)]
pub(crate) unsafe fn written<T>(t: Box<[MaybeUninit<T>]>) -> Vec<T> {
    // SAFETY: every element is initialized (the caller's promise).
    unsafe { t.assume_init() }.into_vec()
}

/// A value a table builder writes once: a plain value, or one of an [`unwritten`] table.
pub(crate) trait Slot<T>: Send {
    fn set(&mut self, x: T);
}

impl<T: Send> Slot<T> for T {
    #[inline(always)]
    fn set(&mut self, x: T) {
        *self = x;
    }
}

impl<T: Send> Slot<T> for MaybeUninit<T> {
    #[inline(always)]
    fn set(&mut self, x: T) {
        self.write(x);
    }
}

/// Writes `src` into the first `src.len()` values of `dst`.
#[inline(always)]
pub(crate) fn put<T: Copy>(dst: &mut [impl Slot<T>], src: &[T]) {
    for (d, &s) in dst[..src.len()].iter_mut().zip(src) {
        d.set(s);
    }
}

/// Writes `x` into every value of `dst` (a row about to be written, so the zeros land in
/// cache lines the row's own writes then find there, rather than in a separate pass over the
/// table) and hands the row back as written values.
#[inline(always)]
#[allow(unsafe_code)]
pub(crate) fn init<T: Copy>(dst: &mut [MaybeUninit<T>], x: T) -> &mut [T] {
    for d in dst.iter_mut() {
        d.write(x);
    }
    // SAFETY: every value of `dst` is written just above, and `MaybeUninit<T>` has the size,
    // alignment and layout of `T`.
    unsafe { &mut *(dst as *mut [MaybeUninit<T>] as *mut [T]) }
}

/// Writes `x` into every value of `dst`, in parallel chunks.
pub(crate) fn fill<T: Copy + Send + Sync>(dst: &mut [MaybeUninit<T>], x: T) {
    use rayon::prelude::*;
    dst.par_chunks_mut(1 << 16).for_each(|c| {
        init(c, x);
    });
}

/// Advises the whole, aligned 2 MiB windows inside `v` for transparent huge pages: Linux
/// only, a no-op elsewhere, for buffers under [`ADVISE_MIN`] bytes and for those that hold no
/// such window. Only pages not yet touched are affected, so call it before the first write.
/// Returns whether a range was advised and accepted.
///
/// A window reaching past either end of `v` never becomes a huge page: the allocator writes
/// its header of the neighbouring block (or of `v`, just before it) into that window before
/// `v` is handed out, and a huge page needs a window with nothing in it touched. Advising
/// only the inner windows skips the system call for every table under 2 MiB (most of a
/// refinement's tables below its last levels), and keeps the kernel from splitting the
/// allocator's mappings at arbitrary pages (each `madvise` of a part of a mapping cuts it).
pub(crate) fn advise_huge<T>(v: &[T]) -> bool {
    let bytes = std::mem::size_of_val(v);
    if bytes < ADVISE_MIN {
        return false;
    }
    let start = v.as_ptr() as usize;
    let first = start.next_multiple_of(HUGE_PAGE);
    let end = (start + bytes) / HUGE_PAGE * HUGE_PAGE;
    if end <= first {
        return false;
    }
    sys::madvise_huge(first, end - first)
}

#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
mod sys {
    /// `madvise(addr, len, MADV_HUGEPAGE)`; whether the kernel accepted it.
    pub(super) fn madvise_huge(addr: usize, len: usize) -> bool {
        // SAFETY: `addr` is 2 MiB aligned and `addr..addr + len` lies inside the caller's live
        // buffer, all mapped. MADV_HUGEPAGE is advice only: it sets how the kernel backs pages of
        // the range not yet touched (and may let the kernel merge small pages later), and never
        // frees memory or changes its contents, so no value, ours or a neighbouring
        // allocation's, changes and no Rust reference is invalidated. A kernel without THP
        // answers EINVAL, reported as `false` and otherwise ignored.
        unsafe { libc::madvise(addr as *mut libc::c_void, len, libc::MADV_HUGEPAGE) == 0 }
    }
}

#[cfg(not(target_os = "linux"))]
mod sys {
    pub(super) fn madvise_huge(_addr: usize, _len: usize) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_tables_are_plain_zeros() {
        let v: Vec<u32> = zeroed(1000, 0u32);
        assert_eq!(v.len(), 1000);
        assert!(v.iter().all(|&x| x == 0));
        assert!(!advise_huge(&v));
    }

    #[test]
    fn large_tables_are_zeros_and_stay_writable() {
        let n = 3 * HUGE_PAGE / 4 + 12345;
        assert!(4 * n >= ADVISE_MIN);
        let mut v: Vec<u32> = zeroed(n, 0u32);
        assert_eq!(v.len(), n);
        assert!(v.iter().all(|&x| x == 0));
        for (i, x) in v.iter_mut().enumerate() {
            *x = i as u32;
        }
        assert!(v.iter().enumerate().all(|(i, &x)| x == i as u32));
        let f: Vec<[f32; 2]> = zeroed(HUGE_PAGE, [0.0f32; 2]);
        assert!(f.iter().all(|x| *x == [0.0, 0.0]));
    }

    /// Where the kernel supports transparent huge pages, advising a large table succeeds, and
    /// the table, and the memory around it, read back what was written before and after.
    #[cfg(target_os = "linux")]
    #[test]
    fn advice_is_accepted_where_thp_exists() {
        if std::fs::metadata("/sys/kernel/mm/transparent_hugepage/enabled").is_err() {
            return;
        }
        // Neighbours written before the advice, sharing pages with the table.
        let before: Vec<u32> = (0..1000).collect();
        let mut v = unwritten(3 * HUGE_PAGE / 4 + 1, 0u32);
        fill(&mut v, 5);
        // SAFETY: `fill` wrote every value.
        #[allow(unsafe_code)]
        let mut v = unsafe { written(v) };
        let after: Vec<u32> = (0..1000).rev().collect();
        let mut w = vec![0u8; 3 * HUGE_PAGE];
        assert!(advise_huge(&w));
        assert!(v.iter().all(|&x| x == 5));
        w.iter_mut().step_by(4096).for_each(|x| *x = 7);
        assert_eq!(w.iter().filter(|&&x| x == 7).count(), 3 * HUGE_PAGE / 4096);
        v[12345] = 6;
        assert_eq!(v.iter().filter(|&&x| x == 6).count(), 1);
        assert!(before.iter().enumerate().all(|(i, &x)| x == i as u32));
        assert!(after.iter().rev().enumerate().all(|(i, &x)| x == i as u32));
    }
}
