//! Prim transforms: `xformOpOrder` and its `xformOp:*` attributes composed into a local
//! matrix, and ancestors' matrices into a world matrix.
//!
//! Matrices follow USD's convention: row vectors, `p' = p * M`, translation in the last row.
//! The ops of `xformOpOrder` apply to a point from last to first, so the local matrix is
//! `M_last * ... * M_first`, and a prim's world matrix is `local * parent_world`.

use super::attrs::PrimReader;
use crate::error::Result;
use openusd::sdf::Value;

/// A 4x4 matrix, rows first.
pub type Matrix = [[f64; 4]; 4];

/// The identity matrix.
pub const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// `a * b`.
pub fn mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

/// A point transformed by `m` (row vector times matrix, divided by w when it is not 1),
/// computed in `f64` and rounded to `R` once.
pub fn transform_point<R: crate::Real>(m: &Matrix, p: [R; 3]) -> [R; 3] {
    let v = [p[0].to_f64(), p[1].to_f64(), p[2].to_f64(), 1.0];
    let mut out = [0.0f64; 4];
    for (j, o) in out.iter_mut().enumerate() {
        *o = (0..4).map(|k| v[k] * m[k][j]).sum();
    }
    let w = if out[3] != 0.0 { out[3] } else { 1.0 };
    [0, 1, 2].map(|k| R::from_f64(out[k] / w))
}

fn translate(t: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    m[3][..3].copy_from_slice(&t);
    m
}

fn scale(s: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    for k in 0..3 {
        m[k][k] = s[k];
    }
    m
}

/// Rotation by `deg` degrees about axis `axis` (0 x, 1 y, 2 z), row-vector form.
fn rotate(axis: usize, deg: f64) -> Matrix {
    let (s, c) = deg.to_radians().sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = IDENTITY;
    m[i][i] = c;
    m[i][j] = s;
    m[j][i] = -s;
    m[j][j] = c;
    m
}

/// A unit quaternion `(w, x, y, z)` as a row-vector rotation matrix.
fn orient(q: [f64; 4]) -> Matrix {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [w, x, y, z] = if n > 0.0 {
        q.map(|c| c / n)
    } else {
        [1.0, 0.0, 0.0, 0.0]
    };
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + w * z),
            2.0 * (x * z - w * y),
            0.0,
        ],
        [
            2.0 * (x * y - w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + w * x),
            0.0,
        ],
        [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
            0.0,
        ],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// The inverse of an affine or general 4x4 matrix (Gauss-Jordan); `None` when singular.
fn inverse(m: &Matrix) -> Option<Matrix> {
    let mut a = *m;
    let mut inv = IDENTITY;
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let d = a[col][col];
        for k in 0..4 {
            a[col][k] /= d;
            inv[col][k] /= d;
        }
        for row in 0..4 {
            if row != col {
                let f = a[row][col];
                for k in 0..4 {
                    a[row][k] -= f * a[col][k];
                    inv[row][k] -= f * inv[col][k];
                }
            }
        }
    }
    Some(inv)
}

fn vec3(r: &PrimReader, name: &str, v: Value) -> Result<[f64; 3]> {
    Ok(match v {
        Value::Vec3dVec(_) | Value::Vec3fVec(_) => {
            return Err(r.error(name, "expected one 3-vector, found an array"))
        }
        Value::Vec3d(p) => [p.x, p.y, p.z],
        Value::Vec3f(p) => [p.x as f64, p.y as f64, p.z as f64],
        Value::Vec3h(p) => [
            f32::from(p.x) as f64,
            f32::from(p.y) as f64,
            f32::from(p.z) as f64,
        ],
        other => {
            let t: &'static str = (&other).into();
            return Err(r.error(name, format!("expected a 3-vector, found a {t} value")));
        }
    })
}

fn scalar(r: &PrimReader, name: &str, v: Value) -> Result<f64> {
    Ok(match v {
        Value::Double(x) => x,
        Value::Float(x) => x as f64,
        Value::Half(x) => f32::from(x) as f64,
        other => {
            let t: &'static str = (&other).into();
            return Err(r.error(name, format!("expected a scalar angle, found a {t} value")));
        }
    })
}

/// The matrix of one op, named as in `xformOpOrder` (`xformOp:translate`,
/// `xformOp:rotateXYZ:spin`, `!invert!xformOp:scale`, ...).
fn op_matrix(r: &PrimReader, entry: &str) -> Result<Matrix> {
    let (invert, name) = match entry.strip_prefix("!invert!") {
        Some(rest) => (true, rest),
        None => (false, entry),
    };
    let kind = name
        .strip_prefix("xformOp:")
        .map(|k| k.split(':').next().unwrap_or(""))
        .ok_or_else(|| r.error("xformOpOrder", format!("\"{entry}\" is not an xformOp")))?;
    let value = r
        .value(name)?
        .ok_or_else(|| r.error(name, "listed in xformOpOrder but has no value"))?;
    let m = match kind {
        "translate" => translate(vec3(r, name, value)?),
        "scale" => scale(vec3(r, name, value)?),
        "rotateX" => rotate(0, scalar(r, name, value)?),
        "rotateY" => rotate(1, scalar(r, name, value)?),
        "rotateZ" => rotate(2, scalar(r, name, value)?),
        "orient" => match value {
            Value::Quatd(q) => orient([q.w, q.x, q.y, q.z]),
            Value::Quatf(q) => orient([q.w as f64, q.x as f64, q.y as f64, q.z as f64]),
            _ => return Err(r.error(name, "expected a quaternion")),
        },
        "transform" => match value {
            Value::Matrix4d(m) => {
                let mut out = IDENTITY;
                for (i, row) in out.iter_mut().enumerate() {
                    row.copy_from_slice(&m.0[i * 4..i * 4 + 4]);
                }
                out
            }
            _ => return Err(r.error(name, "expected a matrix4d")),
        },
        k if k.len() == 9 && k.starts_with("rotate") => {
            // rotateXYZ etc.: the first axis named applies first.
            let v = vec3(r, name, value)?;
            let mut m = IDENTITY;
            for c in k[6..].chars() {
                let axis = match c {
                    'X' => 0,
                    'Y' => 1,
                    'Z' => 2,
                    _ => return Err(r.error(name, format!("unknown xformOp \"{k}\""))),
                };
                m = mul(&m, &rotate(axis, v[axis]));
            }
            m
        }
        other => return Err(r.error(name, format!("unknown xformOp \"{other}\""))),
    };
    if invert {
        inverse(&m).ok_or_else(|| r.error(name, "!invert! of a singular transform"))
    } else {
        Ok(m)
    }
}

/// The prim's local transform, and whether it resets the parent's (`!resetXformStack!`).
pub(super) fn local(r: &PrimReader) -> Result<(Matrix, bool)> {
    let Some(order) = r.tokens("xformOpOrder")? else {
        return Ok((IDENTITY, false));
    };
    let mut m = IDENTITY;
    let mut reset = false;
    for entry in &order {
        if entry == "!resetXformStack!" {
            m = IDENTITY;
            reset = true;
            continue;
        }
        // Earlier ops apply last: M = M_op * M_so_far.
        m = mul(&op_matrix(r, entry)?, &m);
    }
    Ok((m, reset))
}
