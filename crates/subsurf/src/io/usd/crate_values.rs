//! Field values into a crate file's value area, as Pixar's `crateFile.cpp` lays them out
//! (crate version 0.8.0; 0.9.0 when a `timecode` is written), and the token, string and
//! path tables the values and specs refer to.
//!
//! A value is a 64-bit *rep*: the type (bits 48..56), an array bit (63), an inlined bit (62)
//! and a 48-bit payload. Values of at most 4 bytes (bool, int, float, token, string, asset,
//! enums) are inlined; others are written at the end of the value area and the payload is
//! their file offset. Arrays are 8-byte aligned, a `u64` count, then the elements
//! (uncompressed, which every reader accepts); tokens, strings and paths inside values are
//! `u32` indices into the tables. Dictionaries and time samples hold nested reps, each led
//! by an `i64` jump over the nested value's own data.

use super::crate_types as ty;
use openusd::sdf::{self, Value};
use std::collections::HashMap;

/// Sdf fields whose value is a `TfTokenVector` (not a `VtArray<TfToken>`, as attribute
/// values are): Pixar's reader checks their type.
const TOKEN_VECTOR_FIELDS: &[&str] = &[
    "primChildren",
    "properties",
    "variantChildren",
    "variantSetChildren",
    "primOrder",
    "propertyOrder",
];

/// Sdf fields whose value is a `std::vector<std::string>`.
const STRING_VECTOR_FIELDS: &[&str] = &["subLayers"];

const ARRAY_BIT: u64 = 1 << 63;
const INLINED_BIT: u64 = 1 << 62;

fn rep(t: u8, array: bool, inlined: bool, payload: u64) -> u64 {
    (if array { ARRAY_BIT } else { 0 })
        | (if inlined { INLINED_BIT } else { 0 })
        | ((t as u64) << 48)
        | (payload & ((1 << 48) - 1))
}

/// The token, string and path tables of a crate file, filled as values and specs use them.
#[derive(Default)]
pub(super) struct Tables {
    /// Tokens, in index order.
    pub tokens: Vec<String>,
    token_ix: HashMap<String, u32>,
    /// Strings, as indices into `tokens`.
    pub strings: Vec<u32>,
    string_ix: HashMap<String, u32>,
    /// Paths, in index order (every path's ancestors before it).
    pub paths: Vec<sdf::Path>,
    path_ix: HashMap<sdf::Path, u32>,
}

impl Tables {
    /// The index of token `s`, added if new.
    pub fn token(&mut self, s: &str) -> u32 {
        if let Some(&i) = self.token_ix.get(s) {
            return i;
        }
        let i = self.tokens.len() as u32;
        self.tokens.push(s.to_string());
        self.token_ix.insert(s.to_string(), i);
        i
    }

    /// The index of string `s` (in the string table), added if new.
    pub fn string(&mut self, s: &str) -> u32 {
        if let Some(&i) = self.string_ix.get(s) {
            return i;
        }
        let t = self.token(s);
        let i = self.strings.len() as u32;
        self.strings.push(t);
        self.string_ix.insert(s.to_string(), i);
        i
    }

    /// The index of path `p`, added (after its ancestors) if new.
    pub fn path(&mut self, p: &sdf::Path) -> u32 {
        if let Some(&i) = self.path_ix.get(p) {
            return i;
        }
        // The unknown ancestors, nearest first (a loop, not recursion: a corrupt layer can
        // hold paths thousands of components deep).
        let mut chain = vec![p.clone()];
        // A corrupt path whose parent is not shorter (e.g. a property path whose prim part is
        // the path itself) ends the chain instead of repeating forever.
        while let Some(parent) = chain.last().and_then(|q| {
            q.parent()
                .filter(|parent| parent.as_str().len() < q.as_str().len())
        }) {
            if self.path_ix.contains_key(&parent) {
                break;
            }
            chain.push(parent);
        }
        let mut i = 0;
        for q in chain.into_iter().rev() {
            i = self.paths.len() as u32;
            self.paths.push(q.clone());
            self.path_ix.insert(q, i);
        }
        i
    }

    /// The index of a path already in the table.
    pub fn path_index(&self, p: &sdf::Path) -> Option<u32> {
        self.path_ix.get(p).copied()
    }
}

/// The value area being written (the file's bytes so far) and the tables.
pub(super) struct Values {
    /// The file's bytes: the bootstrap header, then the values written so far.
    pub buf: Vec<u8>,
    /// The tables the values refer to.
    pub tables: Tables,
    /// The crate version the values need (minor, patch).
    pub version: (u8, u8),
}

impl Values {
    /// An empty value area after a `header`-byte bootstrap.
    pub fn new(header: usize) -> Values {
        Values {
            buf: vec![0; header],
            tables: Tables::default(),
            version: (8, 0),
        }
    }

    fn u32(&mut self, x: u32) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }

    fn u64(&mut self, x: u64) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }

    fn f64(&mut self, x: f64) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }

    /// Writes `bytes` out of line: the rep points at them.
    fn out_of_line(&mut self, t: u8, bytes: &[u8]) -> u64 {
        let at = self.buf.len() as u64;
        self.buf.extend_from_slice(bytes);
        rep(t, false, false, at)
    }

    fn align8(&mut self) {
        while self.buf.len() % 8 != 0 {
            self.buf.push(0);
        }
    }

    /// An array: empty is payload 0; else 8-byte aligned, `u64` count, elements.
    fn array(&mut self, t: u8, count: usize, elements: impl FnOnce(&mut Self)) -> u64 {
        if count == 0 {
            return rep(t, true, false, 0);
        }
        self.align8();
        let at = self.buf.len() as u64;
        self.u64(count as u64);
        elements(self);
        rep(t, true, false, at)
    }

    fn pod_array<T: bytemuck::Pod>(&mut self, t: u8, v: &[T]) -> u64 {
        self.array(t, v.len(), |s| {
            s.buf.extend_from_slice(bytemuck::cast_slice(v))
        })
    }

    fn index_array(&mut self, t: u8, idx: Vec<u32>) -> u64 {
        self.array(t, idx.len(), |s| idx.iter().for_each(|&i| s.u32(i)))
    }

    /// A `u64` count then `u32` indices (the `std::vector` form of tokens, strings, paths).
    fn index_vector(&mut self, idx: &[u32]) {
        self.u64(idx.len() as u64);
        for &i in idx {
            self.u32(i);
        }
    }

    /// A nested value led by an `i64` jump over its own data, then its rep.
    fn nested(&mut self, value: &Value) -> Result<(), String> {
        let at = self.buf.len();
        self.u64(0);
        let r = self.pack("", value)?;
        let jump = (self.buf.len() - at) as i64;
        self.buf[at..at + 8].copy_from_slice(&jump.to_le_bytes());
        self.u64(r);
        Ok(())
    }

    fn dictionary(&mut self, d: &HashMap<String, Value>) -> Result<(), String> {
        let mut keys: Vec<&String> = d.keys().collect();
        keys.sort();
        self.u64(keys.len() as u64);
        for k in keys {
            let s = self.tables.string(k);
            self.u32(s);
            self.nested(&d[k])?;
        }
        Ok(())
    }

    fn layer_offset(&mut self, o: &sdf::LayerOffset) {
        self.f64(o.offset);
        self.f64(o.scale);
    }

    /// A list op: the header byte, then each non-empty list, written by `items`.
    fn list_op<T: Default + Clone + PartialEq>(
        &mut self,
        t: u8,
        op: &sdf::ListOp<T>,
        mut items: impl FnMut(&mut Self, &[T]) -> Result<(), String>,
    ) -> Result<u64, String> {
        let at = self.buf.len() as u64;
        let lists = [
            (1u8 << 1, &op.explicit_items),
            (1 << 2, &op.added_items),
            (1 << 5, &op.prepended_items),
            (1 << 6, &op.appended_items),
            (1 << 3, &op.deleted_items),
            (1 << 4, &op.ordered_items),
        ];
        let mut header = u8::from(op.explicit);
        for (bit, list) in lists {
            if !list.is_empty() {
                header |= bit;
            }
        }
        self.buf.push(header);
        for (_, list) in lists {
            if !list.is_empty() {
                items(self, list)?;
            }
        }
        Ok(rep(t, false, false, at))
    }

    fn paths(&mut self, v: &[sdf::Path]) -> Vec<u32> {
        v.iter().map(|p| self.tables.path(p)).collect()
    }

    /// Packs the value of field `field` (which decides between `TfTokenVector` and
    /// `VtArray<TfToken>`, as Sdf types its fields); the rep, or why it cannot be written.
    pub fn pack(&mut self, field: &str, value: &Value) -> Result<u64, String> {
        use bytemuck::bytes_of;
        let inl = |t: u8, payload: u32| rep(t, false, true, payload as u64);
        Ok(match value {
            Value::Bool(b) => inl(ty::BOOL, *b as u32),
            Value::Uchar(x) => inl(ty::UCHAR, *x as u32),
            Value::Int(x) => inl(ty::INT, *x as u32),
            Value::Uint(x) => inl(ty::UINT, *x),
            Value::Half(x) => inl(ty::HALF, x.to_bits() as u32),
            Value::Float(x) => inl(ty::FLOAT, x.to_bits()),
            Value::Int64(x) => self.out_of_line(ty::INT64, &x.to_le_bytes()),
            Value::Uint64(x) => self.out_of_line(ty::UINT64, &x.to_le_bytes()),
            Value::Double(x) => self.out_of_line(ty::DOUBLE, &x.to_le_bytes()),
            Value::String(s) => inl(ty::STRING, self.tables.string(s)),
            Value::Token(t) => inl(ty::TOKEN, self.tables.token(t.as_str())),
            Value::AssetPath(a) => inl(ty::ASSET_PATH, self.tables.token(&a.authored_path)),
            Value::Specifier(s) => inl(ty::SPECIFIER, *s as u32),
            Value::Permission(p) => inl(ty::PERMISSION, *p as u32),
            Value::Variability(v) => inl(ty::VARIABILITY, *v as u32),
            Value::ValueBlock => inl(ty::VALUE_BLOCK, 0),
            Value::TimeCode(t) => {
                self.version = self.version.max((9, 0));
                self.out_of_line(ty::TIME_CODE, &t.0.to_le_bytes())
            }
            Value::Vec2h(v) => self.out_of_line(ty::VEC2H, bytes_of(v)),
            Value::Vec2f(v) => self.out_of_line(ty::VEC2F, bytes_of(v)),
            Value::Vec2d(v) => self.out_of_line(ty::VEC2D, bytes_of(v)),
            Value::Vec2i(v) => self.out_of_line(ty::VEC2I, bytes_of(v)),
            Value::Vec3h(v) => self.out_of_line(ty::VEC3H, bytes_of(v)),
            Value::Vec3f(v) => self.out_of_line(ty::VEC3F, bytes_of(v)),
            Value::Vec3d(v) => self.out_of_line(ty::VEC3D, bytes_of(v)),
            Value::Vec3i(v) => self.out_of_line(ty::VEC3I, bytes_of(v)),
            Value::Vec4h(v) => self.out_of_line(ty::VEC4H, bytes_of(v)),
            Value::Vec4f(v) => self.out_of_line(ty::VEC4F, bytes_of(v)),
            Value::Vec4d(v) => self.out_of_line(ty::VEC4D, bytes_of(v)),
            Value::Vec4i(v) => self.out_of_line(ty::VEC4I, bytes_of(v)),
            Value::Matrix2d(m) => self.out_of_line(ty::MATRIX2D, bytes_of(m)),
            Value::Matrix3d(m) => self.out_of_line(ty::MATRIX3D, bytes_of(m)),
            Value::Matrix4d(m) => self.out_of_line(ty::MATRIX4D, bytes_of(m)),
            // GfQuat stores its imaginary part first, then the real part.
            Value::Quath(q) => self.out_of_line(ty::QUATH, bytes_of(&[q.x, q.y, q.z, q.w])),
            Value::Quatf(q) => self.out_of_line(ty::QUATF, bytes_of(&[q.x, q.y, q.z, q.w])),
            Value::Quatd(q) => self.out_of_line(ty::QUATD, bytes_of(&[q.x, q.y, q.z, q.w])),
            Value::BoolVec(v) => {
                let bytes: Vec<u8> = v.iter().map(|&b| b as u8).collect();
                self.pod_array(ty::BOOL, &bytes)
            }
            Value::UcharVec(v) => self.pod_array(ty::UCHAR, v),
            Value::IntVec(v) => self.pod_array(ty::INT, v),
            Value::UintVec(v) => self.pod_array(ty::UINT, v),
            Value::Int64Vec(v) => self.pod_array(ty::INT64, v),
            Value::Uint64Vec(v) => self.pod_array(ty::UINT64, v),
            Value::HalfVec(v) => self.pod_array(ty::HALF, v),
            Value::FloatVec(v) => self.pod_array(ty::FLOAT, v),
            Value::DoubleVec(v) => self.pod_array(ty::DOUBLE, v),
            Value::TimeCodeVec(v) => {
                self.version = self.version.max((9, 0));
                let t: Vec<f64> = v.iter().map(|t| t.0).collect();
                self.pod_array(ty::TIME_CODE, &t)
            }
            Value::Vec2hVec(v) => self.pod_array(ty::VEC2H, v),
            Value::Vec2fVec(v) => self.pod_array(ty::VEC2F, v),
            Value::Vec2dVec(v) => self.pod_array(ty::VEC2D, v),
            Value::Vec2iVec(v) => self.pod_array(ty::VEC2I, v),
            Value::Vec3hVec(v) => self.pod_array(ty::VEC3H, v),
            Value::Vec3fVec(v) => self.pod_array(ty::VEC3F, v),
            Value::Vec3dVec(v) => self.pod_array(ty::VEC3D, v),
            Value::Vec3iVec(v) => self.pod_array(ty::VEC3I, v),
            Value::Vec4hVec(v) => self.pod_array(ty::VEC4H, v),
            Value::Vec4fVec(v) => self.pod_array(ty::VEC4F, v),
            Value::Vec4dVec(v) => self.pod_array(ty::VEC4D, v),
            Value::Vec4iVec(v) => self.pod_array(ty::VEC4I, v),
            Value::Matrix2dVec(v) => self.pod_array(ty::MATRIX2D, v),
            Value::Matrix3dVec(v) => self.pod_array(ty::MATRIX3D, v),
            Value::Matrix4dVec(v) => self.pod_array(ty::MATRIX4D, v),
            Value::QuathVec(v) => {
                let xyzw: Vec<_> = v.iter().map(|q| [q.x, q.y, q.z, q.w]).collect();
                self.pod_array(ty::QUATH, &xyzw)
            }
            Value::QuatfVec(v) => {
                let xyzw: Vec<_> = v.iter().map(|q| [q.x, q.y, q.z, q.w]).collect();
                self.pod_array(ty::QUATF, &xyzw)
            }
            Value::QuatdVec(v) => {
                let xyzw: Vec<_> = v.iter().map(|q| [q.x, q.y, q.z, q.w]).collect();
                self.pod_array(ty::QUATD, &xyzw)
            }
            Value::TokenVec(v) => {
                let idx: Vec<u32> = v.iter().map(|t| self.tables.token(t.as_str())).collect();
                if TOKEN_VECTOR_FIELDS.contains(&field) {
                    let at = self.buf.len() as u64;
                    self.index_vector(&idx);
                    rep(ty::TOKEN_VECTOR, false, false, at)
                } else {
                    self.index_array(ty::TOKEN, idx)
                }
            }
            Value::StringVec(v) => {
                let idx: Vec<u32> = v.iter().map(|s| self.tables.string(s)).collect();
                if STRING_VECTOR_FIELDS.contains(&field) {
                    let at = self.buf.len() as u64;
                    self.index_vector(&idx);
                    rep(ty::STRING_VECTOR, false, false, at)
                } else {
                    self.index_array(ty::STRING, idx)
                }
            }
            // Asset arrays hold string indices (a single asset, a token index).
            Value::AssetPathVec(v) => {
                let idx = v
                    .iter()
                    .map(|a| self.tables.string(&a.authored_path))
                    .collect();
                self.index_array(ty::ASSET_PATH, idx)
            }
            Value::PathVec(v) => {
                let idx = self.paths(v);
                let at = self.buf.len() as u64;
                self.index_vector(&idx);
                rep(ty::PATH_VECTOR, false, false, at)
            }
            Value::LayerOffsetVec(v) => {
                let at = self.buf.len() as u64;
                self.u64(v.len() as u64);
                v.iter().for_each(|o| self.layer_offset(o));
                rep(ty::LAYER_OFFSET_VECTOR, false, false, at)
            }
            Value::Dictionary(d) => {
                let at = self.buf.len() as u64;
                self.dictionary(d)?;
                rep(ty::DICTIONARY, false, false, at)
            }
            Value::VariantSelectionMap(m) => {
                let at = self.buf.len() as u64;
                let mut keys: Vec<&String> = m.keys().collect();
                keys.sort();
                self.u64(keys.len() as u64);
                for k in keys {
                    let (a, b) = (self.tables.string(k), self.tables.string(&m[k]));
                    self.u32(a);
                    self.u32(b);
                }
                rep(ty::VARIANT_SELECTION_MAP, false, false, at)
            }
            Value::TimeSamples(samples) => self.time_samples(samples)?,
            Value::Payload(p) => {
                let at = self.buf.len() as u64;
                self.payload(p);
                rep(ty::PAYLOAD, false, false, at)
            }
            Value::TokenListOp(op) => self.list_op(ty::TOKEN_LIST_OP, op, |s, items| {
                let idx: Vec<u32> = items.iter().map(|t| s.tables.token(t.as_str())).collect();
                s.index_vector(&idx);
                Ok(())
            })?,
            Value::StringListOp(op) => self.list_op(ty::STRING_LIST_OP, op, |s, items| {
                let idx: Vec<u32> = items.iter().map(|t| s.tables.string(t)).collect();
                s.index_vector(&idx);
                Ok(())
            })?,
            Value::PathListOp(op) => self.list_op(ty::PATH_LIST_OP, op, |s, items| {
                let idx = s.paths(items);
                s.index_vector(&idx);
                Ok(())
            })?,
            Value::IntListOp(op) => self.list_op(ty::INT_LIST_OP, op, pod_list)?,
            Value::Int64ListOp(op) => self.list_op(ty::INT64_LIST_OP, op, pod_list)?,
            Value::UIntListOp(op) => self.list_op(ty::UINT_LIST_OP, op, pod_list)?,
            Value::UInt64ListOp(op) => self.list_op(ty::UINT64_LIST_OP, op, pod_list)?,
            Value::ReferenceListOp(op) => self.list_op(ty::REFERENCE_LIST_OP, op, |s, items| {
                s.u64(items.len() as u64);
                for r in items {
                    let (a, p) = (s.tables.string(&r.asset_path), s.tables.path(&r.prim_path));
                    s.u32(a);
                    s.u32(p);
                    s.layer_offset(&r.layer_offset);
                    s.dictionary(&r.custom_data)?;
                }
                Ok(())
            })?,
            Value::PayloadListOp(op) => self.list_op(ty::PAYLOAD_LIST_OP, op, |s, items| {
                s.u64(items.len() as u64);
                items.iter().for_each(|p| s.payload(p));
                Ok(())
            })?,
            other => {
                let name: &'static str = other.into();
                return Err(format!("a {name} value cannot be written to a crate file"));
            }
        })
    }

    /// A payload: asset (string index), prim path, layer offset (always, from 0.8.0).
    fn payload(&mut self, p: &sdf::Payload) {
        let (a, path) = (
            self.tables.string(&p.asset_path),
            self.tables.path(&p.prim_path),
        );
        self.u32(a);
        self.u32(path);
        let identity = sdf::LayerOffset {
            offset: 0.0,
            scale: 1.0,
        };
        self.layer_offset(p.layer_offset.as_ref().unwrap_or(&identity));
    }

    /// Time samples: a jump, the times (a `DoubleVector`) and their rep; a jump, each
    /// sample's value data, then the count and the samples' reps.
    fn time_samples(&mut self, samples: &[(f64, Value)]) -> Result<u64, String> {
        let at = self.buf.len();
        self.u64(0);
        let times_at = self.buf.len() as u64;
        self.u64(samples.len() as u64);
        samples.iter().for_each(|(t, _)| self.f64(*t));
        let times = rep(ty::DOUBLE_VECTOR, false, false, times_at);
        let jump = (self.buf.len() - at) as i64;
        self.buf[at..at + 8].copy_from_slice(&jump.to_le_bytes());
        self.u64(times);
        let at2 = self.buf.len();
        self.u64(0);
        let reps = samples
            .iter()
            .map(|(_, v)| self.pack("", v))
            .collect::<Result<Vec<u64>, String>>()?;
        let jump = (self.buf.len() - at2) as i64;
        self.buf[at2..at2 + 8].copy_from_slice(&jump.to_le_bytes());
        self.u64(reps.len() as u64);
        reps.iter().for_each(|&r| self.u64(r));
        Ok(rep(ty::TIME_SAMPLES, false, false, at as u64))
    }
}

/// A list of plain numbers: `u64` count, then the values.
fn pod_list<T: bytemuck::Pod>(s: &mut Values, items: &[T]) -> Result<(), String> {
    s.u64(items.len() as u64);
    s.buf.extend_from_slice(bytemuck::cast_slice(items));
    Ok(())
}
