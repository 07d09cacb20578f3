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
//! only allocate); [`empty`] and [`unwritten`], whose builders write every value, also map
//! the table's fresh pages in one call ([`prefault`]). A zero table costs no extra pass on
//! fresh memory (the allocator does not write a large zeroed allocation), but on memory the
//! allocator reuses it is cleared in one serial sweep; tables whose builder writes every value
//! take [`unwritten`] instead.

use std::mem::MaybeUninit;

/// Size of a transparent huge page on the platforms advised (x86-64 and aarch64 with 4 KiB
/// base pages).
const HUGE_PAGE: usize = 2 << 20;

/// Smallest table (in bytes) advised: a smaller one holds no whole huge page.
pub(crate) const ADVISE_MIN: usize = HUGE_PAGE;

/// Smallest table (in bytes) prefaulted ([`prefault`]): 16 pages of 4 KiB.
const PREFAULT_MIN: usize = 64 << 10;

/// Largest part of a table one thread prefaults: larger tables are split across the pool.
const PREFAULT_PART: usize = 256 << 10;

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
    prefault(v.spare_capacity_mut());
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
    prefault(&t);
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

/// Maps the pages wholly inside `v` before its builder writes them, when they are fresh
/// (Linux only; a no-op elsewhere and for tables under [`PREFAULT_MIN`] bytes).
///
/// Every page of a fresh table is faulted in on its first write, one trap per 4 KiB page:
/// about 2.4 µs each on the development machine, most of a cold setup's time (a `loop_pole64`
/// level-5 `Refiner::new` faults in 7,300 pages). `madvise(MADV_POPULATE_WRITE)` maps a range
/// in one call (8 MiB in 3.0 ms instead of 5.0 ms there), split across the thread pool in
/// parts of at most [`PREFAULT_PART`] bytes, as the builders' parallel writes would fault it.
/// Memory the allocator reuses is already mapped, and walking it again would cost about
/// 0.25 µs a page, so a table whose first or last inner page is resident (`mincore`) is left
/// alone. Called after [`advise_huge`], so the advised windows are mapped as huge pages.
/// Returns whether the pages were mapped here (and the kernel accepted every part).
pub(crate) fn prefault<T>(v: &[T]) -> bool {
    let bytes = std::mem::size_of_val(v);
    if bytes < PREFAULT_MIN {
        return false;
    }
    let page = sys::page_size();
    let start = (v.as_ptr() as usize).next_multiple_of(page);
    let end = (v.as_ptr() as usize + bytes) / page * page;
    end > start && !sys::resident(start) && !sys::resident(end - page) && populate(start, end, page)
}

/// Maps the pages `start..end` (page aligned), in parts across the pool; whether the kernel
/// accepted every part.
fn populate(start: usize, end: usize, page: usize) -> bool {
    let len = end - start;
    if len > PREFAULT_PART && rayon::current_num_threads() > 1 {
        let mid = start + len / 2 / page * page;
        let (a, b) = rayon::join(|| populate(start, mid, page), || populate(mid, end, page));
        a && b
    } else {
        sys::populate(start, len)
    }
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

    /// The system's page size (4 KiB where it cannot be read).
    pub(super) fn page_size() -> usize {
        static PAGE: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
        *PAGE.get_or_init(|| {
            // SAFETY: `sysconf` reads a system value and touches no memory of ours.
            let n = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
            usize::try_from(n).ok().filter(|&n| n > 0).unwrap_or(4096)
        })
    }

    /// Whether the page at `addr` (page aligned, inside a live buffer) is mapped.
    pub(super) fn resident(addr: usize) -> bool {
        let mut v = [0u8; 1];
        // SAFETY: `addr` is a page of the caller's live buffer, and `mincore` writes one byte
        // per page of the range asked (one page here) into `v`, which holds one.
        let ok = unsafe { libc::mincore(addr as *mut libc::c_void, page_size(), v.as_mut_ptr()) };
        ok == 0 && v[0] & 1 == 1
    }

    /// `madvise(addr, len, MADV_POPULATE_WRITE)`; whether the kernel accepted it.
    pub(super) fn populate(addr: usize, len: usize) -> bool {
        // SAFETY: `addr..addr + len` is page aligned and lies inside the caller's live
        // buffer, nothing of which has been written or referenced yet. MADV_POPULATE_WRITE
        // maps the range's pages as a write to each would (zero-filled, contents unchanged)
        // and never frees memory, so no value changes and no Rust reference is invalidated.
        // A kernel before 5.14 answers EINVAL, memory pressure ENOMEM: reported as `false`,
        // and the builder's writes then fault the pages in as before.
        unsafe { libc::madvise(addr as *mut libc::c_void, len, libc::MADV_POPULATE_WRITE) == 0 }
    }
}

#[cfg(not(target_os = "linux"))]
mod sys {
    pub(super) fn madvise_huge(_addr: usize, _len: usize) -> bool {
        false
    }
    pub(super) fn page_size() -> usize {
        4096
    }
    pub(super) fn populate(_addr: usize, _len: usize) -> bool {
        false
    }
    pub(super) fn resident(_addr: usize) -> bool {
        true
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

    /// A fresh table is mapped whole by [`prefault`] before anything writes it (where the
    /// kernel has `MADV_POPULATE_WRITE`), on one thread and split across a pool alike; a
    /// table whose pages are mapped already is left alone.
    #[cfg(target_os = "linux")]
    #[test]
    fn fresh_tables_are_mapped_before_their_first_write() {
        let page = sys::page_size();
        let inner = |t: &[MaybeUninit<u64>]| {
            let start = (t.as_ptr() as usize).next_multiple_of(page);
            let end = (t.as_ptr() as usize + std::mem::size_of_val(t)) / page * page;
            (start..end).step_by(page)
        };
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                // 4 MiB: the allocator maps a block this large afresh.
                let mut t: Box<[MaybeUninit<u64>]> = Box::new_uninit_slice(1 << 19);
                if inner(&t).any(sys::resident) {
                    return; // reused memory: nothing to map
                }
                if !prefault(&t) {
                    return; // a kernel before 5.14
                }
                assert!(inner(&t).all(sys::resident), "{threads} threads");
                // Mapped now, so a second call leaves it alone; the table is writable.
                assert!(!prefault(&t));
                for (i, x) in t.iter_mut().enumerate() {
                    x.write(i as u64);
                }
                // SAFETY: every value written just above.
                #[allow(unsafe_code)]
                let t = unsafe { written(t) };
                assert!(t.iter().enumerate().all(|(i, &x)| x == i as u64));
            });
        }
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
