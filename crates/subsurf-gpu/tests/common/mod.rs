//! Helpers shared by the GPU integration tests.

#![allow(dead_code)]

use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::{Mesh, Topology};
use subsurf_gpu::GpuContext;

/// A regression shape of `testdata/shapes` (`name` without `.obj`) and its patch table at
/// `isolation`.
pub fn load(name: &str, isolation: u32) -> (Mesh, PatchTable) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../testdata/shapes")
        .join(format!("{name}.obj"));
    let mesh = subsurf::io::read_path(&path).unwrap();
    let table = PatchTable::build(
        &Topology::new(&mesh).unwrap(),
        &PatchOptions {
            isolation_level: isolation,
            ..Default::default()
        },
    )
    .unwrap();
    (mesh, table)
}

/// Opens a GPU context. Without an adapter: panics with the installation hint, unless
/// `SUBSURF_SKIP_GPU=1`, in which case it prints a loud SKIPPED line and returns `None`.
pub fn context_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(ctx) => {
            eprintln!("[{test}] adapter: {}", ctx.adapter_info().name);
            Some(ctx)
        }
        Err(e) if std::env::var("SUBSURF_SKIP_GPU").as_deref() == Ok("1") => {
            eprintln!("\n!!!!!!!! SKIPPED GPU TEST `{test}` (SUBSURF_SKIP_GPU=1): {e} !!!!!!!!\n");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// SplitMix64 (Steele, Lea and Flood 2014): a small deterministic generator for test data.
#[derive(Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n`.
    pub fn below(&mut self, n: u32) -> u32 {
        (self.next_u64() % u64::from(n)) as u32
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let u = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * u
    }
}

/// A random CSR stencil table: `rows` rows of `0..=max_len` entries over `sources` source
/// vertices, weights in [-1, 1).
pub struct RandomTable {
    pub offsets: Vec<u32>,
    pub indices: Vec<u32>,
    pub weights: Vec<f32>,
}

pub fn random_table(rng: &mut Rng, rows: usize, sources: u32, max_len: u32) -> RandomTable {
    let mut offsets = Vec::with_capacity(rows + 1);
    offsets.push(0u32);
    let mut indices = Vec::new();
    let mut weights = Vec::new();
    for _ in 0..rows {
        let len = rng.below(max_len + 1);
        for _ in 0..len {
            indices.push(rng.below(sources));
            weights.push(rng.range(-1.0, 1.0));
        }
        offsets.push(indices.len() as u32);
    }
    RandomTable {
        offsets,
        indices,
        weights,
    }
}

pub fn random_values(rng: &mut Rng, n: usize, magnitude: f32) -> Vec<f32> {
    (0..n).map(|_| rng.range(-magnitude, magnitude)).collect()
}

/// Asserts that `gpu` matches the CPU twin's `cpu` within the f32 summation error bound of
/// each output: both differ from the exact sum by at most `γ_n Σ_j |w_j s_jk|`
/// (Higham 2002, §4.2, `γ_n = n u / (1 - n u)`, `u = 2^-24`), so they differ from each other
/// by at most twice that (plus one ulp of slack for fused multiply-adds). No NaN allowed.
pub fn assert_close_to_twin(t: &RandomTable, src: &[f32], stride: usize, gpu: &[f32], cpu: &[f32]) {
    assert_eq!(gpu.len(), cpu.len());
    let u = f32::EPSILON as f64 / 2.0;
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        assert!(g.is_finite(), "GPU output {i} is {g}");
        let (row, k) = (i / stride, i % stride);
        let (b, e) = (t.offsets[row] as usize, t.offsets[row + 1] as usize);
        let n = (e - b) as f64 + 1.0;
        let magnitude: f64 = (b..e)
            .map(|j| (t.weights[j] as f64 * src[t.indices[j] as usize * stride + k] as f64).abs())
            .sum();
        let gamma = n * u / (1.0 - n * u);
        let tol = 2.0 * gamma * magnitude + f32::MIN_POSITIVE as f64;
        let diff = (*g as f64 - *c as f64).abs();
        assert!(
            diff <= tol,
            "output {i} (row {row}, component {k}): GPU {g} vs CPU {c}, |diff| {diff:e} > tolerance {tol:e}"
        );
    }
}

/// The bit patterns of `v`, for comparisons that must be exact.
pub fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}
