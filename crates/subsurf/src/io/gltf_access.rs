//! glTF 2.0 data access for [`super::gltf_read`]: the GLB container, buffers (GLB `BIN`
//! chunk, `data:` URIs, files next to a `.gltf`) and accessors (strided, normalized, sparse).
//!
//! Every offset, length and count is checked against the bytes that exist before anything is
//! read or allocated, so malformed files are [`Error::Gltf`] errors naming the part at fault.

use crate::error::{Error, Result};
use serde_json::Value;
use std::path::Path;

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;
/// Accessors without a buffer view are all zeros; their size is not bounded by the file.
const MAX_ZERO_ELEMENTS: usize = 1 << 24;

/// A [`Error::Gltf`] at `location`.
pub(crate) fn gltf_error(location: impl Into<String>, reason: impl Into<String>) -> Error {
    Error::Gltf {
        location: location.into(),
        reason: reason.into(),
    }
}

/// A parsed glTF document: its JSON and its loaded buffers.
pub(crate) struct Document {
    /// The JSON root object.
    pub json: Value,
    buffers: Vec<Vec<u8>>,
}

/// Whether `bytes` start like a binary glTF file.
pub fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(GLB_MAGIC)
}

fn u32_at(b: &[u8], i: usize) -> Option<u32> {
    let s = b.get(i..i.checked_add(4)?)?;
    Some(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Splits a GLB file into its JSON chunk and optional BIN chunk.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>)> {
    let hdr = "GLB header";
    if bytes.len() < 12 {
        return Err(gltf_error(
            hdr,
            format!("{} bytes, shorter than the 12-byte header", bytes.len()),
        ));
    }
    let version = u32_at(bytes, 4).unwrap_or(0);
    if version != 2 {
        return Err(gltf_error(
            hdr,
            format!("version {version} (only glTF 2 is read)"),
        ));
    }
    let length = u32_at(bytes, 8).unwrap_or(0) as usize;
    if length > bytes.len() {
        return Err(gltf_error(
            hdr,
            format!(
                "declares {length} bytes but the file has {} (truncated?)",
                bytes.len()
            ),
        ));
    }
    let bytes = &bytes[..length];
    let mut at = 12usize;
    let mut json = None;
    let mut bin = None;
    let mut k = 0usize;
    while at < bytes.len() {
        let loc = format!("GLB chunk {k} at byte {at}");
        let (Some(len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(gltf_error(loc, "truncated chunk header"));
        };
        let start = at + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                gltf_error(
                    &loc,
                    format!(
                        "{len} bytes of data, past the end of the file ({} bytes)",
                        bytes.len()
                    ),
                )
            })?;
        let data = &bytes[start..end];
        match (k, kind) {
            (0, CHUNK_JSON) => json = Some(data),
            (0, _) => return Err(gltf_error(loc, "the first chunk is not JSON")),
            (1, CHUNK_BIN) => bin = Some(data),
            (_, CHUNK_JSON) => return Err(gltf_error(loc, "a second JSON chunk")),
            _ => {} // Unknown chunk types are skipped, as the specification asks.
        }
        at = end;
        k += 1;
    }
    let json = json.ok_or_else(|| gltf_error(hdr, "no JSON chunk"))?;
    Ok((json, bin))
}

impl Document {
    /// Parses a `.glb` or `.gltf` file. External buffer files are looked up in `base_dir`;
    /// without one they are an error.
    pub fn parse(bytes: &[u8], base_dir: Option<&Path>) -> Result<Document> {
        let (json_bytes, bin) = if is_glb(bytes) {
            split_glb(bytes)?
        } else {
            (bytes, None)
        };
        let json_bytes = json_bytes
            .strip_prefix(b"\xEF\xBB\xBF")
            .unwrap_or(json_bytes);
        let json: Value = serde_json::from_slice(json_bytes).map_err(|e| {
            gltf_error(
                "JSON",
                format!("line {}, column {}: {e}", e.line(), e.column()),
            )
        })?;
        if !json.is_object() {
            return Err(gltf_error("JSON", "the root is not an object"));
        }
        let mut doc = Document {
            json,
            buffers: Vec::new(),
        };
        let n = doc.array("buffers")?.len();
        for i in 0..n {
            let data = doc.load_buffer(i, bin, base_dir)?;
            doc.buffers.push(data);
        }
        Ok(doc)
    }

    /// The top-level array `key` (empty when absent).
    pub fn array(&self, key: &str) -> Result<&[Value]> {
        match self.json.get(key) {
            None => Ok(&[]),
            Some(Value::Array(a)) => Ok(a),
            Some(_) => Err(gltf_error(key, "is not an array")),
        }
    }

    /// Element `i` of the top-level array `key`, an object.
    pub fn item(&self, key: &str, i: usize) -> Result<&Value> {
        let a = self.array(key)?;
        let v = a.get(i).ok_or_else(|| {
            gltf_error(
                format!("{key}[{i}]"),
                format!("does not exist ({} {key})", a.len()),
            )
        })?;
        if !v.is_object() {
            return Err(gltf_error(format!("{key}[{i}]"), "is not an object"));
        }
        Ok(v)
    }

    fn load_buffer(&self, i: usize, bin: Option<&[u8]>, base: Option<&Path>) -> Result<Vec<u8>> {
        let loc = format!("buffers[{i}]");
        let b = self.item("buffers", i)?;
        let len = index_field(b, "byteLength", &loc)?
            .ok_or_else(|| gltf_error(&loc, "has no byteLength"))?;
        let mut data = match b.get("uri") {
            None => match (i, bin) {
                (0, Some(bin)) => bin.to_vec(),
                _ => return Err(gltf_error(&loc, "has no uri and there is no GLB BIN chunk")),
            },
            Some(Value::String(uri)) => {
                match uri.strip_prefix("data:") {
                    Some(rest) => {
                        let (_, b64) = rest
                            .split_once(";base64,")
                            .ok_or_else(|| gltf_error(&loc, "data: URI is not base64"))?;
                        decode_base64(b64).map_err(|r| gltf_error(&loc, r))?
                    }
                    None => {
                        let base = base.ok_or_else(|| {
                        gltf_error(
                            &loc,
                            format!("refers to the file '{uri}', which can only be read from a path"),
                        )
                    })?;
                        let name = percent_decode(uri).map_err(|r| gltf_error(&loc, r))?;
                        let path = base.join(&name);
                        std::fs::read(&path).map_err(|e| {
                            gltf_error(&loc, format!("reading '{}': {e}", path.display()))
                        })?
                    }
                }
            }
            Some(_) => return Err(gltf_error(&loc, "uri is not a string")),
        };
        if data.len() < len {
            return Err(gltf_error(
                &loc,
                format!("byteLength is {len} but only {} bytes exist", data.len()),
            ));
        }
        data.truncate(len);
        Ok(data)
    }

    /// The bytes of buffer view `v` and its byte stride (0: tightly packed).
    fn view(&self, v: usize) -> Result<(&[u8], usize)> {
        let loc = format!("bufferViews[{v}]");
        let view = self.item("bufferViews", v)?;
        let b =
            index_field(view, "buffer", &loc)?.ok_or_else(|| gltf_error(&loc, "has no buffer"))?;
        let off = index_field(view, "byteOffset", &loc)?.unwrap_or(0);
        let len = index_field(view, "byteLength", &loc)?
            .ok_or_else(|| gltf_error(&loc, "has no byteLength"))?;
        let stride = index_field(view, "byteStride", &loc)?.unwrap_or(0);
        let buf = self.buffers.get(b).ok_or_else(|| {
            gltf_error(
                &loc,
                format!("buffer {b} does not exist ({} buffers)", self.buffers.len()),
            )
        })?;
        let data = off
            .checked_add(len)
            .and_then(|end| buf.get(off..end))
            .ok_or_else(|| {
                gltf_error(
                    &loc,
                    format!(
                        "bytes {off}..{off}+{len} are past the end of buffer {b} ({} bytes)",
                        buf.len()
                    ),
                )
            })?;
        Ok((data, stride))
    }

    /// Reads accessor `a` as `count` rows of `comps` numbers, checking its `type` is `ty` and
    /// its component type one of `ctypes`. Normalized integers are mapped to `[0, 1]` or
    /// `[-1, 1]`; sparse substitutions are applied.
    pub fn read_accessor(&self, a: usize, ty: &str, ctypes: &[u32]) -> Result<Vec<f64>> {
        let loc = format!("accessors[{a}]");
        let acc = self.item("accessors", a)?;
        let found_ty = acc.get("type").and_then(Value::as_str).unwrap_or("");
        if found_ty != ty {
            return Err(gltf_error(
                &loc,
                format!("type is '{found_ty}', expected '{ty}'"),
            ));
        }
        let comps = match ty {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            _ => 4,
        };
        let ctype = index_field(acc, "componentType", &loc)?.unwrap_or(0) as u32;
        if !ctypes.contains(&ctype) {
            return Err(gltf_error(
                &loc,
                format!(
                    "componentType {ctype} ({}) is not accepted here (expected {})",
                    ctype_name(ctype),
                    ctypes
                        .iter()
                        .map(|&c| ctype_name(c))
                        .collect::<Vec<_>>()
                        .join(" or ")
                ),
            ));
        }
        let normalized = acc
            .get("normalized")
            .and_then(Value::as_bool)
            .unwrap_or(false);
        let count =
            index_field(acc, "count", &loc)?.ok_or_else(|| gltf_error(&loc, "has no count"))?;
        let csize = ctype_size(ctype);
        let elem = comps * csize;
        let mut out = match index_field(acc, "bufferView", &loc)? {
            None => {
                if count > MAX_ZERO_ELEMENTS {
                    return Err(gltf_error(
                        &loc,
                        format!(
                            "{count} elements without a bufferView (limit {MAX_ZERO_ELEMENTS})"
                        ),
                    ));
                }
                vec![0.0; count * comps]
            }
            Some(v) => {
                let (data, stride) = self.view(v)?;
                let stride = if stride == 0 { elem } else { stride };
                if stride < elem {
                    return Err(gltf_error(
                        &loc,
                        format!("bufferViews[{v}].byteStride {stride} is less than the element size {elem}"),
                    ));
                }
                let off = index_field(acc, "byteOffset", &loc)?.unwrap_or(0);
                let data = data.get(off..).unwrap_or(&[]);
                read_rows(data, count, stride, comps, ctype, normalized)
                    .ok_or_else(|| gltf_error(&loc, format!(
                        "{count} elements of {elem} bytes (stride {stride}) from byte {off} do not fit in bufferViews[{v}]"
                    )))?
            }
        };
        if let Some(sparse) = acc.get("sparse") {
            self.apply_sparse(sparse, &loc, count, comps, ctype, normalized, &mut out)?;
        }
        Ok(out)
    }

    fn apply_sparse(
        &self,
        sparse: &Value,
        loc: &str,
        count: usize,
        comps: usize,
        ctype: u32,
        normalized: bool,
        out: &mut [f64],
    ) -> Result<()> {
        let loc = format!("{loc}.sparse");
        let n =
            index_field(sparse, "count", &loc)?.ok_or_else(|| gltf_error(&loc, "has no count"))?;
        let part = |key: &str| -> Result<(&[u8], u32)> {
            let p = sparse
                .get(key)
                .filter(|p| p.is_object())
                .ok_or_else(|| gltf_error(&loc, format!("has no {key} object")))?;
            let ploc = format!("{loc}.{key}");
            let v = index_field(p, "bufferView", &ploc)?
                .ok_or_else(|| gltf_error(&ploc, "has no bufferView"))?;
            let off = index_field(p, "byteOffset", &ploc)?.unwrap_or(0);
            let ct = index_field(p, "componentType", &ploc)?.unwrap_or(0) as u32;
            let (data, _) = self.view(v)?;
            Ok((data.get(off..).unwrap_or(&[]), ct))
        };
        let (idata, ict) = part("indices")?;
        if ![5121, 5123, 5125].contains(&ict) {
            return Err(gltf_error(
                format!("{loc}.indices"),
                format!("componentType {ict} is not an unsigned integer type"),
            ));
        }
        let (vdata, _) = part("values")?;
        let too_short = |key: &str| {
            gltf_error(
                format!("{loc}.{key}"),
                format!("{n} elements do not fit in its bufferView"),
            )
        };
        let isize = ctype_size(ict);
        let idx = read_rows(idata, n, isize, 1, ict, false).ok_or_else(|| too_short("indices"))?;
        let elem = comps * ctype_size(ctype);
        let vals = read_rows(vdata, n, elem, comps, ctype, normalized)
            .ok_or_else(|| too_short("values"))?;
        for (k, &i) in idx.iter().enumerate() {
            let i = i as usize;
            if i >= count {
                return Err(gltf_error(
                    format!("{loc}.indices"),
                    format!("index {i} is out of range ({count} elements)"),
                ));
            }
            out[i * comps..(i + 1) * comps].copy_from_slice(&vals[k * comps..(k + 1) * comps]);
        }
        Ok(())
    }
}

/// Reads `count` rows of `comps` components, `stride` bytes apart; `None` if they do not fit.
fn read_rows(
    data: &[u8],
    count: usize,
    stride: usize,
    comps: usize,
    ctype: u32,
    normalized: bool,
) -> Option<Vec<f64>> {
    let csize = ctype_size(ctype);
    if count > 0 {
        let need = (count - 1)
            .checked_mul(stride)?
            .checked_add(comps * csize)?;
        if need > data.len() {
            return None;
        }
    }
    let mut out = Vec::with_capacity(count * comps);
    for i in 0..count {
        let row = i * stride;
        for k in 0..comps {
            let at = row + k * csize;
            let b = &data[at..at + csize];
            out.push(component(b, ctype, normalized));
        }
    }
    Some(out)
}

fn component(b: &[u8], ctype: u32, normalized: bool) -> f64 {
    let (v, scale) = match ctype {
        5120 => (b[0] as i8 as f64, 127.0),
        5121 => (b[0] as f64, 255.0),
        5122 => (i16::from_le_bytes([b[0], b[1]]) as f64, 32767.0),
        5123 => (u16::from_le_bytes([b[0], b[1]]) as f64, 65535.0),
        5125 => (u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64, 1.0),
        _ => return f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
    };
    if normalized && scale != 1.0 {
        (v / scale).max(-1.0)
    } else {
        v
    }
}

fn ctype_size(ctype: u32) -> usize {
    match ctype {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        _ => 4,
    }
}

fn ctype_name(ctype: u32) -> &'static str {
    match ctype {
        5120 => "byte",
        5121 => "unsigned byte",
        5122 => "short",
        5123 => "unsigned short",
        5125 => "unsigned int",
        5126 => "float",
        _ => "unknown",
    }
}

/// Field `key` of `obj` as a non-negative integer (`None` when absent).
pub(crate) fn index_field(obj: &Value, key: &str, loc: &str) -> Result<Option<usize>> {
    match obj.get(key) {
        None => Ok(None),
        Some(v) => v
            .as_u64()
            // Some writers spell integers as `24.0`.
            .or_else(|| {
                v.as_f64()
                    .filter(|x| x.fract() == 0.0 && (0.0..9.0e15).contains(x))
                    .map(|x| x as u64)
            })
            .and_then(|x| usize::try_from(x).ok())
            .map(Some)
            .ok_or_else(|| gltf_error(loc, format!("{key} is not a non-negative integer: {v}"))),
    }
}

/// Decodes standard base64 (padding optional, no whitespace).
fn decode_base64(s: &str) -> std::result::Result<Vec<u8>, String> {
    let s = s.trim_end_matches('=');
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let mut acc = 0u32;
    let mut bits = 0u32;
    for (i, c) in s.bytes().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return Err(format!("data: URI has a non-base64 byte at position {i}")),
        };
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Ok(out)
}

/// Undoes `%XX` escapes in a relative URI.
fn percent_decode(uri: &str) -> std::result::Result<String, String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = b
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("uri '{uri}' has a bad % escape"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("uri '{uri}' is not UTF-8 once decoded"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips_known_text() {
        assert_eq!(decode_base64("TWFu").unwrap(), b"Man");
        assert_eq!(decode_base64("TWE=").unwrap(), b"Ma");
        assert_eq!(decode_base64("TQ==").unwrap(), b"M");
        assert!(decode_base64("T*==").is_err());
    }

    #[test]
    fn percent_escapes_are_decoded() {
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_err());
    }

    #[test]
    fn rows_outside_the_data_are_refused() {
        let data = [0u8; 24];
        assert!(read_rows(&data, 2, 12, 3, 5126, false).is_some());
        assert!(read_rows(&data, 3, 12, 3, 5126, false).is_none());
        assert!(read_rows(&data, usize::MAX, 12, 3, 5126, false).is_none());
        assert_eq!(
            read_rows(&[255, 0], 2, 1, 1, 5121, true),
            Some(vec![1.0, 0.0])
        );
    }
}
