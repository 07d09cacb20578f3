//! A layer as a USD crate file (`.usdc`), laid out as Pixar's `crateFile.cpp` reads it.
//!
//! subsurf writes crate version 0.8.0 (0.9.0 when a `timecode` value needs it), the version
//! Pixar's USD itself writes by default and every reader since 2019 opens:
//!
//! - an 88-byte bootstrap (`PXR-USDC`, the version, the table-of-contents offset);
//! - the value area (`crate_values`): every field value not inlined in its rep;
//! - six structural sections, compressed as version 0.4.0 introduced (`crate_codec`):
//!   `TOKENS` (NUL-terminated, LZ4), `STRINGS` (token indices), `FIELDS` (a token index and
//!   a value rep each), `FIELDSETS` (field-index runs, each ended by `u32::MAX`), `PATHS`
//!   (the path tree in pre-order: path index, element token, negative for a property, and
//!   a jump to the next sibling) and `SPECS` (path, field set and spec type of each spec);
//! - the table of contents: each section's name, start and size.
//!
//! Specs are written in path order, fields in the order the spec holds them.

use super::crate_codec::{compress, write_ints};
use super::crate_values::Values;
use openusd::sdf::{self, PathElement, SpecType, Value};
use openusd::tf;
use std::borrow::Cow;
use std::collections::HashMap;

/// The size of the bootstrap header: ident, version, TOC offset, 8 reserved `i64`s.
const BOOTSTRAP: usize = 88;

/// Why a layer could not be written: the spec path and field at fault (either may be empty).
#[derive(Debug)]
pub(super) struct WriteError {
    pub path: String,
    pub field: String,
    pub reason: String,
}

fn file_level(reason: String) -> WriteError {
    WriteError {
        path: String::new(),
        field: String::new(),
        reason,
    }
}

/// The crate file of `data`.
pub(super) fn write(data: &sdf::Data) -> Result<Vec<u8>, WriteError> {
    let mut v = Values::new(BOOTSTRAP);
    // Token 0 is never a property name, so no property element is coded as -0.
    v.tables.token("");
    v.tables.path(&sdf::Path::abs_root());
    let mut specs: Vec<(&sdf::Path, &sdf::SpecData)> = data.iter().collect();
    specs.sort_by(|a, b| a.0.as_str().cmp(b.0.as_str()));

    let mut fields: Vec<(u32, u64)> = Vec::new();
    let mut field_ix: HashMap<(u32, u64), u32> = HashMap::new();
    let mut fieldsets: Vec<i32> = Vec::new();
    let mut spec_rows: Vec<[i32; 3]> = Vec::new();
    for (path, spec) in &specs {
        let path_index = v.tables.path(path);
        let start = fieldsets.len() as i32;
        for (name, value) in sdf_fields(spec) {
            let token = v.tables.token(name);
            let rep = v.pack(name, &value).map_err(|reason| WriteError {
                path: path.as_str().to_string(),
                field: name.to_string(),
                reason,
            })?;
            let ix = *field_ix.entry((token, rep)).or_insert_with(|| {
                fields.push((token, rep));
                fields.len() as u32 - 1
            });
            fieldsets.push(ix as i32);
        }
        fieldsets.push(-1); // u32::MAX: the end of the set
        spec_rows.push([path_index as i32, start, spec.ty as i32]);
    }
    let tree = path_tree(&mut v)?;

    let mut sections: Vec<(&str, usize, usize)> = Vec::new();
    let mut section = |v: &mut Values, name: &'static str, body: Vec<u8>| {
        while v.buf.len() % 8 != 0 {
            v.buf.push(0);
        }
        sections.push((name, v.buf.len(), body.len()));
        v.buf.extend_from_slice(&body);
    };
    let u64s = |xs: &[u64]| -> Vec<u8> { xs.iter().flat_map(|x| x.to_le_bytes()).collect() };

    // Tokens are stored NUL-terminated: one holding a NUL cannot be written (nor read back).
    if let Some(t) = v.tables.tokens.iter().find(|t| t.contains('\0')) {
        return Err(file_level(format!(
            "the token {t:?} holds a NUL character, which a crate file cannot store"
        )));
    }
    let mut chars = Vec::new();
    for t in &v.tables.tokens {
        chars.extend_from_slice(t.as_bytes());
        chars.push(0);
    }
    let packed = compress(&chars).map_err(file_level)?;
    let mut b = u64s(&[
        v.tables.tokens.len() as u64,
        chars.len() as u64,
        packed.len() as u64,
    ]);
    b.extend_from_slice(&packed);
    section(&mut v, "TOKENS", b);

    let mut b = u64s(&[v.tables.strings.len() as u64]);
    b.extend(v.tables.strings.iter().flat_map(|s| s.to_le_bytes()));
    section(&mut v, "STRINGS", b);

    let mut b = u64s(&[fields.len() as u64]);
    let tokens: Vec<i32> = fields.iter().map(|f| f.0 as i32).collect();
    write_ints(&mut b, &tokens).map_err(file_level)?;
    let reps: Vec<u8> = fields.iter().flat_map(|f| f.1.to_le_bytes()).collect();
    let packed = compress(&reps).map_err(file_level)?;
    b.extend_from_slice(&(packed.len() as u64).to_le_bytes());
    b.extend_from_slice(&packed);
    section(&mut v, "FIELDS", b);

    let mut b = u64s(&[fieldsets.len() as u64]);
    write_ints(&mut b, &fieldsets).map_err(file_level)?;
    section(&mut v, "FIELDSETS", b);

    let n = tree[0].len() as u64;
    let mut b = u64s(&[v.tables.paths.len() as u64, n]);
    for column in &tree {
        write_ints(&mut b, column).map_err(file_level)?;
    }
    section(&mut v, "PATHS", b);

    let mut b = u64s(&[spec_rows.len() as u64]);
    for k in 0..3 {
        let column: Vec<i32> = spec_rows.iter().map(|r| r[k]).collect();
        write_ints(&mut b, &column).map_err(file_level)?;
    }
    section(&mut v, "SPECS", b);

    let toc = v.buf.len() as u64;
    let mut b = u64s(&[sections.len() as u64]);
    for (name, start, size) in &sections {
        let mut field = [0u8; 16];
        field[..name.len()].copy_from_slice(name.as_bytes());
        b.extend_from_slice(&field);
        b.extend_from_slice(&(*start as u64).to_le_bytes());
        b.extend_from_slice(&(*size as u64).to_le_bytes());
    }
    v.buf.extend_from_slice(&b);

    let (minor, patch) = v.version;
    v.buf[..8].copy_from_slice(b"PXR-USDC");
    v.buf[8..16].copy_from_slice(&[0, minor, patch, 0, 0, 0, 0, 0]);
    v.buf[16..24].copy_from_slice(&toc.to_le_bytes());
    Ok(v.buf)
}

/// A spec's fields as Sdf names and types them, where the `openusd` crate's in-memory form
/// differs: the property-children key is `properties` (`propertyChildren` in memory),
/// `variantSetNames` is a string list op (a token list op as the text parser reads it), and
/// a relationship states its variability, `uniform`, as Pixar's text reader authors it (its
/// fallback is `varying`).
fn sdf_fields(spec: &sdf::SpecData) -> Vec<(&str, Cow<'_, Value>)> {
    let mut out: Vec<(&str, Cow<'_, Value>)> = spec
        .fields
        .iter()
        .map(|(name, value)| match (name.as_str(), value) {
            ("propertyChildren", v) => ("properties", Cow::Borrowed(v)),
            ("variantSetNames", Value::TokenListOp(op)) => {
                let names = |v: &[tf::Token]| v.iter().map(|t| t.as_str().to_string()).collect();
                let op = sdf::StringListOp {
                    explicit: op.explicit,
                    explicit_items: names(&op.explicit_items),
                    added_items: names(&op.added_items),
                    prepended_items: names(&op.prepended_items),
                    appended_items: names(&op.appended_items),
                    deleted_items: names(&op.deleted_items),
                    ordered_items: names(&op.ordered_items),
                };
                ("variantSetNames", Cow::Owned(Value::StringListOp(op)))
            }
            (name, v) => (name, Cow::Borrowed(v)),
        })
        .collect();
    if spec.ty == SpecType::Relationship && !out.iter().any(|(n, _)| *n == "variability") {
        let uniform = Value::Variability(sdf::Variability::Uniform);
        out.push(("variability", Cow::Owned(uniform)));
    }
    out
}

/// The `PATHS` columns (path indices, element tokens, jumps) of the path table's tree in
/// pre-order. A jump is the distance to the next sibling when a node has both a child (the
/// next entry) and a sibling; 0 for a sibling only, -1 a child only, -2 a leaf.
fn path_tree(v: &mut Values) -> Result<[Vec<i32>; 3], WriteError> {
    let paths = v.tables.paths.clone();
    let n = paths.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut element = vec![0i32; n];
    for (i, p) in paths.iter().enumerate().skip(1) {
        let bad = |why: &str| WriteError {
            path: p.as_str().to_string(),
            field: String::new(),
            reason: format!("this path cannot be written to a crate file ({why})"),
        };
        let parent = p.parent().ok_or_else(|| bad("no parent"))?;
        let parent = v
            .tables
            .path_index(&parent)
            .ok_or_else(|| bad("no parent"))?;
        element[i] = match p.last_element().ok_or_else(|| bad("no final element"))? {
            PathElement::Prim(name) => v.tables.token(name) as i32,
            PathElement::Property(name) => -(v.tables.token(name) as i32),
            PathElement::Variant { set, selection } => {
                v.tables.token(&format!("{{{set}={selection}}}")) as i32
            }
        };
        children[parent as usize].push(i);
    }
    let mut next_sibling = vec![None; n];
    for c in &children {
        for w in c.windows(2) {
            next_sibling[w[0]] = Some(w[1]);
        }
    }
    let mut order = Vec::with_capacity(n);
    let mut stack = vec![0usize];
    while let Some(node) = stack.pop() {
        order.push(node);
        stack.extend(children[node].iter().rev());
    }
    let mut pos = vec![0usize; n];
    for (k, &node) in order.iter().enumerate() {
        pos[node] = k;
    }
    let mut out = [
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    ];
    for (k, &node) in order.iter().enumerate() {
        out[0].push(node as i32);
        out[1].push(element[node]);
        out[2].push(match (children[node].is_empty(), next_sibling[node]) {
            (false, Some(s)) => (pos[s] - k) as i32,
            (true, Some(_)) => 0,
            (false, None) => -1,
            (true, None) => -2,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use openusd::sdf::AbstractData;

    #[test]
    fn a_written_layer_reads_back_with_every_field() {
        let text = r#"#usda 1.0
(
    defaultPrim = "W"
    customLayerData = { string creator = "subsurf" int n = 3 }
)
def Xform "W" (kind = "group")
{
    double3 xformOp:translate = (1, 2, 3)
    quatf xformOp:orient = (0.5, 0.5, 0.5, 0.5)
    matrix4d xformOp:transform = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (4, 5, 6, 1))
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:orient", "xformOp:transform"]
    float f.timeSamples = { 1: 2.5, 4: 3 }
    asset tex = @a.png@
    string[] names = ["x", "y"]
    rel material:binding = </W/M>
    def Mesh "M" (customData = { bool flag = 1 })
    {
        int[] faceVertexCounts = []
        texCoord2f[] primvars:st = [(0, 1)] (interpolation = "faceVarying")
    }
}
"#;
        let data = openusd::usda::parse(text).unwrap();
        let bytes = write(&data).unwrap();
        let cursor = std::io::Cursor::new(bytes);
        let back = openusd::usdc::CrateData::open(cursor, true).unwrap();
        let back = sdf::Data::from_abstract(&back).unwrap();
        let mut n = 0;
        for (path, spec) in data.iter() {
            assert_eq!(back.spec_type(path), Some(spec.ty), "{}", path.as_str());
            for (name, value) in &spec.fields {
                let got = back.spec(path).and_then(|s| s.get(name));
                assert_eq!(got, Some(value), "{} {name}", path.as_str());
                n += 1;
            }
        }
        assert_eq!(back.len(), data.len());
        assert!(n > 20, "{n} fields");
        assert!(data.iter().any(|(_, s)| s.ty == SpecType::Relationship));
        let root = back.spec(&sdf::Path::abs_root()).unwrap();
        assert!(matches!(root.get("primChildren"), Some(Value::TokenVec(v)) if v.len() == 1));
    }

    #[test]
    fn a_value_without_a_crate_form_is_an_error_naming_the_spec_and_field() {
        let mut data = sdf::Data::new();
        let path = sdf::Path::new("/A").unwrap();
        data.create_spec(path, SpecType::Prim)
            .add("custom:thing", Value::ValueVec(vec![Value::Int(1)]));
        let e = write(&data).unwrap_err();
        assert_eq!((e.path.as_str(), e.field.as_str()), ("/A", "custom:thing"));
        assert!(e.reason.contains("cannot be written"), "{}", e.reason);
    }
}
