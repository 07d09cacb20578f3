//! `subsurf compare A B -o OUT.png`: two renders side by side.
//!
//! Each argument is a mesh file, optionally followed by `@METHOD` and `:N`, for example
//! `pawn.obj`, `pawn.obj@refine:1`, `car.obj@limit:8` or `car.obj@:2`. `N` is the refinement
//! level for `refine` and the tessellation rate for `limit` and `prep`; a missing method is
//! `refine` and a missing `N` is `--level` (refine) or 8 (limit, prep). The image options
//! (`--size` per panel, `--view`, `--cage`, ...) apply to both panels.

use crate::cmd_render::{open_gpu, render_spec, save, LookArgs, Method, SurfaceSpec};
use crate::common::SchemeArgs;
use crate::progress::{quiet, Progress};
use anyhow::{anyhow, Context};
use clap::ValueEnum;
use std::path::PathBuf;
use subsurf_render::RgbaImage;

/// Render two surfaces side by side into one PNG.
#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// Left surface: FILE[@METHOD][:N].
    pub left: String,
    /// Right surface: FILE[@METHOD][:N].
    pub right: String,
    /// Output image (.png).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Default refinement level for arguments without `:N`.
    #[arg(short, long, default_value_t = 3)]
    pub level: usize,
    /// Gap between the panels in pixels.
    #[arg(long, default_value_t = 8)]
    pub gap: u32,
    #[command(flatten)]
    pub look: LookArgs,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

/// Parses `FILE[@METHOD][:N]`. The part after the last `@` is read as a method only when it
/// has that form, so file names containing `@` still work.
pub fn parse_spec(s: &str, default_level: usize) -> anyhow::Result<SurfaceSpec> {
    if let Some((file, tail)) = s.rsplit_once('@') {
        let (m, n) = match tail.split_once(':') {
            Some((m, n)) => (m, Some(n)),
            None => (tail, None),
        };
        let method = if m.is_empty() {
            Some(Method::Refine)
        } else {
            Method::from_str(m, true).ok()
        };
        let number = n.map(|n| n.parse::<usize>());
        if let (Some(method), false) = (method, matches!(number, Some(Err(_)))) {
            let level = match number {
                Some(Ok(v)) => v,
                _ if method == Method::Refine => default_level,
                _ => 8,
            };
            if file.is_empty() {
                return Err(anyhow!("'{s}': no file before '@'"));
            }
            return Ok(SurfaceSpec {
                path: PathBuf::from(file),
                method,
                level,
            });
        }
    }
    Ok(SurfaceSpec {
        path: PathBuf::from(s),
        method: Method::Refine,
        level: default_level,
    })
}

pub fn run(a: &CompareArgs) -> anyhow::Result<()> {
    let specs = [
        parse_spec(&a.left, a.level)?,
        parse_spec(&a.right, a.level)?,
    ];
    let progress = Progress::start("opening the GPU");
    let gpu = open_gpu()?;
    let mut images = Vec::new();
    for s in &specs {
        let (im, _) = render_spec(&gpu, s, &a.look, &a.scheme, &progress)
            .with_context(|| format!("panel {}", s.path.display()))?;
        images.push(im);
    }
    let image = RgbaImage::hstack(&images, a.gap, a.look.background);
    save(&image, &a.output)?;
    drop(progress);
    if !quiet() {
        eprintln!(
            "compared {} and {} at {}x{} -> {}",
            a.left,
            a.right,
            image.width,
            image.height,
            a.output.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse() {
        let s = parse_spec("a.obj", 3).unwrap();
        assert_eq!(
            (s.path, s.method, s.level),
            ("a.obj".into(), Method::Refine, 3)
        );
        let s = parse_spec("dir/a.obj@refine:1", 3).unwrap();
        assert_eq!(
            (s.path, s.method, s.level),
            ("dir/a.obj".into(), Method::Refine, 1)
        );
        let s = parse_spec("a.obj@limit", 3).unwrap();
        assert_eq!((s.method, s.level), (Method::Limit, 8));
        let s = parse_spec("a.obj@:0", 3).unwrap();
        assert_eq!((s.method, s.level), (Method::Refine, 0));
        let s = parse_spec("me@host.obj", 2).unwrap();
        assert_eq!((s.path, s.method), ("me@host.obj".into(), Method::Refine));
        assert!(parse_spec("@refine:2", 2).is_err());
    }
}
