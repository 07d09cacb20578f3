//! Arbitrary bytes (as lossy UTF-8) through the OBJ reader and, when they parse, through
//! `Topology::new`. Properties: nothing panics; a read error is a parse error naming a line of
//! the input; a mesh that reads back from its own OBJ output is the same mesh.
#![no_main]

use libfuzzer_sys::fuzz_target;
use subsurf::io::obj;
use subsurf::Topology;
use subsurf::Error;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match obj::read(&text) {
        Ok(mesh) => {
            let mut out = Vec::new();
            obj::write(&mesh, &mut out).expect("writing a mesh that was read");
            let again = obj::read(std::str::from_utf8(&out).expect("UTF-8 output"))
                .expect("reading our own output");
            assert_eq!(again, mesh, "read -> write -> read changed the mesh");
            if let Ok(t) = Topology::new(&mesh) {
                if let Err(e) = t.check_consistency() {
                    panic!("inconsistent topology: {e}");
                }
            }
        }
        Err(Error::Parse { line, .. }) => {
            assert!(
                line >= 1 && line <= text.lines().count().max(1),
                "line {line} out of the input"
            );
        }
        Err(e) => panic!("non-parse error from the reader: {e}"),
    }
});
