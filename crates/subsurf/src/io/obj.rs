//! Wavefront OBJ with OpenSubdiv's tag lines.
//!
//! Read: `v x y z [w ...]` (columns after z are ignored), `vt u [v [w]]`, `vn x y z` (checked,
//! then dropped), `f` with corners `a`, `a/b`, `a/b/c` or `a//c`, 1-based or negative
//! (relative) indices, polygons of any size, `#` comments, CRLF line ends, `\` line
//! continuation, and the `t` tags described in the `obj_tags` module. `o g s usemtl mtllib l p`
//! and the other display statements are ignored.
//!
//! Texture coordinates become face-varying data: if the faces carry `vt` indices every face
//! must, and [`Mesh::uvs`] holds the `vt` values with one index per face corner.
//!
//! OBJ has no subdivision scheme: [`read`] gives Catmull-Clark, [`read_with_scheme`] takes it
//! from the caller and [`read_file`] from the file name prefix ([`scheme_from_name`]).
//!
//! Write: [`write()`] emits `v`, `vt`, `f` and every tag and non-default option as `t` lines, so
//! that reading the output gives back the same [`Mesh`] (floats use Rust's shortest
//! round-trip formatting). [`write_with_normals`] adds one `vn` per vertex.

use super::obj_tags::{
    boundary_tag, crease_method_tag, parse_tag, triangle_subdivision_tag, uv_interpolation_tag,
    Tags,
};
use super::parse_error;
use crate::error::{Error, Result};
use crate::mesh::{FaceVarying, Mesh, Positions};
use crate::options::{OptionValue, Options, Scheme};
use std::io::Write;
use std::path::Path;

/// The scheme named by a shape file's stem: `catmark_*` Catmull-Clark, `bilinear_*` bilinear,
/// `loop_*` Loop (the convention of OpenSubdiv's regression shapes); `None` otherwise.
pub fn scheme_from_name(file_stem: &str) -> Option<Scheme> {
    let has_prefix = |p: &str| {
        file_stem == p
            || file_stem
                .strip_prefix(p)
                .is_some_and(|rest| rest.starts_with('_'))
    };
    // The prefixes are the schemes' own names.
    Scheme::find(|s| has_prefix(s.name()))
}

/// Reads an OBJ file; the scheme comes from the file name ([`scheme_from_name`]), Catmull-Clark
/// when the name has no scheme prefix. Bytes that are not UTF-8 are replaced (they can only
/// matter inside comments).
pub fn read_file(path: impl AsRef<Path>) -> Result<Mesh> {
    let path = path.as_ref();
    let bytes = std::fs::read(path)?;
    let text = String::from_utf8_lossy(&bytes);
    let scheme = path
        .file_stem()
        .and_then(|s| s.to_str())
        .and_then(scheme_from_name)
        .unwrap_or_default();
    read_with_scheme(&text, scheme)
}

/// Reads OBJ text as a Catmull-Clark mesh.
pub fn read(text: &str) -> Result<Mesh> {
    read_with_scheme(text, Scheme::Catmark)
}

/// Reads OBJ text, setting [`Options::scheme`] to `scheme`.
pub fn read_with_scheme(text: &str, scheme: Scheme) -> Result<Mesh> {
    let mut r = Reader::default();
    let mut pending = String::new();
    let mut pending_line = 0;
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        // `\` at the end of a line joins it with the next one.
        if let Some(head) = raw.trim_end().strip_suffix('\\') {
            if pending.is_empty() {
                pending_line = line_no;
            }
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        if pending.is_empty() {
            r.statement(line_no, raw)?;
        } else {
            pending.push_str(raw);
            let joined = std::mem::take(&mut pending);
            r.statement(pending_line, &joined)?;
        }
    }
    if !pending.is_empty() {
        let joined = std::mem::take(&mut pending);
        r.statement(pending_line, &joined)?;
    }
    r.finish(scheme)
}

/// Reader state: what has been read so far.
#[derive(Debug, Default)]
struct Reader {
    /// Positions as written (f64: the file's digits, rounded once).
    positions: Vec<[f64; 3]>,
    uv_values: Vec<[f32; 2]>,
    num_normals: usize,
    face_counts: Vec<u32>,
    face_indices: Vec<u32>,
    uv_indices: Vec<u32>,
    /// Line of each face, for range errors found at the end.
    face_lines: Vec<usize>,
    /// (line, largest normal index) of faces with normal indices.
    normal_refs: Vec<(usize, u32)>,
    /// Whether faces carry `vt` indices, and the line of the first face (decided by it).
    faces_have_uv: Option<(bool, usize)>,
    tags: Tags,
}

/// One face corner: vertex, optional texture and normal indices (0-based, resolved).
struct CornerRef {
    v: u32,
    t: Option<u32>,
    n: Option<u32>,
}

impl Reader {
    fn statement(&mut self, line: usize, text: &str) -> Result<()> {
        let text = match text.find('#') {
            Some(k) => &text[..k],
            None => text,
        };
        let mut tokens = text.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            return Ok(());
        };
        let args: Vec<&str> = tokens.collect();
        match keyword {
            "v" => {
                if args.len() < 3 {
                    return Err(parse_error(
                        line,
                        format!("'v' needs 3 coordinates, found {}", args.len()),
                    ));
                }
                let p = [
                    coordinate_f64(line, args[0])?,
                    coordinate_f64(line, args[1])?,
                    coordinate_f64(line, args[2])?,
                ];
                self.positions.push(p);
            }
            "vt" => {
                if args.is_empty() {
                    return Err(parse_error(line, "'vt' needs at least 1 coordinate"));
                }
                let u = coordinate(line, args[0])?;
                let v = match args.get(1) {
                    Some(t) => coordinate(line, t)?,
                    None => 0.0,
                };
                if let Some(t) = args.get(2) {
                    coordinate(line, t)?;
                }
                self.uv_values.push([u, v]);
            }
            "vn" => {
                if args.len() != 3 {
                    return Err(parse_error(
                        line,
                        format!("'vn' needs 3 coordinates, found {}", args.len()),
                    ));
                }
                for t in &args {
                    coordinate(line, t)?;
                }
                self.num_normals += 1;
            }
            "f" => self.face(line, &args)?,
            "t" => parse_tag(line, &args, &mut self.tags)?,
            // Grouping, display and material statements do not affect the surface.
            "o" | "g" | "s" | "usemtl" | "mtllib" | "l" | "p" | "vp" | "mg" | "maplib"
            | "usemap" | "lod" | "bevel" | "c_interp" | "d_interp" | "shadow_obj" | "trace_obj"
            | "ctech" | "stech" => {}
            "cstype" | "deg" | "bmat" | "step" | "curv" | "curv2" | "surf" | "parm" | "trim"
            | "hole" | "scrv" | "sp" | "end" | "con" => {
                return Err(Error::Parse {
                    line,
                    reason: format!("free-form geometry ('{keyword}') is not supported"),
                });
            }
            other => {
                let shown: String = other.chars().take(32).collect();
                return Err(parse_error(line, format!("unknown statement '{shown}'")));
            }
        }
        Ok(())
    }

    fn face(&mut self, line: usize, args: &[&str]) -> Result<()> {
        if args.len() < 3 {
            return Err(parse_error(
                line,
                format!("face has {} vertices (at least 3 are needed)", args.len()),
            ));
        }
        let count = u32::try_from(args.len())
            .map_err(|_| parse_error(line, "face has too many vertices"))?;
        let mut max_normal = None;
        let mut face_has_uv = None;
        for (k, token) in args.iter().enumerate() {
            let c = self.corner(line, token)?;
            let has_uv = c.t.is_some();
            match face_has_uv {
                None => face_has_uv = Some(has_uv),
                Some(h) if h != has_uv => {
                    return Err(parse_error(
                        line,
                        format!(
                            "face corner {} has texture index presence different from corner 1",
                            k + 1
                        ),
                    ));
                }
                Some(_) => {}
            }
            self.face_indices.push(c.v);
            if let Some(t) = c.t {
                self.uv_indices.push(t);
            }
            if let Some(n) = c.n {
                max_normal = Some(max_normal.map_or(n, |m: u32| m.max(n)));
            }
        }
        let has_uv = face_has_uv.unwrap_or(false);
        match self.faces_have_uv {
            None => self.faces_have_uv = Some((has_uv, line)),
            Some((first, first_line)) if first != has_uv => {
                let (with, without) = if has_uv {
                    ("has", "had none")
                } else {
                    ("has none", "had them")
                };
                return Err(parse_error(
                    line,
                    format!("face {with} texture (vt) indices but the first face (line {first_line}) {without}; all faces must agree"),
                ));
            }
            Some(_) => {}
        }
        if let Some(n) = max_normal {
            self.normal_refs.push((line, n));
        }
        self.face_counts.push(count);
        self.face_lines.push(line);
        Ok(())
    }

    fn corner(&self, line: usize, token: &str) -> Result<CornerRef> {
        let mut parts = token.split('/');
        let v_text = parts.next().unwrap_or("");
        let t_text = parts.next();
        let n_text = parts.next();
        if parts.next().is_some() {
            return Err(parse_error(
                line,
                format!("face corner '{token}' has more than 3 indices"),
            ));
        }
        let v = resolve(line, "vertex", v_text, self.positions.len())?;
        let t = match (t_text, n_text) {
            (None, _) => None,
            (Some(""), Some(n)) if !n.is_empty() => None,
            (Some(t), _) => Some(resolve(line, "texture", t, self.uv_values.len())?),
        };
        let n = match n_text {
            None => None,
            Some(n) => Some(resolve(line, "normal", n, self.num_normals)?),
        };
        Ok(CornerRef { v, t, n })
    }

    fn finish(self, scheme: Scheme) -> Result<Mesh> {
        let Reader {
            positions,
            uv_values,
            num_normals,
            face_counts,
            face_indices,
            uv_indices,
            face_lines,
            normal_refs,
            faces_have_uv,
            tags,
        } = self;
        // Positive indices may point forward; check them now that all counts are known.
        let has_uv = matches!(faces_have_uv, Some((true, _)));
        let mut start = 0usize;
        for (&n, &line) in face_counts.iter().zip(&face_lines) {
            let end = start + n as usize;
            for &v in &face_indices[start..end] {
                if v as usize >= positions.len() {
                    return Err(out_of_range(line, "vertex", v, positions.len()));
                }
            }
            if has_uv {
                for &t in &uv_indices[start..end] {
                    if t as usize >= uv_values.len() {
                        return Err(out_of_range(line, "texture", t, uv_values.len()));
                    }
                }
            }
            start = end;
        }
        for &(line, n) in &normal_refs {
            if n as usize >= num_normals {
                return Err(out_of_range(line, "normal", n, num_normals));
            }
        }
        tags.check_ranges(positions.len(), face_counts.len())?;
        let uvs = has_uv.then_some(FaceVarying {
            values: uv_values,
            indices: uv_indices,
        });
        Ok(Mesh {
            positions: Positions::from_f64_compact(positions),
            face_counts,
            face_indices,
            uvs,
            creases: tags.creases,
            corners: tags.corners,
            holes: tags.holes,
            options: Options {
                scheme,
                ..tags.options
            },
        })
    }
}

fn out_of_range(line: usize, kind: &str, index: u32, count: usize) -> Error {
    parse_error(
        line,
        format!(
            "{kind} index {} is out of range (the file has {count} {kind} entries)",
            index as u64 + 1
        ),
    )
}

/// Parses a finite coordinate.
/// A position coordinate: the file's digits in `f64` (within the `f32` range, so that the
/// `f32` tables see a finite value too).
fn coordinate_f64(line: usize, token: &str) -> Result<f64> {
    match token.parse::<f64>() {
        Ok(x) if (x as f32).is_finite() => Ok(x),
        Ok(_) => Err(parse_error(
            line,
            format!("coordinate '{}' is not finite in f32", truncate(token)),
        )),
        Err(_) => Err(parse_error(
            line,
            format!("'{}' is not a number", truncate(token)),
        )),
    }
}

fn coordinate(line: usize, token: &str) -> Result<f32> {
    match token.parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(parse_error(
            line,
            format!("coordinate '{token}' is not finite"),
        )),
        Err(_) => Err(parse_error(
            line,
            format!("'{}' is not a number", truncate(token)),
        )),
    }
}

/// Resolves a 1-based or negative (relative to the `count` entries so far) OBJ index to a
/// 0-based one. Positive indices are range-checked later, when all entries are known.
fn resolve(line: usize, kind: &str, token: &str, count: usize) -> Result<u32> {
    let i: i64 = token.parse().map_err(|_| {
        parse_error(
            line,
            format!("{kind} index '{}' is not an integer", truncate(token)),
        )
    })?;
    if i == 0 {
        return Err(parse_error(
            line,
            format!("{kind} index 0 is invalid (OBJ indices start at 1)"),
        ));
    }
    let resolved = if i > 0 {
        i - 1
    } else {
        let r = count as i64 + i;
        if r < 0 {
            return Err(parse_error(
                line,
                format!("relative {kind} index {i} reaches before the first entry ({count} defined so far)"),
            ));
        }
        r
    };
    u32::try_from(resolved).map_err(|_| parse_error(line, format!("{kind} index {i} is too large")))
}

fn truncate(token: &str) -> String {
    token.chars().take(32).collect()
}

/// Writes `mesh` as OBJ; reading the output back gives an equal [`Mesh`] (given the same
/// scheme, which OBJ does not store).
pub fn write(mesh: &Mesh, w: &mut impl Write) -> Result<()> {
    write_impl(mesh, None, w)
}

/// Writes `mesh` as OBJ with one normal per vertex (`vn`, corners `a//a` or `a/t/a`).
pub fn write_with_normals(mesh: &Mesh, normals: &[[f32; 3]], w: &mut impl Write) -> Result<()> {
    if normals.len() != mesh.positions.len() {
        return Err(Error::Internal(format!(
            "{} normals given for {} vertices",
            normals.len(),
            mesh.positions.len()
        )));
    }
    write_impl(mesh, Some(normals), w)
}

fn write_impl(mesh: &Mesh, normals: Option<&[[f32; 3]]>, w: &mut impl Write) -> Result<()> {
    super::check_writable(mesh)?;
    let mut w = std::io::BufWriter::new(w);
    writeln!(
        w,
        "# subsurf: {} vertices, {} faces",
        mesh.positions.len(),
        mesh.face_counts.len()
    )?;
    // What the mesh holds, in the shortest digits that read back to the same values.
    match mesh.positions.as_f64() {
        Some(v) => {
            for p in v {
                writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
            }
        }
        None => {
            for p in &mesh.positions {
                writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
            }
        }
    }
    if let Some(uv) = &mesh.uvs {
        for t in &uv.values {
            writeln!(w, "vt {} {}", t[0], t[1])?;
        }
    }
    if let Some(normals) = normals {
        for n in normals {
            writeln!(w, "vn {} {} {}", n[0], n[1], n[2])?;
        }
    }
    let mut start = 0usize;
    for &n in &mesh.face_counts {
        let end = start + n as usize;
        w.write_all(b"f")?;
        for c in start..end {
            let v = mesh.face_indices[c] as u64 + 1;
            match (&mesh.uvs, normals.is_some()) {
                (None, false) => write!(w, " {v}")?,
                (None, true) => write!(w, " {v}//{v}")?,
                (Some(uv), false) => write!(w, " {v}/{}", uv.indices[c] as u64 + 1)?,
                (Some(uv), true) => write!(w, " {v}/{}/{v}", uv.indices[c] as u64 + 1)?,
            }
        }
        w.write_all(b"\n")?;
        start = end;
    }
    write_tags(mesh, &mut w)?;
    w.flush()?;
    Ok(())
}

/// Writes tags and the options that differ from [`Options::default`] as `t` lines.
fn write_tags(mesh: &Mesh, w: &mut impl Write) -> Result<()> {
    for c in &mesh.creases {
        writeln!(w, "t crease 2/1/0 {} {} {}", c.v0, c.v1, c.sharpness)?;
    }
    for c in &mesh.corners {
        writeln!(w, "t corner 1/1/0 {} {}", c.vertex, c.sharpness)?;
    }
    for f in &mesh.holes {
        writeln!(w, "t hole 1/0/0 {f}")?;
    }
    let o = &mesh.options;
    let d = Options::default();
    if o.boundary != d.boundary {
        writeln!(
            w,
            "t interpolateboundary 1/0/0 {}",
            boundary_tag(o.boundary)
        )?;
    }
    if o.crease_method != d.crease_method {
        let s = crease_method_tag(o.crease_method);
        writeln!(w, "t creasemethod 0/0/1 {s}")?;
    }
    if o.triangle_subdivision != d.triangle_subdivision {
        let s = triangle_subdivision_tag(o.triangle_subdivision);
        writeln!(w, "t smoothtriangles 0/0/1 {s}")?;
    }
    if o.uv_interpolation != d.uv_interpolation {
        let k = uv_interpolation_tag(o.uv_interpolation);
        writeln!(w, "t facevaryinginterpolateboundary 1/0/0 {k}")?;
    }
    if o.fvar_propagate_corners != d.fvar_propagate_corners {
        writeln!(
            w,
            "t facevaryingpropagatecorners 1/0/0 {}",
            u8::from(o.fvar_propagate_corners)
        )?;
    }
    Ok(())
}
