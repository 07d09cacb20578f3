//! glTF 2.0 reader (`.gltf` with its buffers, `.glb`): every triangle primitive of the scene
//! becomes one welded cage with face-varying UVs.
//!
//! - **Primitives.** Modes 4 (triangles), 5 (strip) and 6 (fan) are read as triangles, with
//!   indices of any unsigned type or none (sequential). Point and line primitives (modes 0-3)
//!   carry no surface: they are skipped and named in [`GltfRead::notes`]. A scene with no
//!   triangle at all is an error.
//! - **Transforms.** By default ([`ReadOptions::flatten`] `false`) node transforms are kept out
//!   of the geometry: each glTF mesh the scene uses is read once, in its own coordinates, the
//!   way the file stores it; if the scene places different meshes under different transforms
//!   (so that merging them untransformed would misplace them) that is an error asking for
//!   `flatten`. With `flatten` every node's world transform (matrix, or translation, rotation,
//!   scale) is applied and every mesh instance is merged in world space; a transform that
//!   mirrors (negative determinant) has its triangles' winding reversed, as the glTF
//!   specification asks, so the cage stays oriented.
//! - **Welding.** glTF splits vertices where UVs (or normals) differ; vertices with exactly
//!   the same position (bit for bit, `-0` equal to `0`) are merged into one cage vertex, across
//!   primitives and meshes, so the surface is connected. The UV seam stays in the face-varying
//!   data: corners keep the UV of their glTF vertex, shared by corners of the same cage
//!   vertex with the same UV. Triangles that welding makes degenerate are dropped (counted in
//!   the notes).
//! - **UVs.** `TEXCOORD_0` (float, or normalized unsigned byte/short) becomes the mesh's UVs,
//!   flipped back to subsurf's convention (`v = 1 - v_gltf`; see [`super::gltf`]). When only
//!   some primitives have UVs, the others get UV `(0, 0)` and a note.
//! - **Errors.** Malformed files are [`Error::Gltf`] naming the part at fault
//!   (`meshes[0].primitives[1]`, `accessors[3]`, `GLB header`); required extensions (for
//!   example Draco or meshopt compression) are refused by name. No input makes the reader
//!   panic.

use super::gltf_access::{gltf_error, index_field, Document};
use crate::error::{Error, Result};
use crate::mesh::{FaceVarying, Mesh};
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;

pub use super::gltf_access::is_glb;

/// How a glTF scene becomes one mesh.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Apply node transforms and merge every mesh instance in world space (`--flatten`).
    /// Without it, meshes are read in their own coordinates.
    pub flatten: bool,
}

/// A glTF file read as one mesh, with notes on what was left out.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfRead {
    /// The welded cage (Catmull-Clark, default options).
    pub mesh: Mesh,
    /// Human-readable notes: skipped primitives, dropped degenerate triangles, missing UVs.
    pub notes: Vec<String>,
}

type Mat4 = [f64; 16]; // Column-major, as glTF stores it.

const IDENTITY: Mat4 = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Extensions whose absence of support would misread the geometry.
const SUPPORTED_REQUIRED: &[&str] = &[];

/// Reads a glTF file from memory. External buffer files are looked up in `base_dir` (the
/// folder of the `.gltf`); without one, only GLB chunks and `data:` URIs can be read.
pub fn read(bytes: &[u8], base_dir: Option<&Path>, opts: &ReadOptions) -> Result<GltfRead> {
    let doc = Document::parse(bytes, base_dir)?;
    if let Some(req) = doc.json.get("extensionsRequired").and_then(Value::as_array) {
        for e in req.iter().filter_map(Value::as_str) {
            if !SUPPORTED_REQUIRED.contains(&e) {
                return Err(Error::Unsupported(format!(
                    "glTF extension '{e}' (required by the file)"
                )));
            }
        }
    }
    let (instances, note) = instances(&doc, opts)?;
    let mut b = Builder::default();
    b.notes.extend(note);
    for inst in &instances {
        b.add_mesh(&doc, inst)?;
    }
    b.finish()
}

/// Reads a `.gltf` or `.glb` file; buffers named by relative URIs are read next to it.
pub fn read_file(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<GltfRead> {
    let path = path.as_ref();
    let bytes = std::fs::read(path)?;
    read(&bytes, Some(path.parent().unwrap_or(Path::new("."))), opts)
}

/// One mesh to read and the transform to apply to it.
struct Instance {
    mesh: usize,
    matrix: Mat4,
}

/// The meshes of the default scene with their world transforms (flatten), or each used mesh
/// once, untransformed, with a note when that leaves a transform out.
fn instances(doc: &Document, opts: &ReadOptions) -> Result<(Vec<Instance>, Option<String>)> {
    let scenes = doc.array("scenes")?;
    let scene = match index_field(&doc.json, "scene", "scene")? {
        Some(s) => Some(s),
        None if !scenes.is_empty() => Some(0),
        None => None,
    };
    let mut placed: Vec<(usize, Mat4, usize)> = Vec::new(); // (mesh, world, node)
    match scene {
        None => {
            // No scene: every mesh, as stored.
            for m in 0..doc.array("meshes")?.len() {
                placed.push((m, IDENTITY, usize::MAX));
            }
        }
        Some(s) => {
            let loc = format!("scenes[{s}]");
            let sc = doc.item("scenes", s)?;
            let roots = node_list(sc, &loc)?;
            let nodes = doc.array("nodes")?;
            let mut seen = vec![false; nodes.len()];
            let mut stack: Vec<(usize, Mat4)> =
                roots.into_iter().rev().map(|n| (n, IDENTITY)).collect();
            while let Some((n, parent)) = stack.pop() {
                let loc = format!("nodes[{n}]");
                let node = doc.item("nodes", n)?;
                if std::mem::replace(&mut seen[n], true) {
                    return Err(gltf_error(
                        loc,
                        "is reached twice (the node hierarchy must be a tree)",
                    ));
                }
                let world = mul(&parent, &local_matrix(node, &loc)?);
                if let Some(m) = index_field(node, "mesh", &loc)? {
                    placed.push((m, world, n));
                }
                for c in node_list(node, &loc)?.into_iter().rev() {
                    stack.push((c, world));
                }
            }
        }
    }
    if opts.flatten {
        let all = placed
            .into_iter()
            .map(|(mesh, matrix, _)| Instance { mesh, matrix })
            .collect();
        return Ok((all, None));
    }
    let mut out: Vec<Instance> = Vec::new();
    let mut first: Vec<(usize, Mat4, usize)> = Vec::new();
    for (mesh, world, node) in placed {
        if first.iter().any(|f| f.0 == mesh) {
            continue; // Instances of a mesh already read.
        }
        if let Some(f) = first.iter().find(|f| f.1 != world) {
            return Err(Error::Unsupported(format!(
                "glTF meshes[{}] (nodes[{}]) and meshes[{mesh}] (nodes[{node}]) sit under \
                 different node transforms; flatten the scene (--flatten) to apply them and \
                 merge the meshes in world space",
                f.0, f.2
            )));
        }
        first.push((mesh, world, node));
        out.push(Instance {
            mesh,
            matrix: IDENTITY,
        });
    }
    let note = first.iter().find(|f| f.1 != IDENTITY).map(|f| {
        format!(
            "the transform of nodes[{}] is not applied (flatten applies node transforms)",
            f.2
        )
    });
    Ok((out, note))
}

/// The `nodes` or `children` array of a scene or node.
fn node_list(obj: &Value, loc: &str) -> Result<Vec<usize>> {
    let key = if obj.get("children").is_some() {
        "children"
    } else {
        "nodes"
    };
    match obj.get(key) {
        None => Ok(vec![]),
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_u64()
                    .and_then(|x| usize::try_from(x).ok())
                    .ok_or_else(|| gltf_error(loc, format!("{key} has a bad node index {v}")))
            })
            .collect(),
        Some(_) => Err(gltf_error(loc, format!("{key} is not an array"))),
    }
}

fn numbers<const N: usize>(node: &Value, key: &str, loc: &str) -> Result<Option<[f64; N]>> {
    let Some(v) = node.get(key) else {
        return Ok(None);
    };
    let bad = || gltf_error(loc, format!("{key} is not {N} finite numbers"));
    let a = v.as_array().filter(|a| a.len() == N).ok_or_else(bad)?;
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = x.as_f64().filter(|x| x.is_finite()).ok_or_else(bad)?;
    }
    Ok(Some(out))
}

/// A node's local transform: `matrix`, or `T * R * S`.
fn local_matrix(node: &Value, loc: &str) -> Result<Mat4> {
    if let Some(m) = numbers::<16>(node, "matrix", loc)? {
        return Ok(m);
    }
    let t = numbers::<3>(node, "translation", loc)?.unwrap_or([0.0; 3]);
    let [x, y, z, w] = numbers::<4>(node, "rotation", loc)?.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let s = numbers::<3>(node, "scale", loc)?.unwrap_or([1.0; 3]);
    let n = (x * x + y * y + z * z + w * w).sqrt();
    let (x, y, z, w) = if n > 0.0 {
        (x / n, y / n, z / n, w / n)
    } else {
        (0.0, 0.0, 0.0, 1.0)
    };
    // Rotation matrix columns of the unit quaternion, scaled.
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * w),
            2.0 * (x * z - y * w),
        ],
        [
            2.0 * (x * y - z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + x * w),
        ],
        [
            2.0 * (x * z + y * w),
            2.0 * (y * z - x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    let mut m = IDENTITY;
    for c in 0..3 {
        for k in 0..3 {
            m[c * 4 + k] = r[c][k] * s[c];
        }
    }
    m[12..15].copy_from_slice(&t);
    Ok(m)
}

fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            out[c * 4 + r] = (0..4).map(|k| a[k * 4 + r] * b[c * 4 + k]).sum();
        }
    }
    out
}

fn det3(m: &Mat4) -> f64 {
    m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2])
        + m[8] * (m[1] * m[6] - m[5] * m[2])
}

/// The welded cage under construction.
#[derive(Default)]
struct Builder {
    positions: Vec<[f32; 3]>,
    weld: HashMap<[u32; 3], u32>,
    faces: Vec<u32>,
    /// One UV index per corner (`u32::MAX`: the primitive had none).
    uv_corners: Vec<u32>,
    uv_values: Vec<[f32; 2]>,
    uv_key: HashMap<(u32, [u32; 2]), u32>,
    notes: Vec<String>,
    degenerate: usize,
    without_uv: usize,
    primitives: usize,
}

impl Builder {
    fn add_mesh(&mut self, doc: &Document, inst: &Instance) -> Result<()> {
        let m = inst.mesh;
        let mesh = doc.item("meshes", m)?;
        let prims = match mesh.get("primitives") {
            Some(Value::Array(a)) => a,
            _ => {
                return Err(gltf_error(
                    format!("meshes[{m}]"),
                    "has no primitives array",
                ))
            }
        };
        for (p, prim) in prims.iter().enumerate() {
            let loc = match mesh.get("name").and_then(Value::as_str) {
                Some(name) => format!("meshes[{m}] ('{name}').primitives[{p}]"),
                None => format!("meshes[{m}].primitives[{p}]"),
            };
            self.add_primitive(doc, prim, &loc, &inst.matrix)?;
        }
        Ok(())
    }

    fn add_primitive(&mut self, doc: &Document, prim: &Value, loc: &str, m: &Mat4) -> Result<()> {
        if !prim.is_object() {
            return Err(gltf_error(loc, "is not an object"));
        }
        let mode = index_field(prim, "mode", loc)?.unwrap_or(4);
        match mode {
            4..=6 => {}
            0..=3 => {
                let kind = if mode == 0 { "points" } else { "lines" };
                self.notes
                    .push(format!("{loc}: {kind} (mode {mode}) skipped, no surface"));
                return Ok(());
            }
            _ => return Err(gltf_error(loc, format!("unknown mode {mode}"))),
        }
        let attrs = prim
            .get("attributes")
            .filter(|a| a.is_object())
            .ok_or_else(|| gltf_error(loc, "has no attributes object"))?;
        let attr = |key: &str| index_field(attrs, key, &format!("{loc}.attributes"));
        let pa = attr("POSITION")?.ok_or_else(|| gltf_error(loc, "has no POSITION attribute"))?;
        let pos = doc
            .read_accessor(pa, "VEC3", &[5126])
            .map_err(|e| within(e, loc))?;
        let n = pos.len() / 3;
        let uvs = match attr("TEXCOORD_0")? {
            Some(ta) => {
                let uv = doc
                    .read_accessor(ta, "VEC2", &[5126, 5121, 5123])
                    .map_err(|e| within(e, loc))?;
                if uv.len() / 2 != n {
                    return Err(gltf_error(
                        loc,
                        format!("TEXCOORD_0 has {} elements for {n} positions", uv.len() / 2),
                    ));
                }
                Some(uv)
            }
            None => None,
        };
        let indices: Vec<u32> = match index_field(prim, "indices", loc)? {
            Some(ia) => {
                let ix = doc
                    .read_accessor(ia, "SCALAR", &[5121, 5123, 5125])
                    .map_err(|e| within(e, loc))?;
                let mut out = Vec::with_capacity(ix.len());
                for (k, &i) in ix.iter().enumerate() {
                    if i >= n as f64 {
                        return Err(gltf_error(
                            loc,
                            format!("index {k} is {i}, out of range ({n} vertices)"),
                        ));
                    }
                    out.push(i as u32);
                }
                out
            }
            None => (0..n as u32).collect(),
        };
        // World positions of the vertices the triangles use, welded, in accessor order.
        let tris = triangles(&indices, mode);
        let mut used = vec![false; n];
        for &i in tris.iter().flatten() {
            used[i as usize] = true;
        }
        let mut ids = vec![u32::MAX; n];
        for (v, p) in pos.chunks_exact(3).enumerate() {
            if !used[v] {
                continue;
            }
            let q = transform(m, [p[0], p[1], p[2]]);
            if let Some(&bad) = q.iter().find(|x| !x.is_finite()) {
                return Err(gltf_error(
                    loc,
                    format!("POSITION {v} has a non-finite coordinate {bad}"),
                ));
            }
            let key = q.map(|x| (x + 0.0).to_bits()); // -0 and 0 are one position.
            let next = self.positions.len() as u32;
            let id = *self.weld.entry(key).or_insert(next);
            if id == next {
                self.positions.push(q);
            }
            ids[v] = id;
        }
        let flip = det3(m) < 0.0;
        if uvs.is_none() && !tris.is_empty() {
            self.without_uv += 1;
        }
        self.primitives += 1;
        for t in tris {
            let t = if flip { [t[0], t[2], t[1]] } else { t };
            let c = t.map(|i| ids[i as usize]);
            if c[0] == c[1] || c[1] == c[2] || c[0] == c[2] {
                self.degenerate += 1;
                continue;
            }
            self.faces.extend_from_slice(&c);
            for (&gv, &cv) in t.iter().zip(&c) {
                let uv_id = match &uvs {
                    None => u32::MAX,
                    Some(uv) => {
                        let g = gv as usize * 2;
                        let value = [uv[g] as f32, (1.0 - uv[g + 1]) as f32];
                        let key = (cv, value.map(|x| (x + 0.0).to_bits()));
                        let next = self.uv_values.len() as u32;
                        let id = *self.uv_key.entry(key).or_insert(next);
                        if id == next {
                            self.uv_values.push(value);
                        }
                        id
                    }
                };
                self.uv_corners.push(uv_id);
            }
        }
        Ok(())
    }

    fn finish(mut self) -> Result<GltfRead> {
        if self.faces.is_empty() {
            return Err(gltf_error("meshes", "the scene has no triangles"));
        }
        if self.degenerate > 0 {
            self.notes.push(format!(
                "{} degenerate triangles (two corners at one position) dropped",
                self.degenerate
            ));
        }
        // Vertices only degenerate triangles used are dropped, the others keep their order.
        let mut remap = vec![u32::MAX; self.positions.len()];
        for &v in &self.faces {
            remap[v as usize] = 0;
        }
        let mut kept = 0u32;
        let mut positions = Vec::with_capacity(self.positions.len());
        for (r, p) in remap.iter_mut().zip(&self.positions) {
            if *r == 0 {
                *r = kept;
                kept += 1;
                positions.push(*p);
            }
        }
        for v in &mut self.faces {
            *v = remap[*v as usize];
        }
        self.positions = positions;
        let uvs = if self.uv_values.is_empty() {
            None
        } else {
            if self.without_uv > 0 {
                self.notes.push(format!(
                    "{} of {} primitives have no TEXCOORD_0; their corners get UV (0, 0)",
                    self.without_uv, self.primitives
                ));
                let zero = self.uv_values.len() as u32;
                self.uv_values.push([0.0, 0.0]);
                for c in &mut self.uv_corners {
                    if *c == u32::MAX {
                        *c = zero;
                    }
                }
            }
            Some(FaceVarying {
                values: self.uv_values,
                indices: self.uv_corners,
            })
        };
        let mesh = Mesh {
            positions: self.positions.into(),
            face_counts: vec![3; self.faces.len() / 3],
            face_indices: self.faces,
            uvs,
            ..Mesh::default()
        };
        Ok(GltfRead {
            mesh,
            notes: self.notes,
        })
    }
}

/// Adds the primitive's location to an accessor error.
fn within(e: Error, loc: &str) -> Error {
    match e {
        Error::Gltf { location, reason } => Error::Gltf {
            location: format!("{loc}: {location}"),
            reason,
        },
        other => other,
    }
}

fn transform(m: &Mat4, p: [f64; 3]) -> [f32; 3] {
    if *m == IDENTITY {
        return p.map(|x| x as f32);
    }
    let mut q = [0.0f32; 3];
    for r in 0..3 {
        q[r] = (m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]) as f32;
    }
    q
}

/// The triangles of a primitive of mode 4, 5 or 6 (incomplete trailing triangles dropped).
fn triangles(ix: &[u32], mode: usize) -> Vec<[u32; 3]> {
    match mode {
        4 => ix.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        5 => (0..ix.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [ix[i], ix[i + 1], ix[i + 2]]
                } else {
                    [ix[i + 1], ix[i], ix[i + 2]]
                }
            })
            .collect(),
        _ => (1..ix.len().saturating_sub(1))
            .map(|i| [ix[i], ix[i + 1], ix[0]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trs_matches_its_matrix_product() {
        // Rotation of 90 degrees about z, then scale 2 on x, translation (1, 2, 3).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let node: Value = serde_json::from_str(&format!(
            r#"{{"translation":[1,2,3],"rotation":[0,0,{h},{h}],"scale":[2,1,1]}}"#
        ))
        .unwrap();
        let m = local_matrix(&node, "n").unwrap();
        let p = transform(&m, [1.0, 0.0, 0.0]);
        // S: (2,0,0); R: (0,2,0); T: (1,4,3).
        for (a, b) in p.iter().zip([1.0, 4.0, 3.0]) {
            assert!((a - b).abs() < 1e-6, "{p:?}");
        }
        assert!((det3(&m) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn strips_and_fans_keep_the_winding() {
        assert_eq!(triangles(&[0, 1, 2, 3], 5), vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles(&[0, 1, 2, 3], 6), vec![[1, 2, 0], [2, 3, 0]]);
        assert_eq!(triangles(&[0, 1, 2, 3], 4), vec![[0, 1, 2]]);
    }
}
