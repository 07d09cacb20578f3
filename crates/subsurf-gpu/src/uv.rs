//! Face-varying refinement (UVs) on the GPU: the per-level value stencils of a
//! [`FVarRefinement`] (OpenSubdiv's `PrimvarRefiner::InterpolateFaceVarying`, in any
//! `FVarLinearInterpolation` mode) uploaded once and applied level after level by
//! [`StencilKernel`] (`stencil_apply`, stride 2), with the values of every level staying on the
//! GPU.
//!
//! Each level's table is already in CSR form over the parent level's values, so the kernel is
//! the plain stencil application `dst_i = Σ_j w_ij src_j` and its CPU twin is
//! [`crate::cpu::stencil_apply`]; chunking against the binding and dispatch limits is the
//! kernel's. The corner-to-value indices of each level depend on the topology only and are
//! taken from the refinement as they are.

use crate::buffers::VertexBuffer;
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::kernels::stencil::{ChunkLimits, StencilKernel};
use crate::table::StencilTable;
use subsurf::refine::FVarRefinement;
use subsurf::FaceVarying;

/// Floats per face-varying value (u, v).
const STRIDE: usize = 2;

/// A [`FVarRefinement`]'s level stencils resident on the GPU, one value buffer per level.
#[derive(Debug)]
pub struct GpuUvRefiner {
    kernels: Vec<StencilKernel>,
    /// `levels[0]` holds the base values, `levels[k]` level `k`'s.
    levels: Vec<VertexBuffer>,
    /// Corner → value indices of the last level.
    last_indices: Vec<u32>,
}

impl GpuUvRefiner {
    /// Uploads every level's table, chunked against the adapter's limits.
    pub fn new(ctx: &GpuContext, fvar: &FVarRefinement) -> Result<Self> {
        Self::with_limits(ctx, fvar, ChunkLimits::from_context(ctx))
    }

    /// Uploads with the given chunk limits (clamped to the adapter's).
    pub fn with_limits(
        ctx: &GpuContext,
        fvar: &FVarRefinement,
        limits: ChunkLimits,
    ) -> Result<Self> {
        let limits = ChunkLimits {
            max_stride: STRIDE,
            ..limits
        };
        let mut levels = Vec::with_capacity(fvar.levels.len());
        for l in &fvar.levels {
            levels.push(VertexBuffer::zeroed(ctx, l.num_values, STRIDE)?);
        }
        let mut kernels = Vec::with_capacity(fvar.stencils.len());
        for (k, s) in fvar.stencils.iter().enumerate() {
            if s.num_rows() != fvar.levels[k + 1].num_values {
                return Err(GpuError::InvalidStencil(format!(
                    "level {} has {} values but its stencils {} rows",
                    k + 1,
                    fvar.levels[k + 1].num_values,
                    s.num_rows()
                )));
            }
            let t = StencilTable::new(s.offsets(), s.indices(), s.weights())?;
            kernels.push(StencilKernel::with_limits(ctx, &t, limits)?);
        }
        let last_indices = fvar
            .levels
            .last()
            .map(|l| l.corner_values.clone())
            .unwrap_or_default();
        Ok(Self {
            kernels,
            levels,
            last_indices,
        })
    }

    /// Number of refinement steps.
    pub fn max_level(&self) -> usize {
        self.kernels.len()
    }

    /// Dispatches per update (one per level, more when a table is chunked).
    pub fn num_dispatches(&self) -> usize {
        self.kernels.iter().map(StencilKernel::num_chunks).sum()
    }

    /// Writes the base values (one per base value index) and submits every level.
    pub fn update(&mut self, ctx: &GpuContext, values: &[[f32; 2]]) -> Result<()> {
        let want = self.levels[0].vertex_count();
        if values.len() != want {
            return Err(GpuError::BufferMismatch(format!(
                "{} base values for a refinement of {want}",
                values.len()
            )));
        }
        self.levels[0].write(ctx, values.as_flattened())?;
        for (k, kernel) in self.kernels.iter().enumerate() {
            let (done, rest) = self.levels.split_at_mut(k + 1);
            kernel.apply(ctx, &done[k], &mut rest[0])?;
        }
        Ok(())
    }

    /// The last level's values on the GPU (2 floats per value).
    pub fn output(&self) -> &VertexBuffer {
        &self.levels[self.levels.len() - 1]
    }

    /// Reads the last level back with its corner indices (waits for the submitted work).
    pub fn download(&self, ctx: &GpuContext) -> Result<FaceVarying> {
        let flat = self.output().download(ctx)?;
        Ok(FaceVarying {
            values: flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
            indices: self.last_indices.clone(),
        })
    }

    /// [`Self::update`] then [`Self::download`].
    pub fn refine(&mut self, ctx: &GpuContext, values: &[[f32; 2]]) -> Result<FaceVarying> {
        self.update(ctx, values)?;
        self.download(ctx)
    }
}
