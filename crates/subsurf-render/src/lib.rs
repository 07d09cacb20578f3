//! # subsurf-render
//!
//! Headless rendering of triangle meshes to PNG with wgpu: smooth shading from per-vertex
//! normals (a two-sided headlight plus a key light), per-triangle colour classes, an
//! optional wireframe overlay (the control cage), automatic perspective framing of the
//! bounding box and 4x multisampling.
//!
//! ```
//! use subsurf_render::{render, RenderError, RenderMesh, RenderOptions, View};
//! // A unit square facing +z, seen from the front.
//! let mesh = RenderMesh {
//!     positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     normals: vec![[0.0, 0.0, 1.0]; 4],
//!     indices: vec![0, 1, 2, 0, 2, 3],
//!     ..Default::default()
//! };
//! let options = RenderOptions { width: 64, height: 48, view: View::Front, ..Default::default() };
//! let image = match render(&mesh, &options) {
//!     Ok(image) => image,
//!     Err(RenderError::NoAdapter(why)) => {
//!         eprintln!("no GPU adapter, nothing rendered: {why}");
//!         return Ok(());
//!     }
//!     Err(e) => return Err(e),
//! };
//! assert_eq!((image.width, image.height), (64, 48));
//! assert_ne!(image.pixel(32, 24), options.background); // the square fills the centre
//! assert_eq!(image.pixel(0, 0), options.background); // and misses the corners
//! let mut png = Vec::new();
//! image.write_png(&mut png)?; // or image.save_png("square.png")
//! assert!(png.starts_with(b"\x89PNG"));
//! # Ok::<(), RenderError>(())
//! ```
//!
//! Without a GPU, Mesa's software Vulkan driver (lavapipe, `mesa-vulkan-drivers`) works
//! with `WGPU_BACKEND=vulkan`.

#![warn(missing_docs)]
mod camera;
mod device;
mod gpu_pass;
mod image;
mod prepare;

pub use camera::{Camera, Mat4, UpAxis, View};
pub use device::{describe, open, Gpu};
pub use image::RgbaImage;

/// Errors of the renderer.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No adapter could be opened; the message says how to install one.
    #[error("{0}")]
    NoAdapter(String),
    /// The device could not be created or reported an error.
    #[error("GPU device error: {0}")]
    Device(String),
    /// The mesh is inconsistent (lengths, indices, non-finite values).
    #[error("invalid render mesh: {0}")]
    InvalidMesh(String),
    /// The options are unusable (zero size, ...).
    #[error("invalid render options: {0}")]
    InvalidOptions(String),
    /// A buffer or image would exceed the device limits.
    #[error("too large for the device: {0}")]
    TooLarge(String),
    /// PNG encoding failed.
    #[error("PNG encoding: {0}")]
    Png(String),
    /// File output failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// What to draw: triangles with per-vertex normals, optional per-triangle colour classes
/// and optional line segments drawn on top (the control cage).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RenderMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// One normal per vertex (need not be unit length).
    pub normals: Vec<[f32; 3]>,
    /// Three vertex indices per triangle.
    pub indices: Vec<u32>,
    /// Optional colour class of each triangle (index into [`RenderOptions::palette`]).
    pub triangle_class: Option<Vec<u8>>,
    /// Line segments drawn over the surface.
    pub lines: Vec<[[f32; 3]; 2]>,
}

impl RenderMesh {
    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.indices.len() / 3
    }

    /// Vertices and line ends.
    pub fn points(&self) -> impl Iterator<Item = &[f32; 3]> + Clone {
        self.positions
            .iter()
            .chain(self.lines.iter().flat_map(|l| l.iter()))
    }

    /// Bounding box of the vertices and line ends; `None` when there is nothing to draw.
    pub fn bounding_box(&self) -> Option<([f32; 3], [f32; 3])> {
        use subsurf::mesh::{bounding_box, union_box};
        union_box(
            bounding_box(&self.positions),
            bounding_box(self.lines.as_flattened()),
        )
    }

    /// The sphere about the bounding-box centre through the farthest vertex or line end.
    pub fn bounding_sphere(&self) -> Option<([f32; 3], f32)> {
        let (lo, hi) = self.bounding_box()?;
        let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
        let r2 = self
            .points()
            .map(|p| (0..3).map(|k| (p[k] - c[k]) * (p[k] - c[k])).sum::<f32>())
            .fold(0.0f32, f32::max);
        Some((c, r2.sqrt()))
    }
}

impl From<subsurf::surface::Surface> for RenderMesh {
    /// The triangles of `subsurf::surface::build` as drawn: classes kept when the surface
    /// computed any (`colors` other than `None`), the cage as lines.
    fn from(s: subsurf::surface::Surface) -> Self {
        let classed = s.colors != subsurf::surface::Colors::None;
        RenderMesh {
            positions: s.positions,
            normals: s.normals,
            indices: s.triangles.into_iter().flatten().collect(),
            triangle_class: classed.then_some(s.triangle_class),
            lines: s.cage,
        }
    }
}

/// A categorical palette (sRGB): neutral grey first, then well-separated hues.
pub const PALETTE: [[u8; 3]; 8] = [
    [200, 203, 210], // 0 grey
    [240, 160, 80],  // 1 orange
    [125, 165, 220], // 2 blue
    [90, 175, 90],   // 3 green
    [210, 70, 70],   // 4 red
    [150, 100, 190], // 5 purple
    [225, 200, 70],  // 6 yellow
    [80, 190, 190],  // 7 teal
];

/// Camera framing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fit {
    /// The bounding sphere (about the box centre) touches the narrower border: the same
    /// distance from every view direction.
    Sphere,
    /// The projected points themselves, centred with the same margin on opposite sides, the
    /// binding pair of sides at the margin: elongated models fill the image (the default).
    Tight,
}

// One name per value, for every front end (`--view`, `view=`; `docs/vocabulary.md`).
subsurf::option_value!(View, "view", {
    Front => "front",
    Back => "back",
    Left => "left",
    Right => "right",
    Top => "top",
    Iso => "iso",
});

subsurf::option_value!(UpAxis, "up", {
    Y => "y",
    Z => "z",
});

subsurf::option_value!(Fit, "fit", {
    Tight => "tight",
    Sphere => "sphere",
});

/// The named backgrounds, sRGB + alpha.
pub const BACKGROUNDS: [(&str, [u8; 4]); 3] = [
    ("white", [255, 255, 255, 255]),
    ("black", [0, 0, 0, 255]),
    ("transparent", [255, 255, 255, 0]),
];

/// A background: a name of [`BACKGROUNDS`] (any case) or `RRGGBB` (an optional `#` first),
/// as `--background` and `background=` take it.
pub fn parse_background(s: &str) -> Result<[u8; 4], String> {
    if let Some((_, c)) = BACKGROUNDS
        .iter()
        .find(|(name, _)| name.eq_ignore_ascii_case(s))
    {
        return Ok(*c);
    }
    // The older spelling of transparent, still read.
    if s.eq_ignore_ascii_case("none") {
        return Ok(BACKGROUNDS[2].1);
    }
    let hex = s.strip_prefix('#').unwrap_or(s);
    if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        let names: Vec<&str> = BACKGROUNDS.iter().map(|(n, _)| *n).collect();
        return Err(format!(
            "background {s:?}: use {} or RRGGBB",
            names.join(", ")
        ));
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|e| e.to_string());
    Ok([byte(0)?, byte(2)?, byte(4)?, 255])
}

/// How to render.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// View direction.
    pub view: View,
    /// Which model axis is up.
    pub up: UpAxis,
    /// Colour of each triangle class (sRGB); class `k` uses `palette[k % len]`.
    pub palette: Vec<[u8; 3]>,
    /// Surface colour when the mesh has no classes (sRGB).
    pub base_color: [u8; 3],
    /// Background (sRGB + alpha).
    pub background: [u8; 4],
    /// Line colour (sRGB).
    pub line_color: [u8; 3],
    /// Line width in pixels.
    pub line_width: f32,
    /// Add the key light (upper left); off leaves the headlight only, which keeps shading
    /// mirror-symmetric for symmetric views.
    pub key_light: bool,
    /// Multisample count: 1 or 4.
    pub samples: u32,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// How the camera distance is chosen.
    pub fit: Fit,
    /// Camera distance over the distance at which the bounding sphere touches the narrower
    /// image border (1 = touching; larger leaves a border).
    pub margin: f32,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 600,
            view: View::Iso,
            up: UpAxis::Y,
            palette: PALETTE.to_vec(),
            base_color: [196, 200, 212],
            background: [255, 255, 255, 255],
            line_color: [30, 30, 40],
            line_width: 1.5,
            key_light: true,
            samples: 4,
            fov_y_degrees: 30.0,
            margin: 1.05,
            fit: Fit::Tight,
        }
    }
}

impl RenderOptions {
    /// The camera these options give for `mesh`, or `None` for an empty mesh.
    pub fn camera(&self, mesh: &RenderMesh) -> Option<Camera> {
        if self.fit == Fit::Tight {
            return Camera::frame_points(
                mesh.points(),
                self.view,
                self.up,
                self.width as f32 / self.height.max(1) as f32,
                self.fov_y_degrees.to_radians(),
                self.margin,
            );
        }
        let (center, radius) = mesh.bounding_sphere()?;
        Some(Camera::frame(
            center,
            radius,
            self.view,
            self.up,
            self.width as f32 / self.height.max(1) as f32,
            self.fov_y_degrees.to_radians(),
            self.margin,
        ))
    }
}

/// Renders `mesh` on a freshly opened device. To render several images, open one [`Gpu`]
/// and call [`render_with`].
pub fn render(mesh: &RenderMesh, options: &RenderOptions) -> Result<RgbaImage, RenderError> {
    prepare::validate(mesh, options)?;
    let gpu = open()?;
    render_with(&gpu, mesh, options)
}

/// Renders `mesh` with an open device.
pub fn render_with(
    gpu: &Gpu,
    mesh: &RenderMesh,
    options: &RenderOptions,
) -> Result<RgbaImage, RenderError> {
    prepare::validate(mesh, options)?;
    let camera = options
        .camera(mesh)
        .ok_or_else(|| RenderError::InvalidMesh("nothing to draw".into()))?;
    let vertices = prepare::surface_vertices(mesh, options);
    gpu_pass::draw(gpu, &vertices, &mesh.lines, &camera, options)
}

#[cfg(test)]
mod vocabulary_tests {
    use super::*;
    use subsurf::OptionValue;

    fn round_trip<T: OptionValue + std::fmt::Display + std::str::FromStr>()
    where
        T::Err: std::fmt::Display + std::fmt::Debug,
    {
        for &v in T::ALL {
            let back = v.to_string().parse::<T>().ok();
            assert_eq!(back, Some(v));
        }
        let e = "nope".parse::<T>().expect_err("refused").to_string();
        assert!(T::names().all(|n| e.contains(n)), "{e}");
    }

    #[test]
    fn options_round_trip() {
        round_trip::<View>();
        round_trip::<UpAxis>();
        round_trip::<Fit>();
    }

    #[test]
    fn backgrounds() {
        assert_eq!(parse_background("White"), Ok([255, 255, 255, 255]));
        assert_eq!(parse_background("#ff8000"), Ok([255, 128, 0, 255]));
        assert!(parse_background("grey")
            .unwrap_err()
            .contains("transparent"));
    }
}
