//! The bottom layer: what every other layer uses and nothing here uses any of them —
//! parallel splitting of flat tables ([`par`]), the memory budget that refuses a request
//! before it allocates ([`budget`]) and the 3-vector helpers of the scalar kernels
//! ([`vec3`]).

pub(crate) mod budget;
pub(crate) mod par;
pub(crate) mod vec3;
