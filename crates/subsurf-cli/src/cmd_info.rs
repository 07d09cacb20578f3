//! `subsurf info`: what a mesh file contains.

use crate::common::SchemeArgs;
use std::collections::BTreeMap;
use std::path::PathBuf;
use subsurf::Topology;

/// Print counts, histograms, features and problems of a mesh.
#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf, .glb, or a USD stage (its mesh
    /// prims listed); `-` reads OBJ, PLY, GLB or USD from standard input.
    pub input: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

#[derive(Debug, serde::Serialize)]
struct Info {
    file: String,
    scheme: String,
    boundary: String,
    crease_method: String,
    vertices: usize,
    faces: usize,
    edges: usize,
    face_sizes: BTreeMap<usize, usize>,
    valences: BTreeMap<usize, usize>,
    boundary_edges: usize,
    boundary_vertices: usize,
    non_manifold_edges: usize,
    non_manifold_vertices: usize,
    degenerate_faces: usize,
    unused_vertices: usize,
    semi_sharp_edges: usize,
    infinitely_sharp_edges_tagged: usize,
    corners: usize,
    holes: usize,
    has_uvs: bool,
    manifold: bool,
    closed: bool,
    all_quads: bool,
    bbox_min: [f32; 3],
    bbox_max: [f32; 3],
    /// USD input: the stage's mesh prims.
    #[serde(skip_serializing_if = "Option::is_none")]
    prims: Option<Vec<PrimInfo>>,
}

/// One mesh prim of a USD stage.
#[derive(Debug, serde::Serialize)]
struct PrimInfo {
    path: String,
    vertices: usize,
    faces: usize,
    scheme: String,
}

/// The mesh prims of a USD stage; printed (text) when they are several and none is chosen.
fn usd_prims(a: &InfoArgs) -> anyhow::Result<(Vec<PrimInfo>, bool)> {
    let stage = crate::usd_stage::read_stage(&a.input)?;
    let meshes = stage.meshes()?;
    let prims: Vec<PrimInfo> = meshes
        .iter()
        .map(|m| PrimInfo {
            path: m.path.clone(),
            vertices: m.mesh.num_vertices(),
            faces: m.mesh.num_faces(),
            scheme: if m.subdivide {
                m.mesh.options.scheme.to_string()
            } else {
                "none".into()
            },
        })
        .collect();
    let whole = prims.len() == 1 || a.scheme.prim.is_some() || a.scheme.flatten;
    Ok((prims, whole))
}

pub fn run(a: &InfoArgs) -> anyhow::Result<()> {
    let mut prims = None;
    if crate::usd_stage::is_usd(&a.input) {
        let (list, whole) = usd_prims(a)?;
        if !whole {
            if a.json {
                let out =
                    serde_json::json!({ "file": a.input.display().to_string(), "prims": list });
                println!("{}", serde_json::to_string_pretty(&out)?);
            } else {
                println!("file              {}", a.input.display());
                println!("mesh prims        {} (--prim PATH for one)", list.len());
                for p in &list {
                    println!(
                        "  {}  {} vertices, {} faces, scheme {}",
                        p.path, p.vertices, p.faces, p.scheme
                    );
                }
            }
            return Ok(());
        }
        prims = Some(list);
    }
    let mesh = a.scheme.read(&a.input)?;
    let t = Topology::new(&mesh)?;
    let mut face_sizes = BTreeMap::new();
    for f in 0..t.num_faces() {
        *face_sizes.entry(t.face_size(f)).or_insert(0) += 1;
    }
    let mut valences = BTreeMap::new();
    for v in 0..t.num_vertices() {
        *valences.entry(t.valence(v)).or_insert(0) += 1;
    }
    let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [0.0; 3]));
    let info = Info {
        file: crate::common::shown(&a.input, false),
        scheme: mesh.options.scheme.to_string(),
        boundary: mesh.options.boundary.to_string(),
        crease_method: mesh.options.crease_method.to_string(),
        vertices: t.num_vertices(),
        faces: t.num_faces(),
        edges: t.num_edges(),
        face_sizes,
        valences,
        boundary_edges: t.boundary_edges().len(),
        boundary_vertices: (0..t.num_vertices())
            .filter(|&v| t.is_boundary_vertex(v))
            .count(),
        non_manifold_edges: t.non_manifold_edges().len(),
        non_manifold_vertices: t.non_manifold_vertices().len(),
        degenerate_faces: t.degenerate_faces().len(),
        unused_vertices: t.unused_vertices().len(),
        semi_sharp_edges: (0..t.num_edges())
            .filter(|&e| t.is_semi_sharp_edge(e))
            .count(),
        infinitely_sharp_edges_tagged: mesh
            .creases
            .iter()
            .filter(|c| c.sharpness >= subsurf::SHARPNESS_INFINITE)
            .count(),
        corners: mesh.corners.len(),
        holes: mesh.holes.len(),
        has_uvs: mesh.uvs.is_some(),
        manifold: t.is_manifold(),
        closed: t.is_closed(),
        all_quads: t.is_all_quads(),
        bbox_min: lo,
        bbox_max: hi,
        prims,
    };
    if a.json {
        println!("{}", serde_json::to_string_pretty(&info)?);
        return Ok(());
    }
    let hist = |h: &BTreeMap<usize, usize>| {
        h.iter()
            .map(|(k, v)| format!("{k}:{v}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    println!("file              {}", info.file);
    println!(
        "scheme            {} (boundary {}, creases {})",
        info.scheme, info.boundary, info.crease_method
    );
    println!("vertices          {}", info.vertices);
    println!(
        "faces             {}  sizes {}",
        info.faces,
        hist(&info.face_sizes)
    );
    println!("edges             {}", info.edges);
    println!("valences          {}", hist(&info.valences));
    println!(
        "boundary          {} edges, {} vertices",
        info.boundary_edges, info.boundary_vertices
    );
    println!(
        "non-manifold      {} edges, {} vertices",
        info.non_manifold_edges, info.non_manifold_vertices
    );
    println!("degenerate faces  {}", info.degenerate_faces);
    println!("unused vertices   {}", info.unused_vertices);
    println!(
        "creases           {} semi-sharp edges, {} infinitely sharp tags",
        info.semi_sharp_edges, info.infinitely_sharp_edges_tagged
    );
    println!("corners           {}", info.corners);
    println!("holes             {}", info.holes);
    println!(
        "uvs               {}",
        if info.has_uvs { "yes" } else { "no" }
    );
    println!(
        "manifold {}  closed {}  all quads {}",
        info.manifold, info.closed, info.all_quads
    );
    println!(
        "bounding box      {:?} .. {:?}",
        info.bbox_min, info.bbox_max
    );
    for p in info.prims.iter().flatten() {
        println!(
            "mesh prim         {}  {} vertices, {} faces, scheme {}",
            p.path, p.vertices, p.faces, p.scheme
        );
    }
    Ok(())
}
