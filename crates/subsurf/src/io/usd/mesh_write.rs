//! A [`Mesh`] into a `UsdGeomMesh` prim's attribute specs, replacing what the prim had.
//!
//! A cage is written with its tags and every option authored (USD's defaults are not OBJ's,
//! so nothing is left to them); a refined mesh is written as a polygon mesh
//! (`subdivisionScheme = "none"`) that keeps its holes. Creases are written as two-vertex
//! chains with one sharpness each. Attributes that no longer match the new points and faces
//! (normals, velocities, non-constant primvars) are removed; `extent` is recomputed.

use crate::mesh::Mesh;
use crate::options::{BoundaryInterpolation, FVarLinearInterpolation, Scheme, TriangleSubdivision};
use openusd::gf;
use openusd::sdf::{self, schema::ChildrenKey, schema::FieldKey, SpecType, Value, Variability};

/// USD's `subdivisionScheme` token of each scheme (`none`, a polygon mesh, is no scheme).
/// These four functions are USD's one token table; `mesh_read` inverts them.
pub(super) fn scheme_token(s: Scheme) -> &'static str {
    match s {
        Scheme::Catmark => "catmullClark",
        Scheme::Bilinear => "bilinear",
        Scheme::Loop => "loop",
    }
}

/// USD's `interpolateBoundary` token of each boundary rule.
pub(super) fn boundary_token(b: BoundaryInterpolation) -> &'static str {
    match b {
        BoundaryInterpolation::None => "none",
        BoundaryInterpolation::EdgeOnly => "edgeOnly",
        BoundaryInterpolation::EdgeAndCorner => "edgeAndCorner",
    }
}

/// USD's `faceVaryingLinearInterpolation` token of each UV interpolation rule.
pub(super) fn uv_interpolation_token(f: FVarLinearInterpolation) -> &'static str {
    match f {
        FVarLinearInterpolation::None => "none",
        FVarLinearInterpolation::CornersOnly => "cornersOnly",
        FVarLinearInterpolation::CornersPlus1 => "cornersPlus1",
        FVarLinearInterpolation::CornersPlus2 => "cornersPlus2",
        FVarLinearInterpolation::Boundaries => "boundaries",
        FVarLinearInterpolation::All => "all",
    }
}

/// USD's `triangleSubdivisionRule` token of each triangle rule.
pub(super) fn triangle_subdivision_token(t: TriangleSubdivision) -> &'static str {
    match t {
        TriangleSubdivision::Catmark => "catmullClark",
        TriangleSubdivision::Smooth => "smooth",
    }
}

/// Attributes of a mesh prim that describe its points, faces or tags: all replaced.
const REPLACED: &[&str] = &[
    "points",
    "faceVertexCounts",
    "faceVertexIndices",
    "extent",
    "normals",
    "velocities",
    "accelerations",
    "orientation",
    "subdivisionScheme",
    "interpolateBoundary",
    "faceVaryingLinearInterpolation",
    "triangleSubdivisionRule",
    "creaseIndices",
    "creaseLengths",
    "creaseSharpnesses",
    "cornerIndices",
    "cornerSharpnesses",
    "holeIndices",
];

fn property_names(data: &sdf::Data, prim: &sdf::Path) -> Vec<String> {
    match data
        .spec(prim)
        .and_then(|s| s.get(ChildrenKey::PropertyChildren.as_str()))
    {
        Some(Value::TokenVec(v)) => v.iter().map(|t| t.as_str().to_string()).collect(),
        _ => Vec::new(),
    }
}

fn set_property_names(data: &mut sdf::Data, prim: &sdf::Path, names: Vec<String>) {
    if let Some(spec) = data.spec_mut(prim) {
        spec.add(
            ChildrenKey::PropertyChildren.as_str(),
            Value::token_vec(names),
        );
    }
}

/// Whether a primvar keeps its meaning on a refined mesh (only `constant` ones do).
fn is_constant_primvar(data: &sdf::Data, path: &sdf::Path) -> bool {
    matches!(
        data.spec(path).and_then(|s| s.get("interpolation")),
        Some(Value::Token(t)) if t.as_str() == "constant"
    )
}

/// Removes the prim's attributes that `mesh` replaces.
fn clear(data: &mut sdf::Data, prim: &sdf::Path) {
    let mut keep = Vec::new();
    for name in property_names(data, prim) {
        let Ok(path) = prim.append_property(name.as_str()) else {
            continue;
        };
        let base = name.strip_suffix(":indices").unwrap_or(&name);
        let stale = REPLACED.contains(&name.as_str())
            || (name.starts_with("primvars:")
                && !prim
                    .append_property(base)
                    .is_ok_and(|p| is_constant_primvar(data, &p)));
        if stale {
            data.erase_spec(&path);
        } else {
            keep.push(name);
        }
    }
    set_property_names(data, prim, keep);
}

/// Authors one attribute (replacing any spec of that name) and lists it on the prim.
fn set(
    data: &mut sdf::Data,
    prim: &sdf::Path,
    name: &str,
    type_name: &str,
    uniform: bool,
    value: Value,
    extra: &[(&str, Value)],
) {
    let Ok(path) = prim.append_property(name) else {
        return;
    };
    let spec = data.create_spec(path, SpecType::Attribute);
    spec.add(FieldKey::TypeName.as_str(), Value::token(type_name));
    if uniform {
        spec.add(
            FieldKey::Variability.as_str(),
            Value::Variability(Variability::Uniform),
        );
    }
    spec.add(FieldKey::Default.as_str(), value);
    for (k, v) in extra {
        spec.add(k, v.clone());
    }
    let mut names = property_names(data, prim);
    if !names.iter().any(|n| n == name) {
        names.push(name.to_string());
        set_property_names(data, prim, names);
    }
}

fn ints(v: &[u32]) -> Value {
    Value::IntVec(v.iter().map(|&x| x as i32).collect())
}

/// Writes `mesh` into the prim at `prim` (which must have a spec): as a cage with its tags
/// and options, or, when `refined`, as a polygon mesh.
/// With `f64_points`, positions held in `f64` are written as `point3d[]` (the schema's type is
/// `point3f[]`).
pub(super) fn write_mesh(
    data: &mut sdf::Data,
    prim: &sdf::Path,
    mesh: &Mesh,
    refined: bool,
    f64_points: bool,
) {
    clear(data, prim);
    let (ty, points) = match mesh.positions.as_f64() {
        Some(v) if f64_points => (
            "point3d[]",
            Value::Vec3dVec(v.iter().map(|&[x, y, z]| gf::Vec3d { x, y, z }).collect()),
        ),
        _ => (
            "point3f[]",
            Value::Vec3fVec(mesh.positions.iter().map(|&p| p.into()).collect()),
        ),
    };
    set(data, prim, "points", ty, false, points, &[]);
    let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [0.0; 3]));
    let extent = vec![gf::Vec3f::from(lo), gf::Vec3f::from(hi)];
    set(
        data,
        prim,
        "extent",
        "float3[]",
        false,
        Value::Vec3fVec(extent),
        &[],
    );
    set(
        data,
        prim,
        "faceVertexCounts",
        "int[]",
        false,
        ints(&mesh.face_counts),
        &[],
    );
    set(
        data,
        prim,
        "faceVertexIndices",
        "int[]",
        false,
        ints(&mesh.face_indices),
        &[],
    );
    let token = |s: &str| Value::token(s);
    set(
        data,
        prim,
        "orientation",
        "token",
        true,
        token("rightHanded"),
        &[],
    );
    if !mesh.holes.is_empty() {
        set(
            data,
            prim,
            "holeIndices",
            "int[]",
            false,
            ints(&mesh.holes),
            &[],
        );
    }
    let o = &mesh.options;
    let fvar = uv_interpolation_token(o.uv_interpolation);
    // A refined mesh is a polygon mesh; a cage states its scheme.
    let scheme = match o.scheme {
        _ if refined => "none",
        s => scheme_token(s),
    };
    set(
        data,
        prim,
        "subdivisionScheme",
        "token",
        true,
        token(scheme),
        &[],
    );
    if !refined {
        let boundary = boundary_token(o.boundary);
        set(
            data,
            prim,
            "interpolateBoundary",
            "token",
            false,
            token(boundary),
            &[],
        );
        let tri = triangle_subdivision_token(o.triangle_subdivision);
        set(
            data,
            prim,
            "triangleSubdivisionRule",
            "token",
            false,
            token(tri),
            &[],
        );
        write_tags(data, prim, mesh);
    }
    // The face-varying rule also says how the st values were made; kept on refined meshes.
    set(
        data,
        prim,
        "faceVaryingLinearInterpolation",
        "token",
        false,
        token(fvar),
        &[],
    );
    if let Some(uv) = &mesh.uvs {
        let values: Vec<gf::Vec2f> = uv.values.iter().map(|&v| v.into()).collect();
        let interp = [("interpolation", token("faceVarying"))];
        set(
            data,
            prim,
            "primvars:st",
            "texCoord2f[]",
            false,
            Value::Vec2fVec(values),
            &interp,
        );
        set(
            data,
            prim,
            "primvars:st:indices",
            "int[]",
            false,
            ints(&uv.indices),
            &[],
        );
    }
}

fn write_tags(data: &mut sdf::Data, prim: &sdf::Path, mesh: &Mesh) {
    if !mesh.creases.is_empty() {
        let idx: Vec<u32> = mesh.creases.iter().flat_map(|c| [c.v0, c.v1]).collect();
        let lengths = vec![2u32; mesh.creases.len()];
        let sharp = mesh.creases.iter().map(|c| c.sharpness).collect();
        set(data, prim, "creaseIndices", "int[]", false, ints(&idx), &[]);
        set(
            data,
            prim,
            "creaseLengths",
            "int[]",
            false,
            ints(&lengths),
            &[],
        );
        set(
            data,
            prim,
            "creaseSharpnesses",
            "float[]",
            false,
            Value::FloatVec(sharp),
            &[],
        );
    }
    if !mesh.corners.is_empty() {
        let idx: Vec<u32> = mesh.corners.iter().map(|c| c.vertex).collect();
        let sharp = mesh.corners.iter().map(|c| c.sharpness).collect();
        set(data, prim, "cornerIndices", "int[]", false, ints(&idx), &[]);
        set(
            data,
            prim,
            "cornerSharpnesses",
            "float[]",
            false,
            Value::FloatVec(sharp),
            &[],
        );
    }
}
