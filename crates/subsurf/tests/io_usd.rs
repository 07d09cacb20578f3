//! USD in and out, checked against Pixar's own library (usd-core, python3 `pxr`):
//!
//! - stages pxr wrote (`tests/usd_gen.py`: every UsdGeomMesh attribute subsurf reads, all
//!   crease forms, corners, holes, st indexed and not, leftHanded, several prims under
//!   transforms, as usda, usdc and usdz) read into the meshes and world transforms the script
//!   computed independently; the committed copies always, freshly generated ones when pxr is
//!   present;
//! - stages subsurf writes (usda, usdc from subsurf's own crate writer, and usdz packaging a
//!   crate layer; cages and refined meshes) open in `pxr.Usd.Stage.Open` with the same
//!   values, prims, types and transforms, and pxr reports no error reading them; a stage
//!   read and written as usdc is, to pxr, the very layer of the text it came from (every
//!   spec, field and value: xformOps of every type, time samples, dictionaries, list ops,
//!   variants, relationships);
//! - every regression shape written as usdc and as usdz reads back (subsurf's reader) as the
//!   OBJ's mesh bit for bit (the options USD cannot state aside), opens in pxr with the same
//!   points, indices, creases, corners, holes and st, and refines to the same positions;
//! - malformed input is an `Error::Usd` naming the file, the prim and the attribute.
//!
//! The pxr checks fail when `CI=true` and `python3 -c "import pxr"` fails, and are skipped
//! with a loud message otherwise.

use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use subsurf::io::usd::{MeshPrim, Stage, UsdFormat};
use subsurf::{
    BoundaryInterpolation, Error, FVarLinearInterpolation, Mesh, Refiner, Scheme, Topology,
    TriangleSubdivision,
};

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/usd")
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("subsurf-usd-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn have_pxr() -> bool {
    let ok = std::process::Command::new("python3")
        .args(["-c", "import pxr"])
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    if !ok {
        let msg = "io_usd: python3 with pxr (pip install usd-core) is not available";
        if std::env::var("CI").as_deref() == Ok("true") {
            panic!("{msg} (required when CI=true)");
        }
        eprintln!("\n*** SKIPPED: {msg} ***\n");
    }
    ok
}

fn gen_script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/usd_gen.py")
}

/// `usd_gen.py dump FILE`: the stage as pxr reads it.
fn pxr_dump(file: &Path) -> Json {
    pxr_dump_all(&[file.to_path_buf()])
        .as_object_mut()
        .unwrap()
        .remove(file.to_str().unwrap())
        .unwrap()
}

/// `usd_gen.py dumpall FILE...`: each stage as pxr reads it, by file name, in one run; pxr
/// must report nothing (no error or warning) while reading them.
fn pxr_dump_all(files: &[PathBuf]) -> Json {
    let out = std::process::Command::new("python3")
        .arg(gen_script())
        .arg("dumpall")
        .args(files)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "pxr could not read {files:?}: {stderr}"
    );
    assert!(stderr.trim().is_empty(), "pxr reported: {stderr}");
    serde_json::from_slice(&out.stdout).unwrap()
}

fn f32s(v: &Json) -> Vec<f32> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap() as f32)
        .collect()
}

fn u32s(v: &Json) -> Vec<u32> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap() as u32)
        .collect()
}

fn rows<const N: usize>(v: &Json) -> Vec<[f32; N]> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| f32s(r).try_into().unwrap())
        .collect()
}

fn option_names(m: &Mesh, subdivide: bool) -> [&'static str; 4] {
    let o = &m.options;
    [
        match (subdivide, o.scheme) {
            (false, _) => "none",
            (_, Scheme::Catmark) => "catmullClark",
            (_, Scheme::Bilinear) => "bilinear",
            (_, Scheme::Loop) => "loop",
        },
        match o.boundary {
            BoundaryInterpolation::None => "none",
            BoundaryInterpolation::EdgeOnly => "edgeOnly",
            BoundaryInterpolation::EdgeAndCorner => "edgeAndCorner",
        },
        match o.uv_interpolation {
            FVarLinearInterpolation::None => "none",
            FVarLinearInterpolation::CornersOnly => "cornersOnly",
            FVarLinearInterpolation::CornersPlus1 => "cornersPlus1",
            FVarLinearInterpolation::CornersPlus2 => "cornersPlus2",
            FVarLinearInterpolation::Boundaries => "boundaries",
            FVarLinearInterpolation::All => "all",
        },
        match o.triangle_subdivision {
            TriangleSubdivision::Catmark => "catmullClark",
            TriangleSubdivision::Smooth => "smooth",
        },
    ]
}

/// Asserts that `m` is the mesh `usd_gen.py` expects for its prim.
fn check_expected(file: &str, m: &MeshPrim, e: &Json) {
    let at = format!("{file} {}", m.path);
    let mesh = &m.mesh;
    assert_eq!(mesh.positions, rows::<3>(&e["positions"]), "{at}: points");
    assert_eq!(mesh.face_counts, u32s(&e["face_counts"]), "{at}: counts");
    assert_eq!(mesh.face_indices, u32s(&e["face_indices"]), "{at}: indices");
    let creases: Vec<(u32, u32, f32)> = mesh
        .creases
        .iter()
        .map(|c| (c.v0, c.v1, c.sharpness))
        .collect();
    let want: Vec<(u32, u32, f32)> = e["creases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let c = f32s(c);
            (c[0] as u32, c[1] as u32, c[2])
        })
        .collect();
    assert_eq!(creases, want, "{at}: creases");
    let corners: Vec<(u32, f32)> = mesh
        .corners
        .iter()
        .map(|c| (c.vertex, c.sharpness))
        .collect();
    let want: Vec<(u32, f32)> = rows::<2>(&e["corners"])
        .iter()
        .map(|c| (c[0] as u32, c[1]))
        .collect();
    assert_eq!(corners, want, "{at}: corners");
    assert_eq!(mesh.holes, u32s(&e["holes"]), "{at}: holes");
    let names = option_names(mesh, m.subdivide);
    for (k, key) in ["scheme", "boundary", "fvar", "triangles"]
        .iter()
        .enumerate()
    {
        assert_eq!(names[k], e[key].as_str().unwrap(), "{at}: {key}");
    }
    match (&mesh.uvs, e.get("uv_values")) {
        (None, None) => {}
        (Some(uv), Some(values)) => {
            assert_eq!(uv.values, rows::<2>(values), "{at}: st values");
            assert_eq!(uv.indices, u32s(&e["uv_indices"]), "{at}: st indices");
        }
        (a, b) => panic!(
            "{at}: st present {} / expected {}",
            a.is_some(),
            b.is_some()
        ),
    }
    let world = e["world"].as_array().unwrap();
    for (i, row) in world.iter().enumerate() {
        for (j, x) in row.as_array().unwrap().iter().enumerate() {
            let want = x.as_f64().unwrap();
            assert!(
                (m.world[i][j] - want).abs() < 1e-9,
                "{at}: world[{i}][{j}] {} vs pxr {want}",
                m.world[i][j]
            );
        }
    }
}

fn check_dir(dir: &Path) {
    let expected: Json =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let want = expected.as_object().unwrap();
    for name in ["stage.usda", "stage.usdc", "stage.usdz"] {
        let stage = Stage::read_path(dir.join(name)).unwrap();
        let meshes = stage.meshes().unwrap();
        let paths: Vec<&str> = meshes.iter().map(|m| m.path.as_str()).collect();
        // Document order: /World's children, then /C.
        assert_eq!(
            paths,
            ["/World/A", "/World/Group/B", "/World/D", "/C"],
            "{name}"
        );
        for m in &meshes {
            check_expected(name, m, &want[&m.path]);
        }
    }
}

#[test]
fn pxr_written_stages_read_into_the_expected_meshes() {
    check_dir(&data_dir());
    if !have_pxr() {
        return;
    }
    let dir = tmp("gen");
    let st = std::process::Command::new("python3")
        .arg(gen_script())
        .arg("write")
        .arg(&dir)
        .status()
        .unwrap();
    assert!(st.success(), "usd_gen.py write failed");
    check_dir(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Asserts that pxr reads mesh prim `path` of `dump` as `m` (written as a cage, or refined).
fn check_pxr_mesh(file: &str, dump: &Json, path: &str, m: &Mesh, refined: bool) {
    let d = &dump["meshes"][path];
    let at = format!("{file} {path}");
    assert!(d.is_object(), "{at}: pxr sees no mesh prim");
    assert_eq!(rows::<3>(&d["points"]), m.positions, "{at}: points");
    assert_eq!(u32s(&d["faceVertexCounts"]), m.face_counts, "{at}");
    assert_eq!(u32s(&d["faceVertexIndices"]), m.face_indices, "{at}");
    assert_eq!(d["orientation"], "rightHanded", "{at}");
    let names = option_names(m, !refined);
    assert_eq!(d["subdivisionScheme"], names[0], "{at}");
    assert_eq!(d["faceVaryingLinearInterpolation"], names[2], "{at}");
    if !refined {
        assert_eq!(d["interpolateBoundary"], names[1], "{at}");
        assert_eq!(d["triangleSubdivisionRule"], names[3], "{at}");
        let idx: Vec<u32> = m.creases.iter().flat_map(|c| [c.v0, c.v1]).collect();
        assert_eq!(u32s(&d["creaseIndices"]), idx, "{at}");
        let s: Vec<f32> = m.creases.iter().map(|c| c.sharpness).collect();
        assert_eq!(f32s(&d["creaseSharpnesses"]), s, "{at}");
        let idx: Vec<u32> = m.corners.iter().map(|c| c.vertex).collect();
        assert_eq!(u32s(&d["cornerIndices"]), idx, "{at}");
        let s: Vec<f32> = m.corners.iter().map(|c| c.sharpness).collect();
        assert_eq!(f32s(&d["cornerSharpnesses"]), s, "{at}");
    } else {
        assert_eq!(d["creaseIndices"], Json::Array(vec![]), "{at}");
    }
    assert_eq!(u32s(&d["holeIndices"]), m.holes, "{at}");
    let (lo, hi) = m.bounding_box().unwrap();
    assert_eq!(rows::<3>(&d["extent"]), vec![lo, hi], "{at}: extent");
    match &m.uvs {
        None => assert!(d.get("st").is_none(), "{at}: st"),
        Some(uv) => {
            assert_eq!(d["st_interpolation"], "faceVarying", "{at}");
            assert_eq!(rows::<2>(&d["st"]), uv.values, "{at}: st");
            assert_eq!(u32s(&d["st_indices"]), uv.indices, "{at}: st indices");
        }
    }
}

fn refine(mesh: &Mesh, level: usize) -> Mesh {
    let r = Refiner::new(Topology::new(mesh).unwrap(), level).unwrap();
    let positions = r.refine_positions(&mesh.positions);
    let mut out = r.to_tagged_mesh(level, positions).unwrap();
    if let Some(fv) = &mesh.uvs {
        let fvar = r
            .fvar_refinement(&fv.indices, fv.values.len(), mesh.options.uv_interpolation)
            .unwrap();
        out.uvs = fvar.refine(&fv.values).unwrap().pop();
    }
    out
}

#[test]
fn stages_subsurf_writes_open_in_pxr() {
    let src = Stage::read_path(data_dir().join("stage.usda")).unwrap();
    let meshes = src.meshes().unwrap();
    let mut stage = src.clone();
    // /World/A rewritten as a cage (now right-handed), the others refined once.
    let mut written = Vec::new();
    for m in &meshes {
        let refined = m.path != "/World/A" && m.mesh.options.scheme != Scheme::Loop;
        let mesh = if refined {
            refine(&m.mesh, 1)
        } else {
            m.mesh.clone()
        };
        stage.set_mesh(&m.path, &mesh, refined).unwrap();
        written.push((m.path.clone(), mesh, refined, m.world));
    }
    let dir = tmp("write");
    let pxr = have_pxr();
    // The stage as read, written as a crate file: pxr reads the same layer from it as from
    // the text it came from (every spec, field and value, the other prims' included).
    if pxr {
        let file = dir.join("same.usdc");
        src.write_path(&file).unwrap();
        pxr_same(&data_dir().join("stage.usda"), &file);
    }
    for ext in ["usda", "usdc", "usdz"] {
        let file = dir.join(format!("out.{ext}"));
        stage.write_path(&file).unwrap();
        // Read back by subsurf: the same meshes, transforms and flags.
        let back = Stage::read_path(&file).unwrap().meshes().unwrap();
        assert_eq!(back.len(), written.len(), "{ext}");
        for (b, (path, mesh, refined, world)) in back.iter().zip(&written) {
            assert_eq!(&b.path, path, "{ext}");
            assert_eq!(&b.world, world, "{ext} {path}");
            assert_eq!(b.subdivide, !refined, "{ext} {path}");
            assert_eq!(b.mesh.positions, mesh.positions, "{ext} {path}");
            assert_eq!(b.mesh.face_indices, mesh.face_indices, "{ext} {path}");
            assert_eq!(b.mesh.uvs, mesh.uvs, "{ext} {path}");
            if !refined {
                assert_eq!(&b.mesh, mesh, "{ext} {path}");
            }
        }
        if ext == "usdz" {
            check_usdz_layout(&std::fs::read(&file).unwrap());
        }
        if !pxr {
            continue;
        }
        let dump = pxr_dump(&file);
        for (path, mesh, refined, world) in &written {
            check_pxr_mesh(ext, &dump, path, mesh, *refined);
            let w = &dump["meshes"][path.as_str()]["world"];
            for i in 0..4 {
                for j in 0..4 {
                    let want = w[i][j].as_f64().unwrap();
                    assert!((world[i][j] - want).abs() < 1e-9, "{ext} {path}: world");
                }
            }
        }
        let others: Vec<String> = dump["others"]
            .as_array()
            .unwrap()
            .iter()
            .map(|o| format!("{} {}", o[0].as_str().unwrap(), o[1].as_str().unwrap()))
            .collect();
        assert_eq!(
            others,
            ["/World Xform", "/World/Group Xform", "/World/Ball Sphere"],
            "{ext}: the other prims"
        );
    }
    // A bare mesh written through io::write_path_with (holes kept) opens in pxr as one cage
    // prim; write_path leaves its hole faces out.
    let cage = meshes[0].mesh.clone();
    assert!(!cage.holes.is_empty());
    let keep = subsurf::io::WriteOptions {
        keep_holes: true,
        ..Default::default()
    };
    for ext in ["usda", "usdc", "usdz"] {
        let file = dir.join(format!("cage.{ext}"));
        subsurf::io::write_path(&file, &cage, None).unwrap();
        assert_eq!(
            subsurf::io::read_path(&file).unwrap(),
            cage.without_holes(),
            "{ext}"
        );
        subsurf::io::write_path_with(&file, &cage, None, keep).unwrap();
        assert_eq!(subsurf::io::read_path(&file).unwrap(), cage, "{ext}");
        if pxr {
            check_pxr_mesh(ext, &pxr_dump(&file), "/Mesh", &cage, false);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A layer with the value kinds a stage around meshes holds (layer metadata and its
/// dictionary, kind, every xformOp value type, time samples, assets, string arrays,
/// relationships, customData, apiSchemas, variants, a class and an over).
const RICH_LAYER: &str = r#"#usda 1.0
(
    customLayerData = {
        string creator = "subsurf"
        int n = 3
    }
    defaultPrim = "W"
    metersPerUnit = 0.01
    timeCodesPerSecond = 24
)

def Xform "W" (
    prepend apiSchemas = ["MaterialBindingAPI"]
    kind = "group"
    variants = {
        string look = "b"
    }
    prepend variantSets = "look"
)
{
    rel material:binding = </Mat>
    string[] names = ["x", "y"]
    asset tex = @a.png@
    float f.timeSamples = {
        1: 2.5,
        4: 3,
    }
    quatf xformOp:orient = (0.5, 0.5, 0.5, 0.5)
    matrix4d xformOp:transform = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (4, 5, 6, 1))
    double3 xformOp:translate = (1, 2, 3)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:orient", "xformOp:transform"]

    def Mesh "M" (
        customData = {
            bool flag = 1
        }
    )
    {
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
        texCoord2f[] primvars:st = [(0, 1), (1, 1), (1, 0), (0, 0)] (
            interpolation = "faceVarying"
        )
    }
    variantSet "look" = {
        "a" {
            double size = 1
        }
        "b" {
            double size = 2
        }
    }
}

def Material "Mat"
{
}

class "Base"
{
    int x = 1
}

over "Extra"
{
}
"#;

#[test]
fn crate_files_hold_what_pxr_reads_from_the_text() {
    let stage = Stage::read(RICH_LAYER.as_bytes(), "rich.usda").unwrap();
    let bytes = stage.to_bytes(UsdFormat::Usdc).unwrap();
    let back = Stage::read(&bytes, "rich.usdc").unwrap();
    assert_eq!(back.meshes().unwrap(), stage.meshes().unwrap());
    if !have_pxr() {
        return;
    }
    let dir = tmp("rich");
    std::fs::write(dir.join("rich.usda"), RICH_LAYER).unwrap();
    std::fs::write(dir.join("rich.usdc"), &bytes).unwrap();
    pxr_same(&dir.join("rich.usda"), &dir.join("rich.usdc"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Asserts that pxr reads the same layer (every spec, field and value) from both files.
fn pxr_same(a: &Path, b: &Path) {
    let out = std::process::Command::new("python3")
        .arg(gen_script())
        .arg("same")
        .arg(a)
        .arg(b)
        .output()
        .unwrap();
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "pxr reads another layer from {}:\n{}{}",
        b.display(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A `.usdz` package as the USDZ spec asks: stored (uncompressed) entries whose data start
/// at multiples of 64 bytes, the first a USD layer (a crate file, as subsurf writes them).
fn check_usdz_layout(bytes: &[u8]) {
    let u16le = |o: usize| u16::from_le_bytes([bytes[o], bytes[o + 1]]) as usize;
    let u32le = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().unwrap()) as usize;
    let mut o = 0;
    let mut entries = 0;
    while bytes[o..].starts_with(b"PK\x03\x04") {
        assert_eq!(u16le(o + 8), 0, "entry {entries} is not stored");
        let name_len = u16le(o + 26);
        let extra = u16le(o + 28);
        let data = o + 30 + name_len + extra;
        let name = std::str::from_utf8(&bytes[o + 30..o + 30 + name_len]).unwrap();
        assert_eq!(data % 64, 0, "entry {name} starts at {data}");
        if entries == 0 {
            assert!(name.ends_with(".usdc"), "first entry {name}");
            assert!(bytes[data..].starts_with(b"PXR-USDC"));
        }
        o = data + u32le(o + 18);
        entries += 1;
    }
    assert!(entries >= 1);
}

#[test]
fn regression_shapes_refine_the_same_from_usd_as_from_obj() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    names.sort();
    let bits =
        |m: &Mesh| -> Vec<u32> { m.positions.iter().flatten().map(|x| x.to_bits()).collect() };
    let out = tmp("shapes");
    let mut files = Vec::new();
    let mut checked = 0;
    for (k, path) in names.iter().enumerate() {
        let name = path.file_name().unwrap().to_str().unwrap();
        let obj = subsurf::io::read_path(path).unwrap();
        // USD has no crease method or corner propagation: shapes that set them are left out.
        let opts = obj.options;
        if opts.crease_method != Default::default() || opts.fvar_propagate_corners {
            continue;
        }
        // Every shape as usdc and usdz (the crate writer), every other one also as usda.
        let formats = [UsdFormat::Usdc, UsdFormat::Usdz, UsdFormat::Usda];
        let mut usd = None;
        for &format in &formats[..2 + (k % 2 == 0) as usize] {
            let mut bytes = Vec::new();
            subsurf::io::usd::write(&obj, format, &mut bytes).unwrap();
            let back = subsurf::io::usd::read(&bytes, name).unwrap();
            // point3f[] by default: the OBJ file's digits rounded to f32 once.
            let obj32 = Mesh {
                positions: obj.positions.to_vec().into(),
                ..obj.clone()
            };
            assert_eq!(back, obj32, "{name} through {format:?}");
            // The crate format stores the values' bits (text, their shortest decimal form).
            if format != UsdFormat::Usda {
                assert_eq!(bits(&back), bits(&obj), "{name} through {format:?}");
                let uv_bits = |m: &Mesh| {
                    m.uvs.as_ref().map(|u| {
                        u.values
                            .iter()
                            .flatten()
                            .map(|x| x.to_bits())
                            .collect::<Vec<_>>()
                    })
                };
                assert_eq!(uv_bits(&back), uv_bits(&obj), "{name} through {format:?}");
                let ext = if format == UsdFormat::Usdc {
                    "usdc"
                } else {
                    "usdz"
                };
                let file = out.join(format!("{name}.{ext}"));
                std::fs::write(&file, &bytes).unwrap();
                files.push((file, obj.clone()));
            }
            usd = Some(back);
        }
        let usd = usd.unwrap();
        if obj.options.scheme == Scheme::Loop || Topology::new(&obj).is_err() {
            continue;
        }
        let level = if obj.num_faces() > 2000 { 1 } else { 2 };
        let a = refine(&obj, level);
        let b = refine(&usd, level);
        assert_eq!(bits(&a), bits(&b), "{name}: refined positions");
        assert_eq!(a.face_indices, b.face_indices, "{name}");
        assert_eq!(a.uvs, b.uvs, "{name}: refined UVs");
        checked += 1;
    }
    assert!(checked >= 60, "only {checked} shapes checked");
    // Pixar's USD reads every crate file and package with the same values (one pxr run).
    if have_pxr() {
        let paths: Vec<PathBuf> = files.iter().map(|f| f.0.clone()).collect();
        let dumps = pxr_dump_all(&paths);
        for (file, mesh) in &files {
            let name = file.file_name().unwrap().to_str().unwrap();
            let dump = &dumps[file.to_str().unwrap()];
            check_pxr_mesh(name, dump, "/Mesh", mesh, false);
        }
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// The `Error::Usd` of reading `text`'s meshes.
fn usd_error(text: &str) -> (String, String, String) {
    let err = Stage::read(text.as_bytes(), "bad.usda").and_then(|s| s.meshes());
    match err {
        Err(Error::Usd {
            file,
            prim,
            attribute,
            reason,
        }) => {
            assert_eq!(file, "bad.usda", "{reason}");
            (prim, attribute, reason)
        }
        other => panic!("expected Error::Usd, got {other:?}"),
    }
}

#[test]
fn malformed_input_names_the_file_prim_and_attribute() {
    let good = std::fs::read_to_string(data_dir().join("stage.usda")).unwrap();
    assert!(Stage::read(good.as_bytes(), "bad.usda")
        .unwrap()
        .meshes()
        .is_ok());
    let cases: &[(&str, &str, &str, &str)] = &[
        // (replace, with, prim, attribute)
        (
            "int[] holeIndices = [2]",
            "int[] holeIndices = [6]",
            "/World/A",
            "holeIndices",
        ),
        (
            "int[] faceVertexCounts = [3, 3]",
            "int[] faceVertexCounts = [3, 4]",
            "/C",
            "faceVertexIndices",
        ),
        (
            "int[] faceVertexIndices = [0, 1, 2, 2, 1, 3]",
            "int[] faceVertexIndices = [0, 1, 2, 2, 1, 4]",
            "/C",
            "faceVertexIndices",
        ),
        (
            "int[] faceVertexIndices = [0, 1, 2, 2, 1, 3]",
            "float[] faceVertexIndices = [0, 1, 2, 2, 1, 3]",
            "/C",
            "faceVertexIndices",
        ),
        (
            "int[] creaseLengths = [4, 2]",
            "int[] creaseLengths = [4, 3]",
            "/World/A",
            "creaseIndices",
        ),
        (
            "float[] creaseSharpnesses = [2.5, 10]",
            "float[] creaseSharpnesses = [2.5, 10, 1]",
            "/World/A",
            "creaseSharpnesses",
        ),
        (
            "float[] cornerSharpnesses = [3, 1.5]",
            "float[] cornerSharpnesses = [3]",
            "/World/A",
            "cornerSharpnesses",
        ),
        (
            "int[] primvars:st:indices = [0, 1, 2, 3,",
            "int[] primvars:st:indices = [0, 1, 9, 3,",
            "/World/A",
            "primvars:st:indices",
        ),
        (
            "token interpolateBoundary = \"none\"",
            "token interpolateBoundary = \"sometimes\"",
            "/C",
            "interpolateBoundary",
        ),
        (
            "uniform token orientation = \"leftHanded\"",
            "uniform token orientation = \"upsideDown\"",
            "/World/A",
            "orientation",
        ),
        (
            "float3 xformOp:scale = (2, 2, 2)",
            "float xformOp:scale = 2",
            "/World/Group",
            "xformOp:scale",
        ),
        (
            "point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.5)]",
            "int[] points = [0, 1]",
            "/C",
            "points",
        ),
    ];
    for (from, to, prim, attr) in cases {
        assert!(good.contains(from), "fixture lacks {from}");
        let (p, a, reason) = usd_error(&good.replacen(from, to, 1));
        assert_eq!((p.as_str(), a.as_str()), (*prim, *attr), "{to}: {reason}");
    }
    // Not USD, broken text, and a crate file cut or corrupted anywhere: file errors, no panic.
    assert!(matches!(
        Stage::read(b"solid cube\n", "x.usda"),
        Err(Error::Usd { ref file, .. }) if file == "x.usda"
    ));
    assert!(Stage::read(b"#usda 1.0\ndef Mesh \"A\" {\n int[] x = [1,\n", "x.usda").is_err());
    let crate_bytes = std::fs::read(data_dir().join("stage.usdc")).unwrap();
    let zip_bytes = std::fs::read(data_dir().join("stage.usdz")).unwrap();
    let mut rng = 0x2545f491u32;
    for (name, bytes) in [("c.usdc", &crate_bytes), ("z.usdz", &zip_bytes)] {
        for cut in (0..bytes.len()).step_by(97) {
            let r = Stage::read(&bytes[..cut], name).and_then(|s| s.meshes());
            if let Err(e) = r {
                assert!(matches!(e, Error::Usd { .. }), "{name} cut at {cut}: {e}");
            }
        }
        for _ in 0..300 {
            let mut b = bytes.clone();
            for _ in 0..4 {
                rng ^= rng << 13;
                rng ^= rng >> 17;
                rng ^= rng << 5;
                let i = rng as usize % b.len();
                b[i] = (rng >> 24) as u8;
            }
            if let Err(e) = Stage::read(&b, name).and_then(|s| s.meshes()) {
                assert!(matches!(e, Error::Usd { .. }), "{name}: {e}");
            }
        }
    }
}

/// A property spec that its prim does not list (here `/World/A.orientation`, unlisted by a
/// one-byte corruption the fuzz target found) still gives the attribute's value on Pixar's
/// composed stage, and subsurf reads it the same way: the faces of `/World/A` are pxr's with
/// the leftHanded flip (first corner kept, the rest reversed).
#[test]
fn property_specs_a_prim_does_not_list_read_as_pxr_reads_them() {
    let file = data_dir().join("unlisted_property.usdc");
    let stage = Stage::read(&std::fs::read(&file).unwrap(), "unlisted_property.usdc").unwrap();
    let meshes = stage.meshes().unwrap();
    if !have_pxr() {
        return;
    }
    let dump = pxr_dump(&file);
    for m in &meshes {
        let d = &dump["meshes"][m.path.as_str()];
        let counts = u32s(&d["faceVertexCounts"]);
        let mut faces = u32s(&d["faceVertexIndices"]);
        if d["orientation"] == "leftHanded" {
            let mut at = 0;
            for &c in &counts {
                faces[at + 1..at + c as usize].reverse();
                at += c as usize;
            }
        }
        assert_eq!(faces, m.mesh.face_indices, "{}", m.path);
    }
    assert_eq!(dump["meshes"]["/World/A"]["orientation"], "leftHanded");
}

/// A crate file whose PATHS section claims to run far past the end of the file (found by the
/// fuzz target: it made the reader allocate ~3.8 TB for paths) is a typed error naming the
/// file, not an allocation failure.
#[test]
fn a_section_running_past_the_file_is_an_error() {
    let file = data_dir().join("huge_paths_section.usdc");
    match Stage::read(&std::fs::read(&file).unwrap(), "huge_paths_section.usdc") {
        Err(subsurf::Error::Usd { file, .. }) => assert_eq!(file, "huge_paths_section.usdc"),
        Err(e) => panic!("expected Error::Usd, got {e}"),
        Ok(_) => panic!("a PATHS section past the end of the file was accepted"),
    }
}

/// A stage holding a token with a NUL character (a corrupted crate file the fuzz target
/// found) cannot be written as a crate file, whose tokens are NUL-terminated: a typed error,
/// not a file that fails to read back.
#[test]
fn a_token_holding_nul_is_refused_by_the_crate_writer() {
    let file = data_dir().join("nul_in_token.usdc");
    let stage = Stage::read(&std::fs::read(&file).unwrap(), "nul_in_token.usdc").unwrap();
    match stage.to_bytes(UsdFormat::Usdc) {
        Err(subsurf::Error::Usd { reason, .. }) => assert!(reason.contains("NUL"), "{reason}"),
        Err(e) => panic!("expected Error::Usd, got {e}"),
        Ok(bytes) => panic!(
            "written ({} bytes) although a token holds a NUL: {:?}",
            bytes.len(),
            Stage::read(&bytes, "back.usdc").map(|_| ())
        ),
    }
}

/// A crate file whose prim lists itself among its children (found by the fuzz target: the
/// text writer recursed until the stack overflowed) is refused when written as text, naming
/// the nesting; reading it, and writing it as a crate file, do not recurse without bound.
#[test]
fn a_prim_cycle_is_an_error_when_written_not_a_stack_overflow() {
    let file = data_dir().join("prim_cycle.usdc");
    let stage = Stage::read(&std::fs::read(&file).unwrap(), "prim_cycle.usdc").unwrap();
    match stage.to_bytes(UsdFormat::Usda) {
        Err(subsurf::Error::Usd { reason, .. }) => assert!(reason.contains("nested"), "{reason}"),
        Err(e) => panic!("expected Error::Usd, got {e}"),
        Ok(_) => panic!("a prim cycle was written as text"),
    }
    let _ = stage.to_bytes(UsdFormat::Usdc);
}

/// A crate file holding a path whose parent is not shorter than itself (found by the fuzz
/// target: collecting a path's ancestors for the crate writer's path table looped, growing
/// without bound until memory ran out). Writing it ends, as a crate file that reads back
/// with the same meshes, or as a typed error.
#[test]
fn a_path_without_a_shorter_parent_does_not_loop_when_written() {
    let file = data_dir().join("path_parent_loop.usdc");
    let Ok(stage) = Stage::read(&std::fs::read(&file).unwrap(), "path_parent_loop.usdc") else {
        panic!("the fixture no longer reads: regenerate it from the fuzz artifact");
    };
    let meshes = stage.meshes().map(|m| m.len());
    for format in [UsdFormat::Usda, UsdFormat::Usdc] {
        match stage.to_bytes(format) {
            Ok(bytes) if format == UsdFormat::Usdc => {
                let back = Stage::read(&bytes, "back.usdc").and_then(|s| s.meshes());
                assert_eq!(back.map(|m| m.len()).ok(), meshes.as_ref().ok().copied());
            }
            Ok(_) | Err(subsurf::Error::Usd { .. }) => {}
            Err(e) => panic!("expected Error::Usd, got {e}"),
        }
    }
}
