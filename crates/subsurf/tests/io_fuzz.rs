//! A cheap built-in fuzz loop (fixed seed) over mutated regression shapes, so that every test
//! run exercises the readers' no-panic property; `fuzz/` holds the libFuzzer targets that check
//! the same properties at length.

mod common;

use subsurf::io::{obj, ply};
use subsurf::Error;
use subsurf::Topology;

/// Marsaglia's xorshift64 (2003): a tiny deterministic generator.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Tokens that steer mutations towards the readers' edge cases.
const DICTIONARY: &[&[u8]] = &[
    b"-1",
    b"0",
    b"/",
    b"//",
    b"nan",
    b"inf",
    b"1e40",
    b"\\\n",
    b"\n",
    b"\r\n",
    b" ",
    b"#",
    b"t crease 2/1/0 0 1 ",
    b"t crease 4/1/0 0 1 2 3 ",
    b"t hole 1/0/0 ",
    b"t corner 1/1/0 0 ",
    b"t interpolateboundary 1/0/0 ",
    b"f 1 2 3\n",
    b"f -1 -2 -3\n",
    b"f 1/1 2/1 3/1\n",
    b"4294967296",
    b"-9999999999",
    b" 99999 ",
    b"vt 0 0\n",
    b"v 0 0 0\n",
    b"vn 0 0 1\n",
    b"3/",
    b"2/2/",
    b"property list uchar int vertex_indices\n",
    b"element face 1\n",
    b"\xff\xff\xff\xff",
    b"\x00",
];

fn mutate(rng: &mut XorShift, input: &[u8]) -> Vec<u8> {
    let mut data = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(data.len() + 1);
        match rng.below(6) {
            0 if !data.is_empty() => {
                let i = at.min(data.len() - 1);
                data[i] = rng.next() as u8;
            }
            1 => {
                let token = DICTIONARY[rng.below(DICTIONARY.len())];
                data.splice(at..at, token.iter().copied());
            }
            2 => {
                let end = (at + 1 + rng.below(16)).min(data.len());
                data.drain(at..end);
            }
            3 => {
                // Duplicate a chunk somewhere else.
                let end = (at + rng.below(64)).min(data.len());
                let chunk = data[at..end].to_vec();
                let to = rng.below(data.len() + 1);
                data.splice(to..to, chunk);
            }
            4 => data.truncate(at),
            _ => {
                let token = DICTIONARY[rng.below(DICTIONARY.len())];
                let end = (at + token.len()).min(data.len());
                data.splice(at..end, token.iter().copied());
            }
        }
    }
    data
}

/// The properties checked by `fuzz/fuzz_targets/obj_to_topology.rs`.
fn check_obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    match obj::read(&text) {
        Ok(mesh) => {
            let mut out = Vec::new();
            obj::write(&mesh, &mut out).expect("writing a mesh that was read");
            let again = obj::read(std::str::from_utf8(&out).unwrap()).expect("reading our output");
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
                "line {line}"
            );
        }
        Err(e) => panic!("non-parse error from the OBJ reader: {e}"),
    }
}

fn check_ply(data: &[u8]) {
    match ply::read(data) {
        Ok(mesh) => {
            if let Ok(t) = Topology::new(&mesh) {
                if let Err(e) = t.check_consistency() {
                    panic!("inconsistent topology: {e}");
                }
            }
        }
        Err(Error::Parse { .. }) => {}
        Err(e) => panic!("non-parse error from the PLY reader: {e}"),
    }
}

/// Small shapes with tags, UVs, n-gons and non-manifold parts.
const SEEDS: &[&str] = &[
    "catmark_cube_creases1",
    "catmark_cubes_infsharp",
    "catmark_hole_test2",
    "catmark_val2_nonman",
    "catmark_gregory_test2",
    "loop_triangle_edgenone",
    "catmark_square_hedit2",
    "bilinear_nonquads1",
];

#[test]
fn mutated_obj_files_never_panic() {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let mut parsed = 0;
    let mut rejected = 0;
    for name in SEEDS {
        let seed = std::fs::read(common::shape_path(name)).unwrap();
        check_obj(&seed);
        for _ in 0..500 {
            let data = mutate(&mut rng, &seed);
            check_obj(&data);
            if obj::read(&String::from_utf8_lossy(&data)).is_ok() {
                parsed += 1;
            } else {
                rejected += 1;
            }
        }
    }
    // The mutations must exercise both outcomes to be worth anything.
    assert!(
        parsed > 100 && rejected > 100,
        "parsed {parsed}, rejected {rejected}"
    );
}

#[test]
fn mutated_ply_files_never_panic() {
    let mut rng = XorShift(0xD1B5_4A32_D192_ED03);
    let mut parsed = 0;
    for name in SEEDS {
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        let mut binary = Vec::new();
        ply::write(&mesh, None, &mut binary).unwrap();
        for _ in 0..250 {
            let data = mutate(&mut rng, &binary);
            check_ply(&data);
            parsed += usize::from(ply::read(&data).is_ok());
        }
    }
    let ascii = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    check_ply(ascii);
    for _ in 0..1000 {
        check_ply(&mutate(&mut rng, ascii));
    }
    assert!(parsed > 50, "only {parsed} mutated binary files parsed");
}
