//! CPU-side checks and vertex assembly.
//!
//! Triangles of different colour classes that share a vertex get their own copy of it (one
//! per class met at that vertex), so indexed drawing still works with flat per-triangle
//! colours: the vertex count grows only along class borders.

use crate::{RenderError, RenderMesh, RenderOptions};
use bytemuck::{Pod, Zeroable};
use std::collections::HashMap;

/// One GPU vertex: position, normal, sRGB colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub color: [u8; 4],
}

/// Vertices and triangle indices ready for upload.
#[derive(Debug, Default)]
pub(crate) struct SurfaceVertices {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

/// Checks lengths, index ranges and finiteness of `mesh`, and the image size.
pub(crate) fn validate(mesh: &RenderMesh, o: &RenderOptions) -> Result<(), RenderError> {
    let bad = |s: String| Err(RenderError::InvalidMesh(s));
    if o.width == 0 || o.height == 0 {
        return Err(RenderError::InvalidOptions(format!(
            "image size {}x{}",
            o.width, o.height
        )));
    }
    if o.samples != 1 && o.samples != 4 {
        return Err(RenderError::InvalidOptions(format!(
            "{} samples (use 1 or 4)",
            o.samples
        )));
    }
    if o.palette.is_empty() {
        return Err(RenderError::InvalidOptions("empty palette".into()));
    }
    if mesh.normals.len() != mesh.positions.len() {
        return bad(format!(
            "{} normals for {} positions",
            mesh.normals.len(),
            mesh.positions.len()
        ));
    }
    if mesh.indices.len() % 3 != 0 {
        return bad(format!(
            "{} indices is not a multiple of 3",
            mesh.indices.len()
        ));
    }
    let n = mesh.positions.len();
    if let Some(i) = mesh.indices.iter().position(|&i| i as usize >= n) {
        return bad(format!("index {} at {i} >= {n} vertices", mesh.indices[i]));
    }
    if let Some(c) = &mesh.triangle_class {
        if c.len() != mesh.num_triangles() {
            return bad(format!(
                "{} triangle classes for {} triangles",
                c.len(),
                mesh.num_triangles()
            ));
        }
    }
    let finite = |p: &[f32; 3]| p.iter().all(|x| x.is_finite());
    if let Some(v) = mesh.positions.iter().position(|p| !finite(p)) {
        return bad(format!("position {v} is not finite"));
    }
    if mesh.lines.iter().any(|l| !finite(&l[0]) || !finite(&l[1])) {
        return bad("a line end is not finite".into());
    }
    if mesh.indices.is_empty() && mesh.lines.is_empty() {
        return bad("no triangles and no lines".into());
    }
    Ok(())
}

/// Assembles coloured vertices, duplicating a vertex for each extra class it borders.
pub(crate) fn surface_vertices(mesh: &RenderMesh, o: &RenderOptions) -> SurfaceVertices {
    let color = |rgb: [u8; 3]| [rgb[0], rgb[1], rgb[2], 255];
    let make = |v: usize, rgb: [u8; 3]| Vertex {
        position: mesh.positions[v],
        normal: mesh.normals[v],
        color: color(rgb),
    };
    let Some(classes) = &mesh.triangle_class else {
        return SurfaceVertices {
            vertices: (0..mesh.positions.len())
                .map(|v| make(v, o.base_color))
                .collect(),
            indices: mesh.indices.clone(),
        };
    };
    let n = mesh.positions.len();
    // first_class[v]: the class that owns copy v; extra copies in `extra`.
    let mut first_class: Vec<Option<u8>> = vec![None; n];
    let mut extra: HashMap<(u32, u8), u32> = HashMap::new();
    let mut vertices: Vec<Vertex> = (0..n).map(|v| make(v, o.base_color)).collect();
    let mut indices = Vec::with_capacity(mesh.indices.len());
    for (t, tri) in mesh.indices.chunks_exact(3).enumerate() {
        let c = classes[t];
        let rgb = o.palette[c as usize % o.palette.len()];
        for &v in tri {
            let vu = v as usize;
            let idx = match first_class[vu] {
                None => {
                    first_class[vu] = Some(c);
                    vertices[vu].color = color(rgb);
                    v
                }
                Some(fc) if fc == c => v,
                Some(_) => *extra.entry((v, c)).or_insert_with(|| {
                    vertices.push(make(vu, rgb));
                    (vertices.len() - 1) as u32
                }),
            };
            indices.push(idx);
        }
    }
    SurfaceVertices { vertices, indices }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_split_only_border_vertices() {
        // Two triangles sharing edge 1-2, in different classes: 2 extra copies.
        let mesh = RenderMesh {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            indices: vec![0, 1, 2, 2, 1, 3],
            triangle_class: Some(vec![1, 2]),
            lines: vec![],
        };
        let o = RenderOptions::default();
        validate(&mesh, &o).unwrap();
        let s = surface_vertices(&mesh, &o);
        assert_eq!(s.vertices.len(), 6);
        for (t, tri) in s.indices.chunks_exact(3).enumerate() {
            let want = o.palette[[1, 2][t]];
            for (k, &i) in tri.iter().enumerate() {
                let v = s.vertices[i as usize];
                assert_eq!(&v.color[..3], &want[..]);
                // Each copy keeps the position and normal of the vertex it stands for.
                let orig = mesh.indices[3 * t + k] as usize;
                assert_eq!(v.position, mesh.positions[orig]);
                assert_eq!(v.normal, mesh.normals[orig]);
            }
        }
    }
}
