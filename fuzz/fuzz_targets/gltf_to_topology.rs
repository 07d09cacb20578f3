//! Arbitrary bytes through the glTF reader (as a `.glb` when they start with `glTF`, else as
//! `.gltf` JSON, no folder for external buffers) and, when they parse, through
//! `Topology::new`. Properties: nothing panics; a read error is `Error::Gltf` or
//! `Error::Unsupported`; an accepted file gives triangles with in-range indices.
#![no_main]

use libfuzzer_sys::fuzz_target;
use subsurf::io::gltf::{read, ReadOptions};
use subsurf::Topology;
use subsurf::Error;

fuzz_target!(|data: &[u8]| {
    for flatten in [false, true] {
        match read(data, None, &ReadOptions { flatten }) {
            Ok(r) => {
                let n = r.mesh.positions.len() as u32;
                assert!(r.mesh.face_counts.iter().all(|&c| c == 3));
                assert!(r.mesh.face_indices.iter().all(|&v| v < n));
                let _ = Topology::new(&r.mesh);
            }
            Err(Error::Gltf { .. } | Error::Unsupported(_)) => {}
            Err(e) => panic!("unexpected error kind from the reader: {e}"),
        }
    }
});
