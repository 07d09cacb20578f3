//! The layers of `crates/subsurf/src` point downwards only: a module may use the modules of
//! lower layers and its own, never a higher or a sibling layer's. The table below is the
//! architecture (docs/architecture.md); a `use crate::…` or `crate::…::` path in code (not in
//! comments, not in unit tests) that reaches upward fails this test with the file and line.

use std::path::{Path, PathBuf};

/// The layers, bottom first: a module's layer is its index here.
const LAYERS: &[&[&str]] = &[
    &["error", "options", "real"],
    &["util"],
    &["rules", "patch", "mesh"],
    &["shapes", "io"],
    &["topology"],
    &["refine"],
    &["limit", "prep"],
    &["tess"],
    &["surface"],
];

/// The crate root's re-exports, by the module they come from.
const ROOT_ITEMS: &[(&str, &str)] = &[
    ("Error", "error"),
    ("MeshError", "error"),
    ("QueryError", "error"),
    ("TessError", "error"),
    ("Result", "error"),
    ("Mesh", "mesh"),
    ("Corner", "mesh"),
    ("Crease", "mesh"),
    ("FaceVarying", "mesh"),
    ("Positions", "mesh"),
    ("Options", "options"),
    ("OptionValue", "options"),
    ("option_value", "options"),
    ("ParseOptionError", "options"),
    ("Scheme", "options"),
    ("BoundaryInterpolation", "options"),
    ("CreaseMethod", "options"),
    ("FVarLinearInterpolation", "options"),
    ("TriangleSubdivision", "options"),
    ("Real", "real"),
    ("VertexData", "real"),
    ("Refiner", "refine"),
    ("RefineOptions", "refine"),
    ("StencilTable", "refine"),
    ("Topology", "topology"),
    ("SHARPNESS_INFINITE", "options"),
    ("budget", "util"),
];

fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The module a crate-root name stands for: itself, or the module of a root re-export.
fn module_of(name: &str) -> Option<&str> {
    if layer(name).is_some() {
        return Some(name);
    }
    ROOT_ITEMS.iter().find(|(n, _)| *n == name).map(|(_, m)| *m)
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level modules named by `crate::` paths in the code lines of `text` (doc and line
/// comments dropped; the file's unit tests, from its first `#[cfg(test)]`, left out), with
/// their line numbers.
fn crate_paths(text: &str, depth: usize) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.trim_start();
        if code.starts_with("#[cfg(test)]") {
            break;
        }
        let code = match code.find("//") {
            Some(k) => &code[..k],
            None => code,
        };
        // `super::` repeated `depth` times from a file `depth` modules deep is `crate::`.
        let up = "super::".repeat(depth);
        let code = if depth > 0 {
            code.replace(&up, "crate::")
        } else {
            code.to_string()
        };
        let mut rest = &code[..];
        while let Some(k) = rest.find("crate::") {
            let after = &rest[k + "crate::".len()..];
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            // `use crate::{a, b}` groups: every name in the braces.
            if name.is_empty() && after.starts_with('{') {
                let group = &after[1..after.find('}').unwrap_or(after.len())];
                for n in group.split(',') {
                    let n: String = n
                        .trim()
                        .chars()
                        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                        .collect();
                    if !n.is_empty() {
                        out.push((i + 1, n));
                    }
                }
            } else if !name.is_empty() {
                out.push((i + 1, name));
            }
            rest = after;
        }
    }
    out
}

#[test]
fn no_module_uses_a_higher_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut upward = Vec::new();
    let mut checked = 0;
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let stem = rel.file_stem().unwrap().to_str().unwrap();
        // Unit-test files of a module.
        if stem == "tests" || stem.ends_with("_tests") {
            continue;
        }
        let top = rel.iter().next().unwrap().to_str().unwrap();
        let top = top.strip_suffix(".rs").unwrap_or(top);
        if top == "lib" {
            continue; // the crate root re-exports every layer
        }
        let own = layer(top).unwrap_or_else(|| panic!("{top} is in no layer of LAYERS"));
        // Modules between the crate root and this file's code: `a/b.rs` and `a/b/mod.rs`
        // are two deep, `a.rs` and `a/mod.rs` one.
        let depth = rel.iter().count() - usize::from(stem == "mod");
        let text = std::fs::read_to_string(file).unwrap();
        for (line, used) in crate_paths(&text, depth) {
            checked += 1;
            let module = module_of(&used).unwrap_or_else(|| {
                panic!(
                    "{}:{line}: crate::{used} is neither a module of LAYERS nor a root \
                     re-export of ROOT_ITEMS",
                    rel.display()
                )
            });
            if module == top {
                continue;
            }
            let theirs = layer(module).unwrap();
            if theirs >= own {
                upward.push(format!(
                    "{}:{line}: {top} (layer {own}) uses crate::{used} ({module}, layer {theirs})",
                    rel.display()
                ));
            }
        }
    }
    assert!(
        checked > 200,
        "only {checked} crate paths found: is the scan broken?"
    );
    assert!(
        upward.is_empty(),
        "{} upward or sideways uses:\n{}",
        upward.len(),
        upward.join("\n")
    );
}

#[test]
fn the_scan_sees_paths_groups_and_skips_comments_and_tests() {
    let text = "use crate::limit::PatchTable;\n/// [`crate::tess`]\nlet x = crate::{refine, io};\n\
                // crate::surface\n#[cfg(test)]\nuse crate::surface;\n";
    let got: Vec<String> = crate_paths(text, 2).into_iter().map(|(_, n)| n).collect();
    assert_eq!(got, ["limit", "refine", "io"]);
    let up = "use super::super::topology::Topology;\nuse super::par;\n";
    let got: Vec<String> = crate_paths(up, 2).into_iter().map(|(_, n)| n).collect();
    assert_eq!(got, ["topology"]);
    assert_eq!(module_of("Topology"), Some("topology"));
    assert_eq!(layer("surface"), Some(LAYERS.len() - 1));
}
