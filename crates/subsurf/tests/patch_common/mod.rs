//! Helpers shared by the patch property tests.
#![allow(dead_code)]

use subsurf::patch::{PatchEval, PatchWeights};

pub type P3 = [f64; 3];

/// Small deterministic generator (xorshift64*), values in [-1, 1).
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn point(&mut self) -> P3 {
        [self.next(), self.next(), self.next()]
    }
}

pub fn random_grid(seed: u64) -> [P3; 16] {
    let mut r = Rng(seed);
    let mut g = [[0.0; 3]; 16];
    for j in 0..4 {
        for i in 0..4 {
            let q = r.point();
            // A bumpy sheet over the (i, j) grid, so the patch is not degenerate.
            g[4 * j + i] = [i as f64 + 0.3 * q[0], j as f64 + 0.3 * q[1], q[2]];
        }
    }
    g
}

pub fn dist(a: &P3, b: &P3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

pub fn sums<const N: usize>(w: &PatchWeights<f64, N>) -> [f64; 6] {
    let s = |a: &[f64; N]| a.iter().sum::<f64>();
    [s(&w.p), s(&w.du), s(&w.dv), s(&w.duu), s(&w.duv), s(&w.dvv)]
}

pub fn assert_unity<const N: usize>(w: &PatchWeights<f64, N>, tol: f64, what: &str) {
    let s = sums(w);
    assert!((s[0] - 1.0).abs() < tol, "{what}: Σw = {}", s[0]);
    for (k, x) in s[1..].iter().enumerate() {
        assert!(x.abs() < tol, "{what}: derivative {k} sums to {x}");
    }
}

/// Central finite differences of `f` at `(u, v)`: checks du, dv against `f`'s own
/// derivatives, and duu, duv, dvv against differences of du, dv.
pub fn check_fd(f: &dyn Fn(f64, f64) -> PatchEval<f64, 3>, u: f64, v: f64, tol: f64, what: &str) {
    let h = 1e-5;
    let e = f(u, v);
    let (up, um, vp, vm) = (f(u + h, v), f(u - h, v), f(u, v + h), f(u, v - h));
    for c in 0..3 {
        let du = (up.p[c] - um.p[c]) / (2.0 * h);
        let dv = (vp.p[c] - vm.p[c]) / (2.0 * h);
        let duu = (up.du[c] - um.du[c]) / (2.0 * h);
        let duv = (vp.du[c] - vm.du[c]) / (2.0 * h);
        let dvu = (up.dv[c] - um.dv[c]) / (2.0 * h);
        let dvv = (vp.dv[c] - vm.dv[c]) / (2.0 * h);
        let scale = 1.0 + e.duu[c].abs() + e.dvv[c].abs() + e.duv[c].abs();
        assert!(
            (du - e.du[c]).abs() < tol,
            "{what} du at ({u},{v}): {du} vs {}",
            e.du[c]
        );
        assert!(
            (dv - e.dv[c]).abs() < tol,
            "{what} dv at ({u},{v}): {dv} vs {}",
            e.dv[c]
        );
        assert!(
            (duu - e.duu[c]).abs() < tol * scale,
            "{what} duu at ({u},{v})"
        );
        assert!(
            (duv - e.duv[c]).abs() < tol * scale,
            "{what} duv at ({u},{v})"
        );
        assert!(
            (dvu - e.duv[c]).abs() < tol * scale,
            "{what} dvu at ({u},{v})"
        );
        assert!(
            (dvv - e.dvv[c]).abs() < tol * scale,
            "{what} dvv at ({u},{v})"
        );
    }
}
