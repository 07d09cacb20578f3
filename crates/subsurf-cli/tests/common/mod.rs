//! Helpers shared by the CLI's end-to-end tests.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The `subsurf` binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_subsurf"))
}

/// A path relative to the repository root.
pub fn repo(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel)
}

/// A file in this test process's own scratch directory.
pub fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("subsurf-cli-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Runs a command and asserts it succeeded, showing its stderr otherwise.
pub fn run_ok(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs a command that needs a GPU adapter. Without one it fails with the install hint, or
/// returns `None` after a loud SKIPPED line when `SUBSURF_SKIP_GPU=1`. Asserts success.
pub fn run_gpu(cmd: &mut Command) -> Option<Output> {
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() && err.contains("no GPU adapter") {
        if std::env::var("SUBSURF_SKIP_GPU").as_deref() == Ok("1") {
            eprintln!("\n!!!!!!!! SKIPPED GPU CLI TEST (SUBSURF_SKIP_GPU=1): {err} !!!!!!!!\n");
            return None;
        }
        panic!("{err}\n(set SUBSURF_SKIP_GPU=1 to skip GPU tests)");
    }
    assert!(out.status.success(), "{err}");
    Some(out)
}
