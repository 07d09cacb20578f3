//! OpenSubdiv's OBJ tag lines: `t NAME nint/nfloat/nstring ints... floats... strings...`.
//!
//! The tags and their meaning follow OpenSubdiv's regression loader (`regression/common/
//! shape_utils.cpp` parses the line, `far_utils.h` interprets it), which in turn follows
//! RenderMan's `SubdivisionMesh` tags:
//!
//! | tag | arity | meaning |
//! |---|---|---|
//! | `crease` | `n/1/0` or `n/(n-1)/0`, n >= 2 | the chain `v0 v1 … v(n-1)` of edges gets sharpness `s` (one per edge, or one for all) |
//! | `corner` | `n/1/0` or `n/n/0` | vertex sharpness |
//! | `hole` | `n/0/0` | faces that are holes |
//! | `interpolateboundary` | `1/0/0` | 0 none, 1 edge-and-corner, 2 edge-only |
//! | `facevaryinginterpolateboundary` | `1/0/0` | 0 none, 1 corners-only, 2 corners+1, 3 corners+2, 4 boundaries, 5 all |
//! | `facevaryingpropagatecorners` | `1/0/0` | 0 or 1 |
//! | `creasemethod` | `0/0/1` | `normal` (or `uniform`), `chaikin` |
//! | `smoothtriangles` | `0/0/1` | `catmark`, `smooth` |
//! | `vertexedit`, `edgeedit`, `faceedit` | any | hierarchical edits: checked for arity, then ignored as OpenSubdiv 3 does |
//!
//! A two-vertex crease (`2/1/0`, the only form in the regression shapes) is one edge under
//! both the chain reading used here and OpenSubdiv's pairwise reading.

use super::parse_error;
use crate::error::Result;
use crate::mesh::{Corner, Crease};
use crate::options::{
    BoundaryInterpolation, CreaseMethod, FVarLinearInterpolation, OptionValue, Options,
    TriangleSubdivision,
};

/// Tags collected while reading, with the line of each element tag for range checks once
/// the vertex and face counts are known.
#[derive(Debug, Default)]
pub(super) struct Tags {
    pub creases: Vec<Crease>,
    pub crease_lines: Vec<usize>,
    pub corners: Vec<Corner>,
    pub corner_lines: Vec<usize>,
    pub holes: Vec<u32>,
    pub hole_lines: Vec<usize>,
    pub options: Options,
}

impl Tags {
    /// Checks that every tagged vertex and face exists.
    pub fn check_ranges(&self, num_vertices: usize, num_faces: usize) -> Result<()> {
        for (c, &line) in self.creases.iter().zip(&self.crease_lines) {
            for v in [c.v0, c.v1] {
                if v as usize >= num_vertices {
                    return Err(parse_error(
                        line,
                        format!("crease tag: vertex {v} is out of range (the mesh has {num_vertices} vertices)"),
                    ));
                }
            }
        }
        for (c, &line) in self.corners.iter().zip(&self.corner_lines) {
            if c.vertex as usize >= num_vertices {
                return Err(parse_error(
                    line,
                    format!(
                        "corner tag: vertex {} is out of range (the mesh has {num_vertices} vertices)",
                        c.vertex
                    ),
                ));
            }
        }
        for (&f, &line) in self.holes.iter().zip(&self.hole_lines) {
            if f as usize >= num_faces {
                return Err(parse_error(
                    line,
                    format!("hole tag: face {f} is out of range (the mesh has {num_faces} faces)"),
                ));
            }
        }
        Ok(())
    }
}

/// The arguments of one tag line, split by kind.
struct TagArgs<'a> {
    name: &'a str,
    ints: Vec<i64>,
    floats: Vec<f32>,
    strings: Vec<&'a str>,
}

/// Parses the tokens after `t` on line `line` and records the tag.
pub(super) fn parse_tag(line: usize, tokens: &[&str], tags: &mut Tags) -> Result<()> {
    let args = split_args(line, tokens)?;
    let arity = (args.ints.len(), args.floats.len(), args.strings.len());
    let bad_arity = |expected: &str| {
        parse_error(
            line,
            format!(
                "tag '{}' expects {expected} arguments, found {}/{}/{}",
                args.name, arity.0, arity.1, arity.2
            ),
        )
    };
    match args.name {
        "crease" => {
            let n = arity.0;
            if n < 2 || arity.2 != 0 || (arity.1 != 1 && arity.1 != n - 1) {
                return Err(bad_arity("n/1/0 or n/(n-1)/0 with n >= 2"));
            }
            let verts = vertex_indices(line, "crease", &args.ints)?;
            for k in 0..n - 1 {
                let sharpness = if arity.1 == 1 {
                    args.floats[0]
                } else {
                    args.floats[k]
                };
                tags.creases.push(Crease {
                    v0: verts[k],
                    v1: verts[k + 1],
                    sharpness,
                });
                tags.crease_lines.push(line);
            }
        }
        "corner" => {
            let n = arity.0;
            if n < 1 || arity.2 != 0 || (arity.1 != 1 && arity.1 != n) {
                return Err(bad_arity("n/1/0 or n/n/0 with n >= 1"));
            }
            let verts = vertex_indices(line, "corner", &args.ints)?;
            for (k, &vertex) in verts.iter().enumerate() {
                let sharpness = if arity.1 == 1 {
                    args.floats[0]
                } else {
                    args.floats[k]
                };
                tags.corners.push(Corner { vertex, sharpness });
                tags.corner_lines.push(line);
            }
        }
        "hole" => {
            if arity.0 < 1 || arity.1 != 0 || arity.2 != 0 {
                return Err(bad_arity("n/0/0 with n >= 1"));
            }
            for &f in &args.ints {
                let f = u32::try_from(f).map_err(|_| {
                    parse_error(
                        line,
                        format!("hole tag: face index {f} is not a valid index"),
                    )
                })?;
                tags.holes.push(f);
                tags.hole_lines.push(line);
            }
        }
        "interpolateboundary" => {
            if arity != (1, 0, 0) {
                return Err(bad_arity("1/0/0"));
            }
            tags.options.boundary = int_tag(line, &args, boundary_tag)?;
        }
        "facevaryinginterpolateboundary" => {
            if arity != (1, 0, 0) {
                return Err(bad_arity("1/0/0"));
            }
            tags.options.uv_interpolation = int_tag(line, &args, uv_interpolation_tag)?;
        }
        "facevaryingpropagatecorners" => {
            if arity != (1, 0, 0) {
                return Err(bad_arity("1/0/0"));
            }
            tags.options.fvar_propagate_corners = match args.ints[0] {
                0 => false,
                1 => true,
                k => {
                    return Err(parse_error(
                        line,
                        format!(
                            "tag '{}': value {k} is not valid (expected 0, 1)",
                            args.name
                        ),
                    ))
                }
            };
        }
        "creasemethod" => {
            if arity != (0, 0, 1) {
                return Err(bad_arity("0/0/1"));
            }
            tags.options.crease_method = string_tag(line, &args, crease_method_tag)?;
        }
        "smoothtriangles" => {
            if arity != (0, 0, 1) {
                return Err(bad_arity("0/0/1"));
            }
            tags.options.triangle_subdivision = string_tag(line, &args, triangle_subdivision_tag)?;
        }
        // Hierarchical edits: OpenSubdiv 3 dropped them; the arity was checked above.
        "vertexedit" | "edgeedit" | "faceedit" => {}
        other => {
            return Err(parse_error(line, format!("unknown tag '{other}'")));
        }
    }
    Ok(())
}

/// The `interpolateboundary` integer of each boundary rule (OpenSubdiv's `Sdc::Options`
/// order, which is not the enum's).
pub(super) fn boundary_tag(b: BoundaryInterpolation) -> i64 {
    match b {
        BoundaryInterpolation::None => 0,
        BoundaryInterpolation::EdgeAndCorner => 1,
        BoundaryInterpolation::EdgeOnly => 2,
    }
}

/// The `facevaryinginterpolateboundary` integer of each UV interpolation rule.
pub(super) fn uv_interpolation_tag(f: FVarLinearInterpolation) -> i64 {
    match f {
        FVarLinearInterpolation::None => 0,
        FVarLinearInterpolation::CornersOnly => 1,
        FVarLinearInterpolation::CornersPlus1 => 2,
        FVarLinearInterpolation::CornersPlus2 => 3,
        FVarLinearInterpolation::Boundaries => 4,
        FVarLinearInterpolation::All => 5,
    }
}

/// The `creasemethod` string of each crease method (RenderMan's `normal` for uniform); the
/// reader also takes the option's own name ([`OptionValue::name`]).
pub(super) fn crease_method_tag(c: CreaseMethod) -> &'static str {
    match c {
        CreaseMethod::Uniform => "normal",
        CreaseMethod::Chaikin => "chaikin",
    }
}

/// The `smoothtriangles` string of each triangle rule.
pub(super) fn triangle_subdivision_tag(t: TriangleSubdivision) -> &'static str {
    match t {
        TriangleSubdivision::Catmark => "catmark",
        TriangleSubdivision::Smooth => "smooth",
    }
}

/// The value of an integer option tag (`1/0/0`, arity checked), through the tag table `tag`.
fn int_tag<T: OptionValue>(line: usize, args: &TagArgs, tag: fn(T) -> i64) -> Result<T> {
    let k = args.ints[0];
    T::find(|v| tag(v) == k).ok_or_else(|| {
        let mut accepted: Vec<i64> = T::ALL.iter().map(|&v| tag(v)).collect();
        accepted.sort_unstable();
        let accepted: Vec<String> = accepted.iter().map(i64::to_string).collect();
        parse_error(
            line,
            format!(
                "tag '{}': value {k} is not valid (expected {})",
                args.name,
                accepted.join(", ")
            ),
        )
    })
}

/// The value of a string option tag (`0/0/1`, arity checked): its tag token or its name.
fn string_tag<T: OptionValue>(
    line: usize,
    args: &TagArgs,
    tag: fn(T) -> &'static str,
) -> Result<T> {
    let s = args.strings[0];
    T::find(|v| tag(v) == s)
        .or_else(|| T::from_name(s).ok())
        .ok_or_else(|| {
            let mut accepted: Vec<&str> = Vec::new();
            for &v in T::ALL {
                for t in [tag(v), v.name()] {
                    if !accepted.contains(&t) {
                        accepted.push(t);
                    }
                }
            }
            parse_error(
                line,
                format!(
                    "tag '{}': unknown value '{s}' (expected {})",
                    args.name,
                    accepted.join(", ")
                ),
            )
        })
}

/// Converts tag integers to vertex indices.
fn vertex_indices(line: usize, kind: &str, ints: &[i64]) -> Result<Vec<u32>> {
    ints.iter()
        .map(|&v| {
            u32::try_from(v).map_err(|_| {
                parse_error(
                    line,
                    format!("{kind} tag: vertex index {v} is not a valid index"),
                )
            })
        })
        .collect()
}

/// Splits `NAME a/b/c args...` into typed arguments, checking the declared counts.
fn split_args<'a>(line: usize, tokens: &[&'a str]) -> Result<TagArgs<'a>> {
    let Some(&name) = tokens.first() else {
        return Err(parse_error(line, "tag line without a name"));
    };
    let Some(&header) = tokens.get(1) else {
        return Err(parse_error(
            line,
            format!("tag '{name}' lacks its nint/nfloat/nstring counts"),
        ));
    };
    let counts: Vec<&str> = header.split('/').collect();
    let malformed = || {
        parse_error(
            line,
            format!("tag '{name}': malformed counts '{header}' (expected nint/nfloat/nstring)"),
        )
    };
    if counts.len() != 3 {
        return Err(malformed());
    }
    let mut n = [0usize; 3];
    for (slot, text) in n.iter_mut().zip(&counts) {
        *slot = text.parse::<usize>().map_err(|_| malformed())?;
    }
    let rest = &tokens[2..];
    let declared = n[0].checked_add(n[1]).and_then(|s| s.checked_add(n[2]));
    if declared != Some(rest.len()) {
        return Err(parse_error(
            line,
            format!(
                "tag '{name}': counts {header} announce {} arguments but {} follow",
                declared.map_or_else(|| "too many".to_string(), |d| d.to_string()),
                rest.len()
            ),
        ));
    }
    let (int_tokens, rest) = rest.split_at(n[0]);
    let (float_tokens, string_tokens) = rest.split_at(n[1]);
    let ints = int_tokens
        .iter()
        .map(|t| {
            t.parse::<i64>()
                .map_err(|_| parse_error(line, format!("tag '{name}': '{t}' is not an integer")))
        })
        .collect::<Result<Vec<_>>>()?;
    let floats = float_tokens
        .iter()
        .map(|t| match t.parse::<f32>() {
            Ok(x) if x.is_nan() => Err(parse_error(
                line,
                format!("tag '{name}': value '{t}' is NaN"),
            )),
            Ok(x) => Ok(x),
            Err(_) => Err(parse_error(
                line,
                format!("tag '{name}': '{t}' is not a number"),
            )),
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(TagArgs {
        name,
        ints,
        floats,
        strings: string_tokens.to_vec(),
    })
}
