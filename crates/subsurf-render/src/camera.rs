//! Automatic perspective framing of a bounding box from one of six named views.
//!
//! The camera looks at the centre `c` of the axis-aligned bounding box from direction `d`
//! (a unit vector from `c` to the eye). The bounding sphere about `c` has the radius `r` of
//! the farthest point from `c`; with half field of view `α` (the smaller of the vertical one and
//! the horizontal one `atan(aspect · tan(fov_y / 2))`), a sphere of radius `r` seen from
//! distance `D` subtends the half-angle `asin(r / D)`, so `D = r / sin α` makes it touch the
//! narrower image border. A margin factor `m ≥ 1` leaves a border: `D = m · r / sin α`.
//!
//! The tight fit ([`Camera::frame_points`]) frames the points themselves: with view axes
//! `(r̂, û, d̂)` and `(x, y, z)` a point's coordinates relative to the target, the point lies
//! at depth `D − z` and inside the frustum when `|x| ≤ tan(α_x)(D − z)` and
//! `|y| ≤ tan(α_y)(D − z)`, so `D = max_p max(z + m|x| / tan α_x, z + m|y| / tan α_y)`.
//! Solved exactly rather than about a chosen target: per image axis `k` with slope
//! `s_k = tan α_k / m`, an eye at `(e_x, e_y, Z)` in view coordinates sees every point when
//! `max_p(x_p + s z_p) − s Z ≤ e ≤ min_p(x_p − s z_p) + s Z`, which needs
//! `Z ≥ (max_p(x_p + s z_p) − min_p(x_p − s z_p)) / 2s`. The larger of the two needs sets
//! `Z`; on that axis the one position left puts both extremes at the margin, and on the other
//! the eye is moved (by bisection) until the highest and lowest projections are opposite, so
//! the projected silhouette is centred with equal margins on opposite sides, however strong
//! the perspective.

/// Named view directions. With `up = Y`: front looks down `-Z` (the eye on `+Z`), right
/// looks from `+X`, top from `+Y`; `iso` is a three-quarter view from front-right-above.
/// With `up = Z` the same views are rotated by +90° about `X` (front looks down `+Y`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Eye on `+Z` (Y up).
    Front,
    /// Eye on `-Z`.
    Back,
    /// Eye on `-X`.
    Left,
    /// Eye on `+X`.
    Right,
    /// Eye on `+Y`, image up is `-Z`.
    Top,
    /// Eye at azimuth 35° from front towards right, elevation 25°.
    Iso,
}

/// Which model axis points up in the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UpAxis {
    /// `+Y` up (OBJ convention).
    Y,
    /// `+Z` up (CAD convention).
    Z,
}

/// A column-major 4x4 matrix, as WGSL's `mat4x4<f32>`.
pub type Mat4 = [[f32; 4]; 4];

/// Camera placement and projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: [f32; 3],
    /// Point looked at (the bounding-box centre).
    pub target: [f32; 3],
    /// Image-up direction (unit, orthogonal to the view direction).
    pub up: [f32; 3],
    /// Image-right direction (unit).
    pub right: [f32; 3],
    /// Vertical field of view in radians.
    pub fov_y: f32,
    /// Width / height.
    pub aspect: f32,
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
    /// Bounding-sphere radius of the framed box.
    pub radius: f32,
}

pub(crate) fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn scale(a: [f32; 3], s: f32) -> [f32; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(crate) fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn normalize(a: [f32; 3]) -> [f32; 3] {
    let l = dot(a, a).sqrt();
    if l > 0.0 && l.is_finite() {
        scale(a, 1.0 / l)
    } else {
        [0.0, 0.0, 0.0]
    }
}

impl View {
    /// `(eye direction, image up)` in the Y-up frame.
    fn dirs_y_up(self) -> ([f32; 3], [f32; 3]) {
        match self {
            View::Front => ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            View::Back => ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
            View::Left => ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            View::Right => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            View::Top => ([0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
            View::Iso => {
                let (az, el) = (35f32.to_radians(), 25f32.to_radians());
                (
                    [az.sin() * el.cos(), el.sin(), az.cos() * el.cos()],
                    [0.0, 1.0, 0.0],
                )
            }
        }
    }

    /// `(eye direction, image up)` for the given up axis.
    pub fn directions(self, up: UpAxis) -> ([f32; 3], [f32; 3]) {
        let (d, u) = self.dirs_y_up();
        match up {
            UpAxis::Y => (d, u),
            // Rotation by +90° about X: y -> z, z -> -y.
            UpAxis::Z => ([d[0], -d[2], d[1]], [u[0], -u[2], u[1]]),
        }
    }
}

impl Camera {
    /// Frames the sphere `(center, radius)` from `view` in an image of the given aspect ratio,
    /// leaving `margin - 1` of the sphere radius as border (see the module docs).
    pub fn frame(
        center: [f32; 3],
        radius: f32,
        view: View,
        up_axis: UpAxis,
        aspect: f32,
        fov_y: f32,
        margin: f32,
    ) -> Camera {
        let target = center;
        let radius = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            1.0
        };
        let (dir, up0) = view.directions(up_axis);
        let dir = normalize(dir);
        let right = normalize(cross(up0, dir));
        let up = cross(dir, right);
        let half = (0.5 * fov_y).min((aspect * (0.5 * fov_y).tan()).atan());
        let dist = margin * radius / half.sin();
        let eye = add(target, scale(dir, dist));
        Camera {
            eye,
            target,
            up,
            right,
            fov_y,
            aspect,
            near: (dist - 1.5 * radius).max(dist * 1e-3),
            far: dist + 1.5 * radius,
            radius,
        }
    }

    /// Frames `points` tightly from `view` (see the module docs): the projected extent of the
    /// points centred in the image with the same margin on opposite sides, the binding pair
    /// of sides touching the margin; `None` without finite points.
    pub fn frame_points<'a>(
        points: impl Iterator<Item = &'a [f32; 3]> + Clone,
        view: View,
        up_axis: UpAxis,
        aspect: f32,
        fov_y: f32,
        margin: f32,
    ) -> Option<Camera> {
        let (dir, up0) = view.directions(up_axis);
        let dir = normalize(dir);
        let right = normalize(cross(up0, dir));
        let up = cross(dir, right);
        let sy = f64::from((0.5 * fov_y).tan() / margin);
        let s = [sy * f64::from(aspect), sy];
        let axes = [right, up, dir].map(|a| a.map(f64::from));
        let coords = |p: &[f32; 3]| {
            let p = p.map(f64::from);
            axes.map(|a| a[0] * p[0] + a[1] * p[1] + a[2] * p[2])
        };
        let finite = || {
            points
                .clone()
                .filter(|p| p.iter().all(|c| c.is_finite()))
                .map(coords)
        };
        // Per image axis k: A = max(x + s z), B = min(x - s z). An eye at (e_x, e_y, Z) sees
        // every point when A - s Z <= e_k <= B + s Z, possible from Z >= (A - B) / (2 s).
        let (mut a, mut b) = ([f64::MIN; 2], [f64::MAX; 2]);
        let (mut z_lo, mut z_hi) = (f64::MAX, f64::MIN);
        for q in finite() {
            for k in 0..2 {
                a[k] = a[k].max(q[k] + s[k] * q[2]);
                b[k] = b[k].min(q[k] - s[k] * q[2]);
            }
            (z_lo, z_hi) = (z_lo.min(q[2]), z_hi.max(q[2]));
        }
        if z_lo > z_hi {
            return None;
        }
        let need = [0, 1].map(|k| (a[k] - b[k]) / (2.0 * s[k]));
        let extent = (a[0] - b[0]).max(a[1] - b[1]).max(z_hi - z_lo).max(1e-6);
        // The eye's depth: the larger need (that axis touches the margin on both sides), and
        // in front of every point.
        let z = need[0].max(need[1]).max(z_hi + 1e-3 * extent);
        let mut eye = [0.0f64; 2];
        for k in 0..2 {
            if need[k] >= z {
                // Binding: the only position that fits, both sides at the margin.
                eye[k] = 0.5 * (a[k] + b[k]);
                continue;
            }
            // Free: centre the projected extent, where the highest projection equals minus
            // the lowest; `top(e) + bottom(e)` falls as `e` grows, so bisect.
            let balance = |e: f64| {
                let (mut hi, mut lo) = (f64::MIN, f64::MAX);
                for q in finite() {
                    let t = (q[k] - e) / (z - q[2]);
                    (hi, lo) = (hi.max(t), lo.min(t));
                }
                hi + lo
            };
            let (mut e0, mut e1) = (a[k] - s[k] * z, b[k] + s[k] * z);
            for _ in 0..64 {
                let m = 0.5 * (e0 + e1);
                if balance(m) > 0.0 {
                    e0 = m;
                } else {
                    e1 = m;
                }
                if e1 - e0 <= 1e-9 * extent {
                    break;
                }
            }
            eye[k] = 0.5 * (e0 + e1);
        }
        // The target: on the view axis at the middle of the points' depth range.
        let at = |c: [f64; 3]| {
            [0, 1, 2].map(|i| (axes[0][i] * c[0] + axes[1][i] * c[1] + axes[2][i] * c[2]) as f32)
        };
        let target = at([eye[0], eye[1], 0.5 * (z_lo + z_hi)]);
        let eye = at([eye[0], eye[1], z]);
        let mut radius = 0.0f32;
        for p in points.filter(|p| p.iter().all(|c| c.is_finite())) {
            let v = sub(*p, target);
            radius = radius.max(dot(v, v));
        }
        let radius = radius.sqrt().max(1e-6);
        Some(Camera {
            eye,
            target,
            up,
            right,
            fov_y,
            aspect,
            // The depth range of the points, with room on both sides.
            near: (0.9 * (z - z_hi)).max(1e-3 * z) as f32,
            far: (1.1 * (z - z_lo) + 1e-3 * extent) as f32,
            radius,
        })
    }

    /// World-to-clip matrix (right-handed view, wgpu depth range 0..1).
    pub fn view_proj(&self) -> Mat4 {
        let f = normalize(sub(self.target, self.eye)); // forward = -z in view space
        let (r, u) = (self.right, self.up);
        let e = self.eye;
        // View matrix rows: r, u, -f; translation -R·e.
        let view: Mat4 = [
            [r[0], u[0], -f[0], 0.0],
            [r[1], u[1], -f[1], 0.0],
            [r[2], u[2], -f[2], 0.0],
            [-dot(r, e), -dot(u, e), dot(f, e), 1.0],
        ];
        let t = 1.0 / (0.5 * self.fov_y).tan();
        let (n, fa) = (self.near, self.far);
        let proj: Mat4 = [
            [t / self.aspect, 0.0, 0.0, 0.0],
            [0.0, t, 0.0, 0.0],
            [0.0, 0.0, fa / (n - fa), -1.0],
            [0.0, 0.0, n * fa / (n - fa), 0.0],
        ];
        mul(&proj, &view)
    }

    /// Projects a world point to pixel coordinates `(x right, y down)` in a `w x h` image.
    pub fn project(&self, p: [f32; 3], w: u32, h: u32) -> [f32; 2] {
        let m = self.view_proj();
        let c = transform(&m, [p[0], p[1], p[2], 1.0]);
        let (x, y) = (c[0] / c[3], c[1] / c[3]);
        [(x * 0.5 + 0.5) * w as f32, (0.5 - y * 0.5) * h as f32]
    }
}

/// `a · b` for column-major matrices.
pub fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [[0.0; 4]; 4];
    for c in 0..4 {
        out[c] = transform(a, b[c]);
    }
    out
}

/// `m · v`.
pub fn transform(m: &Mat4, v: [f32; 4]) -> [f32; 4] {
    let mut out = [0.0; 4];
    for k in 0..4 {
        for r in 0..4 {
            out[r] += m[k][r] * v[k];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_touches_the_narrow_border() {
        // A sphere of radius sqrt(3). Seen from distance D = r / sin(a) the sphere
        // of radius r is tangent to the view cone, so its silhouette reaches the border.
        let cam = Camera::frame(
            [0.0; 3],
            3f32.sqrt(),
            View::Front,
            UpAxis::Y,
            1.0,
            30f32.to_radians(),
            1.0,
        );
        let r = 3f32.sqrt();
        let d = dot(sub(cam.eye, cam.target), sub(cam.eye, cam.target)).sqrt();
        assert!((d - r / 15f32.to_radians().sin()).abs() < 1e-4);
        // The tangent point of the sphere in the image-up direction projects onto the top
        // border: angle asin(r/d) = 15 degrees from the axis.
        let a = (r / d).asin();
        let tangent = add(
            cam.target,
            add(
                scale(cam.up, r * a.cos()),
                scale(normalize(sub(cam.eye, cam.target)), r * a.sin()),
            ),
        );
        let px = cam.project(tangent, 100, 100);
        assert!((px[1] - 0.0).abs() < 1e-2, "{px:?}");
        assert!((px[0] - 50.0).abs() < 1e-3);
        // The centre projects to the image centre.
        let c = cam.project(cam.target, 100, 100);
        assert!((c[0] - 50.0).abs() < 1e-3 && (c[1] - 50.0).abs() < 1e-3);
    }

    #[test]
    fn tight_fit_touches_the_border_and_contains_every_point() {
        // A long box, and two boxes far apart along the iso direction (strong perspective:
        // the near one is much larger on screen), in a square and a wide image.
        let corners = |lo: [f32; 3], hi: [f32; 3]| {
            (0..8)
                .map(move |i: usize| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
        };
        let long: Vec<[f32; 3]> = corners([-4.0, 0.0, -1.0], [4.0, 1.0, 1.0]).collect();
        let two: Vec<[f32; 3]> = corners([-3.0, -1.0, -1.0], [-1.0, 1.0, 1.0])
            .chain(corners([5.0, 5.0, 5.0], [7.0, 7.0, 7.0]))
            .collect();
        for (pts, view, aspect) in [View::Front, View::Iso, View::Top]
            .into_iter()
            .flat_map(|v| [(&long, v, 1.0), (&two, v, 1.0), (&two, v, 4.0 / 3.0)])
        {
            let cam = Camera::frame_points(pts.iter(), view, UpAxis::Y, aspect, 0.6, 1.0).unwrap();
            let mut extreme = 0.0f32;
            for p in pts {
                let px = cam.project(*p, 100, 100);
                assert!((-1e-3..=100.001).contains(&px[0]), "{view:?} {px:?}");
                assert!((-1e-3..=100.001).contains(&px[1]), "{view:?} {px:?}");
                extreme = extreme.max((px[0] - 50.0).abs()).max((px[1] - 50.0).abs());
            }
            // Some corner touches the border.
            assert!((extreme - 50.0).abs() < 1e-2, "{view:?} {extreme}");
            // Centred: the projected extent has equal margins on opposite sides.
            let px: Vec<[f32; 2]> = pts.iter().map(|p| cam.project(*p, 100, 100)).collect();
            let (x0, x1) = px
                .iter()
                .fold((f32::MAX, f32::MIN), |a, p| (a.0.min(p[0]), a.1.max(p[0])));
            let (y0, y1) = px
                .iter()
                .fold((f32::MAX, f32::MIN), |a, p| (a.0.min(p[1]), a.1.max(p[1])));
            assert!((x0 - (100.0 - x1)).abs() < 1e-2, "{view:?} x {x0} {x1}");
            assert!((y0 - (100.0 - y1)).abs() < 1e-2, "{view:?} y {y0} {y1}");
        }
    }

    #[test]
    fn views_are_right_handed_and_up_z_rotates() {
        for v in [
            View::Front,
            View::Back,
            View::Left,
            View::Right,
            View::Top,
            View::Iso,
        ] {
            for up in [UpAxis::Y, UpAxis::Z] {
                let cam = Camera::frame([0.5; 3], 0.9, v, up, 1.5, 0.5, 1.1);
                let f = normalize(sub(cam.target, cam.eye));
                // right x up = -forward (towards the eye) in a right-handed frame.
                let b = cross(cam.right, cam.up);
                assert!(dot(b, f) < -0.999, "{v:?} {up:?}");
            }
        }
        // Front with Z up: the eye sits on -Y and +Z is image up.
        let cam = Camera::frame([0.0; 3], 1.7, View::Front, UpAxis::Z, 1.0, 0.5, 1.0);
        assert!(cam.eye[1] < -1.0 && cam.up[2] > 0.999);
        // Right of the image is +X for the front view in both conventions.
        assert!(cam.right[0] > 0.999);
    }
}
