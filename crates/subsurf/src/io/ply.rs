//! Stanford PLY (Turk 1994): ASCII, binary little- and big-endian in; binary little-endian out.
//!
//! Read: the `vertex` element's `x y z` (any scalar type), optional `nx ny nz` normals and
//! per-vertex texture coordinates (`u v`, `s t` or `texture_u texture_v`, which become
//! face-varying data indexed like the faces), and the `face` element's `vertex_indices` (or
//! `vertex_index`) list. Every other element and property is read past and dropped.
//!
//! Errors are [`crate::Error::Parse`]: header problems name the header line; problems in an
//! ASCII body name the body line; problems in a binary body name the header line of the
//! element being read, with the element number in the reason.

use super::parse_error;
use crate::error::{Error, Result};
use crate::mesh::{FaceVarying, Mesh, Positions};
use std::io::Write;
use std::path::Path;

/// Reads a PLY file (positions, faces, per-vertex UVs; normals are dropped).
pub fn read_file(path: impl AsRef<Path>) -> Result<Mesh> {
    let bytes = std::fs::read(path)?;
    read(&bytes)
}

/// Reads PLY bytes (positions, faces, per-vertex UVs; normals are dropped).
pub fn read(bytes: &[u8]) -> Result<Mesh> {
    Ok(read_with_normals(bytes)?.0)
}

/// Reads PLY bytes, also returning the per-vertex normals when the file has `nx ny nz`.
pub fn read_with_normals(bytes: &[u8]) -> Result<(Mesh, Option<Vec<[f32; 3]>>)> {
    let header = parse_header(bytes)?;
    let body = &bytes[header.body_start..];
    let mut src = match header.format {
        Encoding::Ascii => {
            let text = std::str::from_utf8(body)
                .map_err(|_| parse_error(header.lines + 1, "ASCII PLY body is not valid text"))?;
            Source::Ascii(AsciiSource {
                lines: text.lines(),
                tokens: Vec::new(),
                next: 0,
                line: header.lines,
            })
        }
        Encoding::Binary { big_endian } => Source::Binary {
            bytes: body,
            pos: 0,
            big_endian,
        },
    };
    let mut mesh = Mesh::default();
    let mut normals: Option<Vec<[f32; 3]>> = None;
    let mut uv_values: Option<Vec<[f32; 2]>> = None;
    let mut face_lines: Vec<usize> = Vec::new();
    for el in &header.elements {
        let cap = el.count.min(bytes.len());
        match el.name.as_str() {
            "vertex" => {
                let slot = |name: &str| el.props.iter().position(|p| p.name == name);
                let xyz = [slot("x"), slot("y"), slot("z")];
                let [Some(x), Some(y), Some(z)] = xyz else {
                    return Err(parse_error(el.line, "vertex element lacks x, y or z"));
                };
                let nrm = match (slot("nx"), slot("ny"), slot("nz")) {
                    (Some(a), Some(b), Some(c)) => Some([a, b, c]),
                    _ => None,
                };
                let uv = [("u", "v"), ("s", "t"), ("texture_u", "texture_v")]
                    .iter()
                    .find_map(|(a, b)| Some([slot(a)?, slot(b)?]));
                // Kept in f64 when any coordinate is declared `double`.
                let wide = [x, y, z].iter().any(|&k| el.props[k].ty == Ty::F64);
                let mut points: Vec<[f64; 3]> = Vec::with_capacity(cap);
                let mut n_out = nrm.map(|_| Vec::with_capacity(cap));
                let mut uv_out = uv.map(|_| Vec::with_capacity(cap));
                let mut row = vec![0f64; el.props.len()];
                for i in 0..el.count {
                    let line = read_row(&mut src, el, i, &mut row)?;
                    let p = [row[x], row[y], row[z]];
                    if p.iter().any(|&c| !(c as f32).is_finite()) {
                        return Err(parse_error(
                            line,
                            format!("vertex {i} has a non-finite coordinate {p:?}"),
                        ));
                    }
                    points.push(p);
                    if let (Some(out), Some([a, b, c])) = (&mut n_out, nrm) {
                        out.push([row[a] as f32, row[b] as f32, row[c] as f32]);
                    }
                    if let (Some(out), Some([a, b])) = (&mut uv_out, uv) {
                        out.push([row[a] as f32, row[b] as f32]);
                    }
                }
                mesh.positions = if wide {
                    Positions::from_f64(points)
                } else {
                    Positions::from_f32(points.iter().map(|p| p.map(|c| c as f32)).collect())
                };
                normals = n_out;
                uv_values = uv_out;
            }
            "face" => {
                let Some(list) = el.props.iter().position(|p| {
                    p.list.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index")
                }) else {
                    return Err(parse_error(
                        el.line,
                        "face element lacks a vertex_indices list",
                    ));
                };
                mesh.face_counts.reserve(cap);
                for i in 0..el.count {
                    let line = src.line_or(el.line);
                    for (k, p) in el.props.iter().enumerate() {
                        match p.list {
                            Some(item) => {
                                let n = src.count(p.ty, line, i)?;
                                if k == list && n < 3 {
                                    return Err(parse_error(
                                        line,
                                        format!(
                                            "face {i} has {n} vertices (at least 3 are needed)"
                                        ),
                                    ));
                                }
                                for _ in 0..n {
                                    let v = src.value(item, line, i)?;
                                    if k == list {
                                        mesh.face_indices.push(index(v, line, i)?);
                                    }
                                }
                                if k == list {
                                    mesh.face_counts.push(n);
                                }
                            }
                            None => {
                                src.value(p.ty, line, i)?;
                            }
                        }
                    }
                    face_lines.push(line);
                    src.end_row(line)?;
                }
            }
            _ if el.props.is_empty() => {}
            _ => {
                let mut row = vec![0f64; el.props.len()];
                for i in 0..el.count {
                    read_row(&mut src, el, i, &mut row)?;
                }
            }
        }
    }
    let nv = mesh.positions.len();
    let mut start = 0usize;
    for (f, (&n, &line)) in mesh.face_counts.iter().zip(&face_lines).enumerate() {
        let end = start + n as usize;
        if let Some(&v) = mesh.face_indices[start..end]
            .iter()
            .find(|&&v| v as usize >= nv)
        {
            return Err(parse_error(
                line,
                format!("face {f}: vertex index {v} is out of range (the file has {nv} vertices)"),
            ));
        }
        start = end;
    }
    if let Some(values) = uv_values {
        mesh.uvs = Some(FaceVarying {
            values,
            indices: mesh.face_indices.clone(),
        });
    }
    Ok((mesh, normals))
}

/// Reads one element instance of scalar properties (lists are read past) into `row`.
fn read_row(src: &mut Source, el: &Element, i: usize, row: &mut [f64]) -> Result<usize> {
    let line = src.line_or(el.line);
    for (k, p) in el.props.iter().enumerate() {
        match p.list {
            Some(item) => {
                let n = src.count(p.ty, line, i)?;
                for _ in 0..n {
                    src.value(item, line, i)?;
                }
            }
            None => row[k] = src.value(p.ty, line, i)?,
        }
    }
    src.end_row(line)?;
    Ok(line)
}

fn index(v: f64, line: usize, i: usize) -> Result<u32> {
    if v.fract() != 0.0 || v < 0.0 || v > u32::MAX as f64 {
        return Err(parse_error(
            line,
            format!("face {i}: vertex index {v} is not a valid index"),
        ));
    }
    Ok(v as u32)
}

/// Body encoding.
#[derive(Debug, Clone, Copy)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

/// Scalar types of PLY properties.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn parse(s: &str) -> Option<Ty> {
        Some(match s {
            "char" | "int8" => Ty::I8,
            "uchar" | "uint8" => Ty::U8,
            "short" | "int16" => Ty::I16,
            "ushort" | "uint16" => Ty::U16,
            "int" | "int32" => Ty::I32,
            "uint" | "uint32" => Ty::U32,
            "float" | "float32" => Ty::F32,
            "double" | "float64" => Ty::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
}

/// A property: scalar of type `ty`, or a list with count type `ty` and item type `list`.
#[derive(Debug)]
struct Property {
    name: String,
    ty: Ty,
    list: Option<Ty>,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
    /// Header line that declares the element.
    line: usize,
}

#[derive(Debug)]
struct Header {
    format: Encoding,
    elements: Vec<Element>,
    /// Number of header lines (the body starts on the next line).
    lines: usize,
    body_start: usize,
}

fn parse_header(bytes: &[u8]) -> Result<Header> {
    let mut pos = 0usize;
    let mut line_no = 0usize;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        line_no += 1;
        let Some(len) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            return Err(parse_error(
                line_no,
                "PLY header does not end with 'end_header'",
            ));
        };
        let raw = &bytes[pos..pos + len];
        pos += len + 1;
        let text = std::str::from_utf8(raw)
            .map_err(|_| parse_error(line_no, "PLY header line is not valid text"))?;
        let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
        if line_no == 1 {
            if tokens != ["ply"] {
                return Err(parse_error(1, "not a PLY file (first line is not 'ply')"));
            }
            continue;
        }
        match tokens.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, version] => {
                if *version != "1.0" {
                    return Err(parse_error(
                        line_no,
                        format!("PLY version '{version}' is not supported"),
                    ));
                }
                format = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::Binary { big_endian: false },
                    "binary_big_endian" => Encoding::Binary { big_endian: true },
                    _ => return Err(parse_error(line_no, format!("unknown PLY format '{f}'"))),
                });
            }
            ["element", name, count] => {
                let count = count.parse::<usize>().map_err(|_| {
                    parse_error(line_no, format!("element count '{count}' is not a number"))
                })?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    props: Vec::new(),
                    line: line_no,
                });
            }
            ["property", "list", count_ty, item_ty, name] => {
                let (Some(c), Some(it)) = (Ty::parse(count_ty), Ty::parse(item_ty)) else {
                    return Err(parse_error(line_no, "unknown type in list property"));
                };
                if matches!(c, Ty::F32 | Ty::F64) {
                    return Err(parse_error(
                        line_no,
                        "list count type must be an integer type",
                    ));
                }
                add_property(&mut elements, line_no, name, c, Some(it))?;
            }
            ["property", ty, name] => {
                let Some(t) = Ty::parse(ty) else {
                    return Err(parse_error(
                        line_no,
                        format!("unknown property type '{ty}'"),
                    ));
                };
                add_property(&mut elements, line_no, name, t, None)?;
            }
            ["end_header"] => break,
            _ => {
                let shown: String = text.chars().take(40).collect();
                return Err(parse_error(
                    line_no,
                    format!("unexpected PLY header line '{shown}'"),
                ));
            }
        }
    }
    let Some(format) = format else {
        return Err(parse_error(line_no, "PLY header has no 'format' line"));
    };
    Ok(Header {
        format,
        elements,
        lines: line_no,
        body_start: pos,
    })
}

fn add_property(
    elements: &mut [Element],
    line: usize,
    name: &str,
    ty: Ty,
    list: Option<Ty>,
) -> Result<()> {
    let Some(el) = elements.last_mut() else {
        return Err(parse_error(line, "property before any element"));
    };
    el.props.push(Property {
        name: name.to_string(),
        ty,
        list,
    });
    Ok(())
}

/// ASCII body: whitespace-separated numbers, one element instance per line.
#[derive(Debug)]
struct AsciiSource<'a> {
    lines: std::str::Lines<'a>,
    tokens: Vec<&'a str>,
    next: usize,
    /// Line number of `tokens`.
    line: usize,
}

#[derive(Debug)]
enum Source<'a> {
    Ascii(AsciiSource<'a>),
    Binary {
        bytes: &'a [u8],
        pos: usize,
        big_endian: bool,
    },
}

impl Source<'_> {
    /// The line of the next element instance (ASCII), or `header_line` (binary).
    fn line_or(&mut self, header_line: usize) -> usize {
        match self {
            Source::Ascii(a) => {
                while a.next >= a.tokens.len() {
                    match a.lines.next() {
                        Some(l) => {
                            a.line += 1;
                            a.tokens = l.split_ascii_whitespace().collect();
                            a.next = 0;
                        }
                        None => return a.line + 1,
                    }
                }
                a.line
            }
            Source::Binary { .. } => header_line,
        }
    }

    /// Checks that an ASCII row has no values left over.
    fn end_row(&mut self, line: usize) -> Result<()> {
        if let Source::Ascii(a) = self {
            if a.next != a.tokens.len() {
                return Err(parse_error(
                    line,
                    format!(
                        "{} values left over at the end of the row",
                        a.tokens.len() - a.next
                    ),
                ));
            }
        }
        Ok(())
    }

    fn count(&mut self, ty: Ty, line: usize, i: usize) -> Result<u32> {
        let v = self.value(ty, line, i)?;
        if v < 0.0 || v.fract() != 0.0 || v > u32::MAX as f64 {
            return Err(parse_error(
                line,
                format!("element {i}: list length {v} is not valid"),
            ));
        }
        Ok(v as u32)
    }

    fn value(&mut self, ty: Ty, line: usize, i: usize) -> Result<f64> {
        match self {
            Source::Ascii(a) => {
                let Some(tok) = a.tokens.get(a.next) else {
                    return Err(parse_error(
                        line,
                        format!("element {i}: row ends too early"),
                    ));
                };
                a.next += 1;
                let v: f64 = tok.parse().map_err(|_| {
                    let shown: String = tok.chars().take(32).collect();
                    parse_error(line, format!("element {i}: '{shown}' is not a number"))
                })?;
                if !matches!(ty, Ty::F32 | Ty::F64) && v.fract() != 0.0 {
                    return Err(parse_error(
                        line,
                        format!("element {i}: '{tok}' is not an integer"),
                    ));
                }
                Ok(v)
            }
            Source::Binary {
                bytes,
                pos,
                big_endian,
            } => {
                let n = ty.size();
                let Some(raw) = bytes.get(*pos..*pos + n) else {
                    return Err(parse_error(
                        line,
                        format!(
                            "element {i}: the file ends early (binary body is {} bytes)",
                            bytes.len()
                        ),
                    ));
                };
                *pos += n;
                let mut b = [0u8; 8];
                b[..n].copy_from_slice(raw);
                if *big_endian {
                    b[..n].reverse();
                }
                Ok(match ty {
                    Ty::I8 => b[0] as i8 as f64,
                    Ty::U8 => b[0] as f64,
                    Ty::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
                    Ty::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
                    Ty::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::F64 => f64::from_le_bytes(b),
                })
            }
        }
    }
}

/// Writes `mesh` as binary little-endian PLY: `x y z` as floats, or as doubles when the
/// mesh holds its positions in `f64` ([`crate::mesh::Positions::is_f64`]), `nx ny nz` with
/// `normals` (one per vertex) as floats, faces as a `vertex_indices` list of `uint` (count `uchar` when every
/// face has at most 255 vertices, else `uint`). UVs and tags are not written; faces tagged as
/// holes are left out (PLY cannot tag them), their vertices kept.
pub fn write(mesh: &Mesh, normals: Option<&[[f32; 3]]>, w: &mut impl Write) -> Result<()> {
    super::check_writable(mesh)?;
    if let Some(n) = normals {
        if n.len() != mesh.positions.len() {
            return Err(Error::Internal(format!(
                "{} normals given for {} vertices",
                n.len(),
                mesh.positions.len()
            )));
        }
    }
    let small = mesh.face_counts.iter().all(|&n| n <= 255);
    let hole = mesh.hole_mask();
    let mut w = std::io::BufWriter::new(w);
    writeln!(
        w,
        "ply\nformat binary_little_endian 1.0\ncomment written by subsurf"
    )?;
    writeln!(w, "element vertex {}", mesh.positions.len())?;
    let wide = mesh.positions.as_f64();
    let ty = if wide.is_some() { "double" } else { "float" };
    writeln!(w, "property {ty} x\nproperty {ty} y\nproperty {ty} z")?;
    if normals.is_some() {
        writeln!(w, "property float nx\nproperty float ny\nproperty float nz")?;
    }
    writeln!(w, "element face {}", hole.iter().filter(|&&h| !h).count())?;
    let count_ty = if small { "uchar" } else { "uint" };
    writeln!(
        w,
        "property list {count_ty} uint vertex_indices\nend_header"
    )?;
    for (i, p) in mesh.positions.iter().enumerate() {
        match wide {
            Some(v) => {
                for c in &v[i] {
                    w.write_all(&c.to_le_bytes())?;
                }
            }
            None => {
                for c in p {
                    w.write_all(&c.to_le_bytes())?;
                }
            }
        }
        if let Some(n) = normals {
            for c in &n[i] {
                w.write_all(&c.to_le_bytes())?;
            }
        }
    }
    let mut start = 0usize;
    for (&n, &h) in mesh.face_counts.iter().zip(&hole) {
        let end = start + n as usize;
        if h {
            start = end;
            continue;
        }
        if small {
            w.write_all(&[n as u8])?;
        } else {
            w.write_all(&n.to_le_bytes())?;
        }
        for v in &mesh.face_indices[start..end] {
            w.write_all(&v.to_le_bytes())?;
        }
        start = end;
    }
    w.flush()?;
    Ok(())
}
