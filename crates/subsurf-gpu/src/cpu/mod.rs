//! CPU twins of the WGSL kernels: one file per kernel, same name, same binding order, same
//! `WORKGROUP_SIZE`. Each twin is written as the body of one invocation plus a loop over the
//! dispatch grid, so that it computes exactly what the shader computes, in the same order.

pub mod limit_eval;
pub mod loop_eval;
pub mod prep_eval_grid;
pub mod prep_patch_pass;
pub mod prep_vertex_pass;
pub mod rate_measure;
pub mod refine_level;
pub mod stencil_apply;
