//! What the examples share: the mesh path and numbers of their command line, medians, and a
//! cache eviction. (Each example uses some of them.)
#![allow(dead_code)]

/// The mesh an example reads: its first argument (`args[1]`), or the car.
pub fn mesh_path(args: &[String]) -> &str {
    args.get(1)
        .map(String::as_str)
        .unwrap_or("testdata/shapes/catmark_car.obj")
}

/// Argument `i` parsed, or `default` where it is missing or does not parse.
pub fn arg<T: std::str::FromStr>(args: &[String], i: usize, default: T) -> T {
    args.get(i).and_then(|s| s.parse().ok()).unwrap_or(default)
}

/// The median of `times` (sorted in place; NaN for none).
pub fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
}

/// A 256 MB buffer whose sweep evicts the caches, as a slider's evaluation and drawing do
/// between two edits.
pub struct Sweep(Vec<u64>);

impl Sweep {
    pub fn new() -> Sweep {
        Sweep(vec![0; 32 << 20])
    }

    /// Writes one word per cache line of the buffer.
    pub fn run(&mut self) {
        for (i, x) in self.0.iter_mut().enumerate().step_by(8) {
            *x = x.wrapping_add(i as u64);
        }
        std::hint::black_box(&self.0);
    }
}
