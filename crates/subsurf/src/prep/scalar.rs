//! Points of a p-rep construction over the crate's scalar [`Real`]: plain `[T; 3]` arrays and
//! the shared vector helpers ([`crate::util::vec3`]).

pub use crate::real::Real;
pub use crate::util::vec3::{add, axpy, cross, normalize, scale, sub, zero3, V3};
