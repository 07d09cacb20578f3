//! What the examples share: the mesh path of their command line.

/// The mesh an example reads: its first argument (`args[1]`), or the car.
pub fn mesh_path(args: &[String]) -> &str {
    args.get(1)
        .map(String::as_str)
        .unwrap_or("testdata/shapes/catmark_car.obj")
}
