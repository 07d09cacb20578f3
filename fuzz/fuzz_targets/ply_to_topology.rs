//! Arbitrary bytes through the PLY reader and, when they parse, through `Topology::new`.
//! Properties: nothing panics; a read error is a parse error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use subsurf::io::ply;
use subsurf::Topology;
use subsurf::Error;

fuzz_target!(|data: &[u8]| {
    match ply::read(data) {
        Ok(mesh) => {
            let _ = Topology::new(&mesh);
        }
        Err(Error::Parse { .. }) => {}
        Err(e) => panic!("non-parse error from the reader: {e}"),
    }
});
