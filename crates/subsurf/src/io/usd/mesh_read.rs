//! A `UsdGeomMesh` prim to a [`Mesh`]: topology, tags, options and `primvars:st`.
//!
//! Unauthored options take USD's defaults (Pixar's UsdGeomMesh schema), not OBJ's:
//! `subdivisionScheme` catmullClark, `interpolateBoundary` edgeAndCorner,
//! `faceVaryingLinearInterpolation` cornersPlus1, `triangleSubdivisionRule` catmullClark,
//! `orientation` rightHanded. A leftHanded mesh has each face's winding flipped as
//! OpenSubdiv's USD consumers do (the first corner kept, the others reversed), its
//! face-varying corners with it.

use super::attrs::PrimReader;
use super::mesh_write::{
    boundary_token, scheme_token, triangle_subdivision_token, uv_interpolation_token,
};
use crate::error::Result;
use crate::mesh::{Corner, Crease, FaceVarying, Mesh};
use crate::options::{
    BoundaryInterpolation, FVarLinearInterpolation, OptionValue, Options, Scheme,
    TriangleSubdivision,
};

/// A mesh prim as read: the cage, and whether it is to be subdivided at all
/// (`subdivisionScheme = "none"` marks a polygon mesh).
pub(super) struct ReadMesh {
    pub mesh: Mesh,
    pub subdivide: bool,
}

/// Reads the mesh prim `r.prim`.
pub(super) fn read_mesh(r: &PrimReader) -> Result<ReadMesh> {
    let positions = r
        .points("points")?
        .ok_or_else(|| r.error("points", "no points authored"))?;
    let face_counts = r.ints("faceVertexCounts")?.unwrap_or_default();
    let mut counts = Vec::with_capacity(face_counts.len());
    let mut total = 0u64;
    for (f, &n) in face_counts.iter().enumerate() {
        if n < 0 {
            return Err(r.error("faceVertexCounts", format!("face {f} has {n} vertices")));
        }
        total += n as u64;
        counts.push(n as u32);
    }
    let mut indices = r
        .indices("faceVertexIndices", positions.len(), "points")?
        .unwrap_or_default();
    if total != indices.len() as u64 {
        return Err(r.error(
            "faceVertexIndices",
            format!(
                "faceVertexCounts add up to {total} corners but {} indices are given",
                indices.len()
            ),
        ));
    }
    let (mut options, subdivide) = read_options(r)?;
    let left = match r.token("orientation")?.as_deref() {
        None | Some("rightHanded") => false,
        Some("leftHanded") => true,
        Some(other) => return Err(bad_token(r, "orientation", other)),
    };
    let mut uvs = read_st(r, &indices)?;
    if left {
        flip_faces(&counts, &mut indices);
        if let Some(uv) = &mut uvs {
            flip_faces(&counts, &mut uv.indices);
        }
    }
    let n = positions.len();
    let creases = read_creases(r, n)?;
    let corners = read_corners(r, n)?;
    let holes = r
        .indices("holeIndices", counts.len(), "faces")?
        .unwrap_or_default();
    options.fvar_propagate_corners = false;
    Ok(ReadMesh {
        mesh: Mesh {
            positions,
            face_counts: counts,
            face_indices: indices,
            uvs,
            creases,
            corners,
            holes,
            options,
        },
        subdivide,
    })
}

fn bad_token(r: &PrimReader, attr: &str, value: &str) -> crate::Error {
    r.error(attr, format!("unknown value \"{value}\""))
}

/// The value whose USD token (`table`, from `mesh_write`) is `t`.
fn token<T: OptionValue>(
    r: &PrimReader,
    attr: &str,
    t: &str,
    table: fn(T) -> &'static str,
) -> Result<T> {
    T::find(|v| table(v) == t).ok_or_else(|| {
        let accepted: Vec<&str> = T::ALL.iter().map(|&v| table(v)).collect();
        r.error(
            attr,
            format!("unknown value \"{t}\" (expected {})", accepted.join(", ")),
        )
    })
}

/// The subdivision options, with USD's defaults, and whether the mesh subdivides.
fn read_options(r: &PrimReader) -> Result<(Options, bool)> {
    let mut o = Options::default();
    let mut subdivide = true;
    o.scheme = match r.token("subdivisionScheme")?.as_deref() {
        None => Scheme::Catmark,
        Some("none") => {
            subdivide = false;
            Scheme::Bilinear
        }
        Some(t) => token(r, "subdivisionScheme", t, scheme_token)?,
    };
    o.boundary = match r.token("interpolateBoundary")?.as_deref() {
        None => BoundaryInterpolation::EdgeAndCorner,
        Some(t) => token(r, "interpolateBoundary", t, boundary_token)?,
    };
    o.uv_interpolation = match r.token("faceVaryingLinearInterpolation")?.as_deref() {
        None => FVarLinearInterpolation::CornersPlus1,
        Some(t) => token(
            r,
            "faceVaryingLinearInterpolation",
            t,
            uv_interpolation_token,
        )?,
    };
    o.triangle_subdivision = match r.token("triangleSubdivisionRule")?.as_deref() {
        None => TriangleSubdivision::Catmark,
        Some(t) => token(r, "triangleSubdivisionRule", t, triangle_subdivision_token)?,
    };
    Ok((o, subdivide))
}

/// Flips each face's winding in place, keeping its first corner.
pub(super) fn flip_faces(counts: &[u32], corners: &mut [u32]) {
    let mut start = 0usize;
    for &n in counts {
        let n = n as usize;
        if n > 1 {
            corners[start + 1..start + n].reverse();
        }
        start += n;
    }
}

/// Crease chains: `creaseLengths[i]` vertices each, one sharpness per chain or one per edge.
fn read_creases(r: &PrimReader, num_vertices: usize) -> Result<Vec<Crease>> {
    let indices = r
        .indices("creaseIndices", num_vertices, "points")?
        .unwrap_or_default();
    let lengths = r.ints("creaseLengths")?.unwrap_or_default();
    let sharp = r.floats("creaseSharpnesses")?.unwrap_or_default();
    let mut edges = 0u64;
    let mut total = 0u64;
    for (i, &n) in lengths.iter().enumerate() {
        if n < 2 {
            return Err(r.error(
                "creaseLengths",
                format!("crease {i} has {n} vertices (at least 2 are needed)"),
            ));
        }
        total += n as u64;
        edges += n as u64 - 1;
    }
    if total != indices.len() as u64 {
        return Err(r.error(
            "creaseIndices",
            format!(
                "creaseLengths add up to {total} vertices but {} indices are given",
                indices.len()
            ),
        ));
    }
    let per_edge = if sharp.len() == lengths.len() {
        false
    } else if sharp.len() as u64 == edges {
        true
    } else {
        return Err(r.error(
            "creaseSharpnesses",
            format!(
                "{} sharpnesses for {} creases of {edges} edges (one per crease or one per edge)",
                sharp.len(),
                lengths.len()
            ),
        ));
    };
    let mut out = Vec::with_capacity(edges as usize);
    let mut start = 0usize;
    for (c, &n) in lengths.iter().enumerate() {
        let chain = &indices[start..start + n as usize];
        for w in chain.windows(2) {
            let s = if per_edge { sharp[out.len()] } else { sharp[c] };
            out.push(Crease {
                v0: w[0],
                v1: w[1],
                sharpness: s,
            });
        }
        start += n as usize;
    }
    Ok(out)
}

fn read_corners(r: &PrimReader, num_vertices: usize) -> Result<Vec<Corner>> {
    let indices = r
        .indices("cornerIndices", num_vertices, "points")?
        .unwrap_or_default();
    let sharp = r.floats("cornerSharpnesses")?.unwrap_or_default();
    if sharp.len() != indices.len() {
        return Err(r.error(
            "cornerSharpnesses",
            format!(
                "{} sharpnesses for {} corner indices",
                sharp.len(),
                indices.len()
            ),
        ));
    }
    Ok(indices
        .into_iter()
        .zip(sharp)
        .map(|(vertex, sharpness)| Corner { vertex, sharpness })
        .collect())
}

/// `primvars:st` as face-varying UVs: faceVarying (indexed or not), or vertex (one value per
/// point, shared by every corner of it). Other interpolations carry no per-corner UVs and are
/// left out.
fn read_st(r: &PrimReader, indices: &[u32]) -> Result<Option<FaceVarying>> {
    const ST: &str = "primvars:st";
    let Some(values) = r.vec2s(ST)? else {
        return Ok(None);
    };
    let interp = match r.field(ST, "interpolation")? {
        None => "constant".to_string(),
        Some(openusd::sdf::Value::Token(t)) => t.as_str().to_string(),
        Some(openusd::sdf::Value::String(s)) => s,
        Some(_) => return Err(r.error(ST, "interpolation is not a token")),
    };
    let corners = indices.len();
    let st_indices = r.indices("primvars:st:indices", values.len(), "st values")?;
    let fv_indices = match (interp.as_str(), st_indices) {
        ("faceVarying", Some(ix)) => {
            if ix.len() != corners {
                return Err(r.error(
                    "primvars:st:indices",
                    format!("{} indices for {corners} face corners", ix.len()),
                ));
            }
            ix
        }
        ("faceVarying", None) => {
            if values.len() != corners {
                return Err(r.error(
                    ST,
                    format!(
                        "{} faceVarying values for {corners} face corners",
                        values.len()
                    ),
                ));
            }
            (0..corners as u32).collect()
        }
        ("vertex" | "varying", ix) => {
            let per_point = match ix {
                Some(ix) => ix,
                None => (0..values.len() as u32).collect(),
            };
            let mut out = Vec::with_capacity(corners);
            for &v in indices {
                match per_point.get(v as usize) {
                    Some(&i) => out.push(i),
                    None => {
                        return Err(r.error(
                            ST,
                            format!(
                                "{interp} st has {} values, point {v} has none",
                                per_point.len()
                            ),
                        ))
                    }
                }
            }
            out
        }
        ("constant" | "uniform", _) => return Ok(None),
        (other, _) => return Err(r.error(ST, format!("unknown interpolation \"{other}\""))),
    };
    Ok(Some(FaceVarying {
        values,
        indices: fv_indices,
    }))
}
