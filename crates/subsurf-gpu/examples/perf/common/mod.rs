//! What the GPU examples share: the mesh path of their command line, medians.

/// The mesh an example reads: its first argument (`args[1]`), or the car.
pub fn mesh_path(args: &[String]) -> &str {
    args.get(1)
        .map(String::as_str)
        .unwrap_or("testdata/shapes/catmark_car.obj")
}

/// The median of `v` (sorted in place; NaN when empty).
pub fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}
