//! The `subsurf` command-line tool.

fn main() -> anyhow::Result<()> {
    println!("subsurf {}", env!("CARGO_PKG_VERSION"));
    Ok(())
}
