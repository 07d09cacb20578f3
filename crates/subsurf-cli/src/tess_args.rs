//! Adaptive tessellation flags of `limit` and `render --method limit`: one rate policy (`--max-edge-length`,
//! `--tolerance`, `--pixels` with `--screen`, `--edge-rates`), else the uniform `--tess`.

use std::path::PathBuf;

use anyhow::Context;
use subsurf::tess::{parse_edge_rates, RatePolicy, ScreenCamera};
use subsurf::Topology;
use subsurf_render::{Camera, UpAxis, View};

use crate::cmd_render::parse_size;
use crate::common::option_parser;

/// How the per-edge tessellation rates are chosen (at most one).
#[derive(Debug, Clone, clap::Args)]
#[group(multiple = false)]
pub struct AdaptiveArgs {
    /// No output edge longer than L world units.
    #[arg(long, value_name = "L")]
    pub max_edge_length: Option<f32>,
    /// Chordal error: every output edge midpoint and facet centroid within E x the bounding
    /// box diagonal of the limit surface.
    #[arg(long, value_name = "E")]
    pub tolerance: Option<f32>,
    /// No output edge longer than P pixels under the camera of `--screen` and `--view`.
    #[arg(long, value_name = "P")]
    pub pixels: Option<f32>,
    /// Rates per base edge: lines `v0 v1 rate` (0-based vertex indices); unlisted edges take
    /// `--tess` − 1.
    #[arg(long, value_name = "FILE")]
    pub edge_rates: Option<PathBuf>,
}

/// The camera flags of the screen-space policy (as `render`'s `--size`, `--view`, `--up`).
#[derive(Debug, Clone, clap::Args)]
pub struct ScreenArgs {
    /// Image size WIDTHxHEIGHT for `--pixels`.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub screen: Option<(u32, u32)>,
    /// View direction for `--pixels`.
    #[arg(long, value_parser = option_parser::<View>(), default_value_t = View::Iso)]
    pub view: View,
    /// Model axis pointing up for `--pixels`.
    #[arg(long, value_parser = option_parser::<UpAxis>(), default_value_t = UpAxis::Y)]
    pub up: UpAxis,
}

impl AdaptiveArgs {
    /// Whether any adaptive flag is given.
    pub fn any(&self) -> bool {
        self.max_edge_length.is_some()
            || self.tolerance.is_some()
            || self.pixels.is_some()
            || self.edge_rates.is_some()
    }

    /// The policy and the name of its flag, checked before any work (`camera`: the camera
    /// of `--pixels`, see [`screen_camera`]).
    pub fn policy(
        &self,
        camera: Option<ScreenCamera>,
        t: &Topology,
        tess: usize,
    ) -> anyhow::Result<(RatePolicy, String)> {
        let uniform = u32::try_from(tess.saturating_sub(1)).unwrap_or(u32::MAX);
        let (policy, origin) = if let Some(l) = self.max_edge_length {
            (
                RatePolicy::MaxEdgeLength(l),
                "--max-edge-length".to_string(),
            )
        } else if let Some(e) = self.tolerance {
            (RatePolicy::Tolerance(e), "--tolerance".to_string())
        } else if let Some(p) = self.pixels {
            let origin = "--pixels".to_string();
            (RatePolicy::screen(camera, p, &origin)?, origin)
        } else if let Some(path) = &self.edge_rates {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("--edge-rates {}", path.display()))?;
            let file = path.display().to_string();
            (
                RatePolicy::Explicit(parse_edge_rates(&text, &file, t, uniform.max(1))?),
                file,
            )
        } else {
            (RatePolicy::Uniform(uniform), "--tess".to_string())
        };
        policy.validate(t, &origin)?;
        Ok((policy, origin))
    }
}

impl ScreenArgs {
    /// The camera of `--screen`, `--view` and `--up` framed on `cage` (`None` without
    /// `--screen`).
    pub fn camera(&self, cage: &[[f32; 3]]) -> Option<ScreenCamera> {
        let (w, h) = self.screen?;
        screen_camera((w, h), self.view, self.up, cage)
    }
}

/// The camera of an image of `size` seen from `view` with `up`, framed on the points `cage`
/// (the base mesh's: `render` frames its output's points, which lie close to them).
pub fn screen_camera(
    (w, h): (u32, u32),
    view: View,
    up: UpAxis,
    cage: &[[f32; 3]],
) -> Option<ScreenCamera> {
    let defaults = subsurf_render::RenderOptions::default();
    let cam = Camera::frame_points(
        cage.iter(),
        view,
        up,
        w as f32 / h.max(1) as f32,
        defaults.fov_y_degrees.to_radians(),
        defaults.margin,
    )?;
    Some(ScreenCamera {
        view_proj: cam.view_proj(),
        width: w,
        height: h,
    })
}
