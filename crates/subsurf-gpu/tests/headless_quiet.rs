//! A Rust program using `subsurf-gpu` directly, on a machine without a display server, gets
//! no `error: XDG_RUNTIME_DIR ...` line (nor any other) on stderr from opening a GPU context:
//! the library switches Mesa's device-select layer off itself (issue 40), as the command line
//! and the Python package do. The test runs itself again as a child process with the display
//! variables removed and reads the child's real stderr (libwayland writes to the file
//! descriptor, past the test harness's capture).

use std::process::Command;
use subsurf_gpu::GpuContext;

const CHILD: &str = "SUBSURF_HEADLESS_CHILD";
const NAME: &str = "a_library_gpu_context_prints_nothing_on_stderr_without_a_display";

#[test]
fn a_library_gpu_context_prints_nothing_on_stderr_without_a_display() {
    if std::env::var_os(CHILD).is_some() {
        match GpuContext::new() {
            Ok(ctx) => println!("adapter: {}", ctx.adapter_info().name),
            Err(e) if std::env::var("SUBSURF_SKIP_GPU").as_deref() == Ok("1") => {
                println!("SKIPPED: {e}")
            }
            Err(e) => panic!("{e}"),
        }
        return;
    }
    let out = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", NAME, "--test-threads=1", "--nocapture"])
        .env(CHILD, "1")
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("DISPLAY")
        .env_remove("NODEVICE_SELECT")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "child failed:\n{stdout}\n{stderr}");
    if stdout.contains("SKIPPED:") {
        eprintln!("\n!!!!!!!! SKIPPED GPU TEST `{NAME}` (SUBSURF_SKIP_GPU=1) !!!!!!!!\n");
        return;
    }
    assert!(stdout.contains("adapter: "), "{stdout}");
    assert!(
        stderr.trim().is_empty(),
        "stderr of a GPU context:\n{stderr}"
    );
}
