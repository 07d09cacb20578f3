//! `subsurf compare A B -o OUT.png`: two renders side by side.
//!
//! Each argument is `FILE[@[METHOD][:N]]`: a mesh file, optionally followed by `@`, a
//! method and `:N`, for example `pawn.obj`, `pawn.obj@refine:1`, `pawn.obj@prep:9` or
//! `car.obj@:2`. Methods: `refine`, `limit`, `prep`, and `prep-bicubic` (the p-rep without
//! its bi-5 perturbations). `N` is the refinement level for `refine` and the samples per
//! patch side for the others; a missing method is `refine` and a missing `N` is `--level`
//! (refine) or 8. The image options
//! (`--size` per panel, `--view`, `--cage`, ...) apply to both panels.

use crate::cmd_render::{
    open_gpu, prepare_spec, render_prepared, save, LookArgs, Method, SurfaceSpec,
};
use crate::common::SchemeArgs;
use crate::progress::Progress;
use anyhow::{anyhow, Context};
use std::path::PathBuf;
use subsurf_render::RgbaImage;

/// Render two surfaces side by side into one PNG.
#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// Left surface: FILE[@[METHOD][:N]], FILE a .obj or .ply mesh, METHOD refine, limit, prep
    /// or prep-bicubic.
    pub left: String,
    /// Right surface: FILE[@[METHOD][:N]], as the left one.
    pub right: String,
    /// Output image (.png; `-` writes the PNG to standard output).
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

/// Parses `FILE[@[METHOD][:N]]`. The part after the last `@` is read as a method only when it
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
            m.to_ascii_lowercase().parse::<Method>().ok()
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
                adaptive: None,
            });
        }
    }
    Ok(SurfaceSpec {
        path: PathBuf::from(s),
        method: Method::Refine,
        level: default_level,
        adaptive: None,
    })
}

pub fn run(a: &CompareArgs) -> anyhow::Result<()> {
    crate::common::check_output_ext(&a.output, "png")?;
    let specs = [
        parse_spec(&a.left, a.level)?,
        parse_spec(&a.right, a.level)?,
    ];
    let progress = Progress::start("reading");
    let mut meshes = Vec::new();
    for s in &specs {
        meshes.push(
            prepare_spec(s, &a.look, &a.scheme, &progress)
                .with_context(|| format!("panel {}", s.path.display()))?,
        );
    }
    progress.stage("opening the GPU");
    let gpu = open_gpu()?;
    let mut images = Vec::new();
    for m in &meshes {
        images.push(render_prepared(&gpu, m, &a.look, &progress)?);
    }
    let image = RgbaImage::hstack(&images, a.gap, a.look.background);
    save(&image, &a.output)?;
    drop(progress);
    crate::say!(
        "compared {} and {} at {}x{} -> {}",
        a.left,
        a.right,
        image.width,
        image.height,
        crate::common::shown(&a.output, true)
    );
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
        let s = parse_spec("p.obj@prep-bicubic:9", 2).unwrap();
        assert_eq!((s.method, s.level), (Method::PrepBicubic, 9));
        assert_eq!(parse_spec("p.obj@Prep", 2).unwrap().method, Method::Prep);
    }
}
