//! OpenSubdiv's `Bfr::Tessellation`: the parametric pattern of one face for given outer
//! (per-edge) and inner rates — the reference for subsurf's per-edge tessellation pattern.

use std::os::raw::{c_float, c_int};

use crate::{Error, Result};

/// The parameterization of the face being tessellated (`Bfr::Parameterization::Type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BfrParam {
    /// `QUAD`: one unit square.
    Quad,
    /// `TRI`: one unit triangle.
    Tri,
    /// `QUAD_SUBFACES`: an n-gon as `n` quadrangular sub-faces.
    QuadSubfaces,
}

/// One face's pattern: `(u, v)` samples (boundary first, in edge order from corner 0) and
/// facets of coordinate indices (a triangle has `-1` as fourth index when `facet_size` is 4).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BfrPattern {
    /// The `(u, v)` samples.
    pub coords: Vec<[f32; 2]>,
    /// How many of `coords` lie on the boundary (they come first).
    pub num_boundary: usize,
    /// Facets, `facet_size` indices each.
    pub facets: Vec<[i32; 4]>,
}

#[cfg(not(osd_missing))]
extern "C" {
    #[allow(clippy::too_many_arguments)]
    fn osd_bfr_tessellation(
        param: c_int,
        face_size: c_int,
        num_rates: c_int,
        rates: *const c_int,
        facet_size: c_int,
        preserve_quads: c_int,
        coords: *mut c_float,
        coord_cap: c_int,
        facets: *mut c_int,
        facet_cap: c_int,
        counts: *mut c_int,
    ) -> c_int;
}

/// Stand-in when OpenSubdiv is absent (never reached: [`bfr_tessellation`] checks first).
#[cfg(osd_missing)]
#[allow(clippy::too_many_arguments)]
unsafe fn osd_bfr_tessellation(
    _: c_int,
    _: c_int,
    _: c_int,
    _: *const c_int,
    _: c_int,
    _: c_int,
    _: *mut c_float,
    _: c_int,
    _: *mut c_int,
    _: c_int,
    _: *mut c_int,
) -> c_int {
    -1
}

/// `Bfr::Tessellation(Parameterization(param, face_size), rates, options)` with
/// `SetFacetSize(facet_size)` and `PreserveQuads(preserve_quads)`: its coords and facets.
/// `rates` follows Bfr: the `face_size` outer rates (edge `i` from corner `i` to `i + 1`),
/// then optionally one inner rate (two for a quad); fewer than `face_size` rates are inner
/// rates only.
pub fn bfr_tessellation(
    param: BfrParam,
    face_size: usize,
    rates: &[i32],
    facet_size: usize,
    preserve_quads: bool,
) -> Result<BfrPattern> {
    if !crate::available() {
        return Err(Error::Unavailable);
    }
    if rates.is_empty() || rates.iter().any(|&r| r < 1) || !(3..=4).contains(&facet_size) {
        return Err(Error::Invalid(format!(
            "rates {rates:?} (each >= 1) with facet size {facet_size} (3 or 4)"
        )));
    }
    let raw_param = match param {
        BfrParam::Quad => 0,
        BfrParam::Tri => 1,
        BfrParam::QuadSubfaces => 2,
    };
    let call = |coords: *mut c_float, cc: usize, facets: *mut c_int, fc: usize| {
        let mut counts = [0 as c_int; 3];
        // SAFETY: `rates` is alive for the call and holds `rates.len()` values; `coords` and
        // `facets` are null (count only) or writable for `cc` pairs and `fc` facets.
        let status = unsafe {
            osd_bfr_tessellation(
                raw_param,
                face_size as c_int,
                rates.len() as c_int,
                rates.as_ptr(),
                facet_size as c_int,
                preserve_quads as c_int,
                coords,
                cc as c_int,
                facets,
                fc as c_int,
                counts.as_mut_ptr(),
            )
        };
        (status, counts)
    };
    let (status, counts) = call(std::ptr::null_mut(), 0, std::ptr::null_mut(), 0);
    if status != 0 {
        return Err(Error::Osd(format!(
            "Bfr::Tessellation rejected {param:?} face of size {face_size} with rates {rates:?}"
        )));
    }
    let (nc, nf) = (counts[0] as usize, counts[1] as usize);
    let mut coords = vec![0f32; 2 * nc];
    let mut facets = vec![0 as c_int; facet_size * nf];
    let (status, counts) = call(coords.as_mut_ptr(), nc, facets.as_mut_ptr(), nf);
    if status != 0 {
        return Err(Error::Osd("Bfr::Tessellation: buffer sizes".to_string()));
    }
    Ok(BfrPattern {
        coords: coords.chunks(2).map(|c| [c[0], c[1]]).collect(),
        num_boundary: counts[2] as usize,
        facets: facets
            .chunks(facet_size)
            .map(|f| [f[0], f[1], f[2], if facet_size == 4 { f[3] } else { -1 }])
            .collect(),
    })
}
