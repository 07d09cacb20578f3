//! glTF 2.0 binary (`.glb`) writer: one mesh, one triangle primitive.
//!
//! The file follows the Khronos glTF 2.0 specification: a 12-byte header (`glTF`, version 2,
//! total length), a JSON chunk padded with spaces and a BIN chunk padded with zeros, both to
//! 4-byte boundaries. The BIN chunk holds, in order, `POSITION` (`VEC3` float, with the
//! `min`/`max` bounds the specification requires), `NORMAL` when given, `TEXCOORD_0` when
//! the mesh has UVs, and `u32` triangle indices.
//!
//! glTF attributes are per vertex, while subsurf's UVs are face-varying: a vertex is emitted
//! once per distinct `(position, uv)` pair met at its face corners. Polygons are fanned into
//! triangles from their first corner; faces tagged as holes are left out. UVs are flipped
//! (`v' = 1 - v`) because glTF puts the texture origin at the top left.

#[doc(inline)]
pub use super::gltf_read::{is_glb, read, read_file, GltfRead, ReadOptions};

use crate::error::{Error, MeshError, Result};
use crate::mesh::Mesh;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write;

const GLB_MAGIC: u32 = 0x4654_6C67; // "glTF"
const CHUNK_JSON: u32 = 0x4E4F_534A; // "JSON"
const CHUNK_BIN: u32 = 0x004E_4942; // "BIN\0"
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Per-vertex streams after splitting face-varying UVs, and the triangle list.
struct Streams {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    uvs: Option<Vec<[f32; 2]>>,
    indices: Vec<u32>,
}

fn build_streams(mesh: &Mesh, normals: Option<&[[f32; 3]]>) -> Result<Streams> {
    super::check_writable(mesh)?;
    let nv = mesh.positions.len();
    if let Some(n) = normals {
        if n.len() != nv {
            return Err(Error::Unsupported(format!(
                "{} normals for {nv} vertices",
                n.len()
            )));
        }
    }
    for (v, p) in mesh.positions.iter().enumerate() {
        if let Some(&value) = p.iter().find(|x| !x.is_finite()) {
            return Err(MeshError::NonFiniteCoordinate { vertex: v, value }.into());
        }
    }
    let hole = mesh.hole_mask();
    let uv = mesh.uvs.as_ref();
    // Vertex remap: without UVs, positions are kept as they are.
    let mut remap: HashMap<(u32, u32), u32> = HashMap::new();
    let mut out = Streams {
        positions: if uv.is_some() {
            vec![]
        } else {
            mesh.positions.to_vec()
        },
        normals: normals.map(|n| if uv.is_some() { vec![] } else { n.to_vec() }),
        uvs: uv.map(|_| vec![]),
        indices: vec![],
    };
    let mut start = 0usize;
    let mut corner_ids = Vec::new();
    for (f, &count) in mesh.face_counts.iter().enumerate() {
        let count = count as usize;
        let corners = start..start + count;
        start += count;
        if count < 3 {
            return Err(MeshError::FaceTooSmall {
                face: f,
                count: count as u32,
            }
            .into());
        }
        corner_ids.clear();
        for (k, c) in corners.enumerate() {
            let v = mesh.face_indices[c];
            if v as usize >= nv {
                return Err(MeshError::VertexIndexOutOfRange {
                    face: f,
                    corner: k,
                    index: v,
                    count: nv,
                }
                .into());
            }
            let id = match uv {
                None => v,
                Some(fv) => {
                    let t = fv.indices[c];
                    let Some(&value) = fv.values.get(t as usize) else {
                        return Err(MeshError::FaceVarying {
                            reason: format!(
                                "face {f}, corner {k}: UV index {t} is out of range ({} values)",
                                fv.values.len()
                            ),
                        }
                        .into());
                    };
                    *remap.entry((v, t)).or_insert_with(|| {
                        out.positions.push(mesh.positions[v as usize]);
                        if let (Some(dst), Some(src)) = (out.normals.as_mut(), normals) {
                            dst.push(src[v as usize]);
                        }
                        if let Some(dst) = out.uvs.as_mut() {
                            dst.push([value[0], 1.0 - value[1]]);
                        }
                        (out.positions.len() - 1) as u32
                    })
                }
            };
            corner_ids.push(id);
        }
        if hole[f] {
            continue;
        }
        for k in 1..count - 1 {
            out.indices
                .extend_from_slice(&[corner_ids[0], corner_ids[k], corner_ids[k + 1]]);
        }
    }
    if out.indices.is_empty() {
        return Err(Error::Unsupported(
            "glTF export of a mesh without faces".into(),
        ));
    }
    Ok(out)
}

/// `[a,b,c]` with shortest round-trip float formatting (exact for `f32`).
fn json_floats(v: &[f32]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", parts.join(","))
}

fn bounds<const N: usize>(data: &[[f32; N]]) -> ([f32; N], [f32; N]) {
    let mut lo = [f32::INFINITY; N];
    let mut hi = [f32::NEG_INFINITY; N];
    for p in data {
        for k in 0..N {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The BIN chunk under construction with its buffer views and accessors (JSON objects).
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
}

impl Builder {
    /// Appends `bytes` as a buffer view (4-byte aligned) with an accessor over it; returns
    /// the accessor index.
    fn add(
        &mut self,
        bytes: &[u8],
        target: u32,
        ctype: u32,
        count: usize,
        ty: &str,
        minmax: Option<(&[f32], &[f32])>,
    ) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        self.views.push(format!(
            r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{},"target":{target}}}"#,
            bytes.len()
        ));
        let mut acc = format!(
            r#"{{"bufferView":{},"componentType":{ctype},"count":{count},"type":"{ty}""#,
            self.views.len() - 1
        );
        if let Some((lo, hi)) = minmax {
            let _ = write!(
                acc,
                r#","min":{},"max":{}"#,
                json_floats(lo),
                json_floats(hi)
            );
        }
        acc.push('}');
        self.accessors.push(acc);
        self.accessors.len() - 1
    }
}

/// Writes `mesh` as a binary glTF 2.0 file. With `normals` (one per vertex) the primitive
/// gets a `NORMAL` attribute; UVs become `TEXCOORD_0`.
pub fn write(mesh: &Mesh, normals: Option<&[[f32; 3]]>, w: &mut impl Write) -> Result<()> {
    let s = build_streams(mesh, normals)?;
    let mut b = Builder::default();
    let n = s.positions.len();
    let (lo, hi) = bounds(&s.positions);
    let a = b.add(
        bytemuck::cast_slice(&s.positions),
        ARRAY_BUFFER,
        FLOAT,
        n,
        "VEC3",
        Some((&lo, &hi)),
    );
    let mut attributes = format!(r#""POSITION":{a}"#);
    if let Some(nrm) = &s.normals {
        let a = b.add(
            bytemuck::cast_slice(nrm),
            ARRAY_BUFFER,
            FLOAT,
            n,
            "VEC3",
            None,
        );
        let _ = write!(attributes, r#","NORMAL":{a}"#);
    }
    if let Some(uv) = &s.uvs {
        let a = b.add(
            bytemuck::cast_slice(uv),
            ARRAY_BUFFER,
            FLOAT,
            n,
            "VEC2",
            None,
        );
        let _ = write!(attributes, r#","TEXCOORD_0":{a}"#);
    }
    let ia = b.add(
        bytemuck::cast_slice(&s.indices),
        ELEMENT_ARRAY_BUFFER,
        UNSIGNED_INT,
        s.indices.len(),
        "SCALAR",
        None,
    );
    let bin = b.bin;
    let mut json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0","generator":"subsurf {}"}},"scene":0,"#,
            r#""scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{{}}},"indices":{},"mode":4}}]}}],"#,
            r#""buffers":[{{"byteLength":{}}}],"bufferViews":[{}],"accessors":[{}]}}"#
        ),
        env!("CARGO_PKG_VERSION"),
        attributes,
        ia,
        bin.len(),
        b.views.join(","),
        b.accessors.join(",")
    )
    .into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let total = u32::try_from(total)
        .map_err(|_| Error::Unsupported(format!("glTF binary of {total} bytes (> 4 GiB)")))?;
    w.write_all(&GLB_MAGIC.to_le_bytes())?;
    w.write_all(&2u32.to_le_bytes())?;
    w.write_all(&total.to_le_bytes())?;
    w.write_all(&(json.len() as u32).to_le_bytes())?;
    w.write_all(&CHUNK_JSON.to_le_bytes())?;
    w.write_all(&json)?;
    w.write_all(&(bin.len() as u32).to_le_bytes())?;
    w.write_all(&CHUNK_BIN.to_le_bytes())?;
    w.write_all(&bin)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u32_at(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes(b[i..i + 4].try_into().unwrap())
    }

    #[test]
    fn header_and_chunks_are_aligned() {
        let mesh = crate::shapes::cube();
        let mut b = vec![];
        write(&mesh, None, &mut b).unwrap();
        assert_eq!(&b[..4], b"glTF");
        assert_eq!(u32_at(&b, 4), 2);
        assert_eq!(u32_at(&b, 8) as usize, b.len());
        let jl = u32_at(&b, 12) as usize;
        assert_eq!(jl % 4, 0);
        assert_eq!(&b[16..20], b"JSON");
        let bl = u32_at(&b, 20 + jl) as usize;
        assert_eq!(&b[24 + jl..28 + jl], b"BIN\0");
        assert_eq!(28 + jl + bl, b.len());
        // 8 positions (12 B each) + 6 quads x 2 triangles x 3 u32 indices.
        assert_eq!(bl, 8 * 12 + 36 * 4);
    }

    #[test]
    fn errors_instead_of_panics() {
        let mut mesh = crate::shapes::cube();
        mesh.face_indices[3] = 99;
        assert!(write(&mesh, None, &mut vec![]).is_err());
        let mut mesh = crate::shapes::cube();
        mesh.positions.as_f32_mut()[0][1] = f32::NAN;
        assert!(write(&mesh, None, &mut vec![]).is_err());
        let mesh = crate::shapes::cube();
        assert!(write(&mesh, Some(&[[0.0; 3]; 2]), &mut vec![]).is_err());
        assert!(write(&Mesh::default(), None, &mut vec![]).is_err());
    }
}
