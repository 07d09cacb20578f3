//! Limit-surface queries `(face, u, v)` checked against the surface's domain before they are
//! evaluated: a Loop base triangle's `u, v ≥ 0`, `u + v ≤ 1`, a ptex face's `[0, 1]²`. The
//! patch maps themselves clamp what they are given onto the domain; a query off it is a
//! typed error ([`QueryError`]) naming it instead.

use super::loop_eval::{LoopLimit, LoopSample};
use crate::error::{QueryError, Result};
use rayon::prelude::*;

/// How far past the triangle's hypotenuse `u + v` may lie and still count as on it: the
/// rounding of `i / n + j / n` with `i + j = n`.
pub const TRIANGLE_SLACK: f64 = 1e-12;

/// The checks every domain shares: the face exists, the parameters are finite.
fn check_face_and_finite(
    query: usize,
    face: u64,
    u: f64,
    v: f64,
    count: usize,
) -> Result<(), QueryError> {
    if face >= count as u64 {
        return Err(QueryError::NoSuchFace { query, face, count });
    }
    if !u.is_finite() || !v.is_finite() {
        return Err(QueryError::NotFinite { query, face, u, v });
    }
    Ok(())
}

/// Checks query `query`, `(face, u, v)` on a mesh of `count` triangles.
pub fn check_triangle(
    query: usize,
    face: u64,
    u: f64,
    v: f64,
    count: usize,
) -> Result<(), QueryError> {
    check_face_and_finite(query, face, u, v, count)?;
    if u < 0.0 || v < 0.0 || u + v > 1.0 + TRIANGLE_SLACK {
        return Err(QueryError::OutsideTriangle { query, face, u, v });
    }
    Ok(())
}

/// Checks query `query`, `(face, u, v)` on a surface of `count` ptex faces.
pub fn check_square(
    query: usize,
    face: u64,
    u: f64,
    v: f64,
    count: usize,
) -> Result<(), QueryError> {
    check_face_and_finite(query, face, u, v, count)?;
    if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
        return Err(QueryError::OutsideSquare { query, face, u, v });
    }
    Ok(())
}

impl LoopLimit {
    /// Number of base faces (triangles) the surface was built on.
    pub fn num_faces(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Every query checked ([`check_triangle`]; the first one off the domain is the error),
    /// then evaluated in parallel: `None` on a hole.
    pub fn eval_batch(&self, queries: &[(u32, f64, f64)]) -> Result<Vec<Option<LoopSample>>> {
        let count = self.num_faces();
        for (k, &(f, u, v)) in queries.iter().enumerate() {
            check_triangle(k, f as u64, u, v, count)?;
        }
        Ok(queries
            .par_iter()
            .map(|&(f, u, v)| self.eval(f as usize, u, v))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Error, Mesh, Scheme, Topology};

    fn tetrahedron() -> Mesh {
        let p = vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ];
        let mut m = Mesh::from_faces(p, &[[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
        m.options.scheme = Scheme::Loop;
        m
    }

    #[test]
    fn queries_off_the_triangle_are_errors_naming_them() {
        let m = tetrahedron();
        let l = LoopLimit::new(&Topology::new(&m).unwrap(), &m.positions, 2).unwrap();
        let ok = l
            .eval_batch(&[(0, 0.25, 0.25), (3, 1.0, 0.0), (2, 0.0, 0.0)])
            .unwrap();
        for (r, q) in ok
            .iter()
            .zip([(0, 0.25, 0.25), (3, 1.0, 0.0), (2, 0.0, 0.0)])
        {
            assert_eq!(*r, l.eval(q.0, q.1, q.2));
            assert!(r.is_some());
        }
        let err = |q: &[(u32, f64, f64)]| match l.eval_batch(q) {
            Err(Error::Query(e)) => e,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            err(&[(0, 0.1, 0.1), (0, 0.6, 0.5)]),
            QueryError::OutsideTriangle {
                query: 1,
                face: 0,
                u: 0.6,
                v: 0.5
            }
        );
        assert_eq!(
            err(&[(4, 0.1, 0.1)]),
            QueryError::NoSuchFace {
                query: 0,
                face: 4,
                count: 4
            }
        );
        assert!(matches!(
            err(&[(1, -0.1, 0.1)]),
            QueryError::OutsideTriangle { query: 0, .. }
        ));
        assert!(matches!(
            err(&[(1, f64::NAN, 0.1)]),
            QueryError::NotFinite { query: 0, .. }
        ));
        let msg = err(&[(0, 0.6, 0.5)]).to_string();
        assert!(
            msg.contains("face 0") && msg.contains("u + v <= 1"),
            "{msg}"
        );
    }

    #[test]
    fn the_hypotenuse_is_inside_up_to_rounding() {
        // i/n + j/n with i + j = n rounds to a little more than 1 for some n.
        for n in 1..200u32 {
            for i in 0..=n {
                let (u, v) = (i as f64 / n as f64, (n - i) as f64 / n as f64);
                assert!(check_triangle(0, 0, u, v, 1).is_ok(), "{n} {i}");
            }
        }
        assert!(check_triangle(0, 0, 0.5, 0.5 + 1e-9, 1).is_err());
        assert!(check_square(0, 0, 1.0, 0.0, 1).is_ok());
        assert!(check_square(0, 0, 1.0 + 1e-9, 0.0, 1).is_err());
        assert!(check_square(0, 1, 0.5, 0.5, 1).is_err());
    }
}
