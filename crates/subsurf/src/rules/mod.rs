//! The arithmetic of the subdivision scheme: sharpness decay, crease rules and the weights
//! ("masks") of new points. Nothing here knows about topology: each function is given the
//! sharpness values and counts of one neighbourhood.

pub mod catmark;
pub mod crease;
pub mod r#loop;
