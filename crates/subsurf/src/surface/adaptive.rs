//! The adaptive limit method: per-edge rates from a [`RatePolicy`], the watertight
//! tessellation of `crate::tess`, one class per triangle from the patch under its centroid.
//! The rates are chosen on the backend ([`Backend::adaptive_rates`]: the GPU measures the rate
//! curves with its kernels); the tessellation is evaluated on the CPU (rayon).

use super::limit::patch_class;
use super::{class, Backend, Colors, Surface, SurfaceError};
use crate::limit::tolerance::table_for_tolerance;
use crate::limit::{LimitSurface, PatchOptions, PatchTable};
use crate::tess::{plan, tessellate_within_tolerance, AdaptiveTessellation, EdgeRates, RatePolicy};
use crate::{Mesh, Topology};

/// An adaptive tessellation with what it was made from.
#[derive(Debug, Clone)]
pub struct Adaptive {
    /// The evaluated tessellation.
    pub tessellation: AdaptiveTessellation,
    /// The rates the policy chose (before n-gon edges were made even).
    pub rates: EdgeRates,
    /// Per triangle: its ptex face and its corners' `(u, v)` there.
    pub triangle_uv: Vec<(u32, [[f32; 2]; 3])>,
}

impl Adaptive {
    /// The smallest and largest edge rate used.
    pub fn rate_range(&self) -> (u32, u32) {
        self.tessellation
            .edge_rates
            .iter()
            .fold((u32::MAX, 0), |(lo, hi), &r| (lo.min(r), hi.max(r)))
    }
}

/// Rates of `policy` on `surface` (chosen on `backend`; a tolerance then checked on every
/// triangle, [`tessellate_within_tolerance`]), then the tessellation at those
/// rates (`origin` names where the policy came from in errors: a flag, a file).
pub fn tessellate(
    surface: &LimitSurface,
    policy: &RatePolicy,
    origin: &str,
    backend: &dyn Backend,
) -> Result<Adaptive, SurfaceError> {
    let rates = backend.adaptive_rates(surface, policy, origin)?;
    if let RatePolicy::Tolerance(e) = *policy {
        let (rates, tessellation, triangle_uv) =
            tessellate_within_tolerance(surface, rates, e, origin)?;
        return Ok(Adaptive {
            tessellation,
            rates,
            triangle_uv,
        });
    }
    let mut p = plan(&surface.table, &rates, origin)?;
    let triangle_uv = std::mem::take(&mut p.triangle_uv);
    Ok(Adaptive {
        tessellation: surface.eval_plan(p),
        rates,
        triangle_uv,
    })
}

/// The limit surface to tessellate under `policy`, and the policy of its chords.
///
/// Under [`RatePolicy::Tolerance`]`(e)` the tolerance bounds the whole approximation: the
/// isolation is chosen per region so that the end caps are within `e/4` of the limit surface
/// (`crate::limit::tolerance`), and the chords get the other `3e/4`
/// (`table_for_tolerance`). Where the deepest isolation
/// ([`crate::limit::MAX_ISOLATION_LEVEL`]) leaves end caps further off than `e/4` (a pole of
/// high valence under a small tolerance), the end caps take their estimated distance, up to
/// `e/2`, and the chords the rest. Every other policy takes the table of `options` as it is.
/// A tolerance that is not a positive finite number is refused first, as the rates refuse it;
/// one whose end caps stay further off than `e/2` at the deepest isolation is refused with
/// [`crate::TessError::ToleranceUnreachable`], naming the base face and the estimate.
pub fn adaptive_surface(
    topo: &Topology,
    positions: &[[f32; 3]],
    policy: &RatePolicy,
    origin: &str,
    options: &PatchOptions,
) -> Result<(LimitSurface, RatePolicy), SurfaceError> {
    if let RatePolicy::Tolerance(e) = *policy {
        policy.validate(topo, origin)?;
        let (table, chords) = table_for_tolerance(topo, options, positions, e, origin)?;
        return Ok((
            LimitSurface::new(table, positions),
            RatePolicy::Tolerance(chords),
        ));
    }
    let table = PatchTable::build(topo, options)?;
    Ok((LimitSurface::new(table, positions), policy.clone()))
}

/// The adaptive limit surface of `mesh` under `policy`.
pub fn adaptive(
    mesh: &Mesh,
    policy: &RatePolicy,
    origin: &str,
    options: &PatchOptions,
    colors: Colors,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    let topo = Topology::new(mesh)?;
    let (surface, policy) = adaptive_surface(&topo, &mesh.positions, policy, origin, options)?;
    let a = tessellate(&surface, &policy, origin, backend)?;
    let table = &surface.table;
    let triangle_class = a
        .triangle_uv
        .iter()
        .map(|(ptex, c)| {
            let u = (c[0][0] + c[1][0] + c[2][0]) / 3.0;
            let v = (c[0][1] + c[1][1] + c[2][1]) / 3.0;
            table
                .patch_map
                .find(*ptex as usize, u, v)
                .map_or(class::PLAIN, |p| patch_class(table, p as usize, colors))
        })
        .collect();
    let (lo, hi) = a.rate_range();
    let t = a.tessellation;
    Ok(Surface {
        summary: format!(
            "{origin}: edge rates {lo}..={hi} on {} ptex faces, {} triangles",
            table.num_ptex_faces(),
            t.triangles.len()
        ),
        positions: t.positions,
        normals: t.normals,
        triangles: t.triangles,
        triangle_class,
        ..Default::default()
    })
}
