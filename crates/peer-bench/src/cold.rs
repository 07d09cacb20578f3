//! Cold one-shot runs: one peer's setup and one frame in a fresh process (`--cold PEER LEVEL
//! MESH`), so that every page it touches is new and no peer inherits the allocator state
//! another left behind, as in a command-line run. The child prints its time and the process's
//! peak resident memory; the harness alternates peers process by process.

use std::process::Command;

use osd_ref::OsdMesh;

use crate::peers::{Kernels, Osd, OsdRs, Subsurf};

/// Peers with a cold run, by the name `--cold` takes, in table row order.
pub const COLD_PEERS: [(&str, usize); 4] =
    [("osd", 0), ("osd-rs", 2), ("kernels", 3), ("subsurf", 4)];

/// Peak resident memory of this process in MiB (`VmHWM`).
fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let l = s.lines().find(|l| l.starts_with("VmHWM:"))?;
            l.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// The child's side: one timed one-shot of `peer`, printed as `ms peak_rss_mib` (peak memory
/// of the whole process, the mesh read included).
pub fn run_child(peer: &str, level: usize, path: &str) -> Result<(), Box<dyn std::error::Error>> {
    let mesh = subsurf::io::read_path(path)?;
    let osd_mesh = OsdMesh::from(&mesh);
    let base = &mesh.positions;
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let t = match peer {
        "osd" => crate::ms(|| crate::one_shot(Osd::setup(&osd_mesh, level), base)).0,
        "osd-rs" => crate::ms(|| crate::one_shot(OsdRs::setup(&mesh, level), base)).0,
        "kernels" => crate::ms(|| crate::one_shot(Kernels::setup(&mesh, level), base)).0,
        "subsurf" => {
            one.install(|| crate::ms(|| crate::one_shot(Subsurf::setup(&mesh, level), base)).0)
        }
        _ => return Err(format!("unknown peer {peer}").into()),
    };
    println!("{t} {}", peak_rss_mib());
    Ok(())
}

/// One cold run of `peer` in a fresh process: `(ms, peak MiB)`.
pub fn cold(
    peer: &str,
    level: usize,
    path: &str,
    cpu: bool,
) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let mut cmd = Command::new(std::env::current_exe()?);
    cmd.args(["--cold", peer, &level.to_string(), path]);
    if cpu {
        cmd.arg("--cpu");
    }
    let out = cmd.output()?;
    if !out.status.success() {
        return Err(format!(
            "cold run of {peer}: {}",
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let text = String::from_utf8(out.stdout)?;
    let mut it = text.split_whitespace().map(str::parse::<f64>);
    match (it.next(), it.next()) {
        (Some(Ok(t)), Some(Ok(m))) => Ok((t, m)),
        _ => Err(format!("cold run of {peer}: unexpected output {text:?}").into()),
    }
}
