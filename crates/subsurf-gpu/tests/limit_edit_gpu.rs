//! Crease edits of an uploaded table ([`GpuLimit::apply_edit`]): after the edit the GPU
//! evaluation equals, bit for bit, the GPU evaluation of a fresh upload of a fresh build of
//! the edited mesh; only changed ranges are written; a rebuilt table is refused.

mod common;

use common::{bits, context_or_skip};
use subsurf::limit::{EditOutcome, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::{Mesh, Topology};
use subsurf_gpu::{GpuContext, GpuError, GpuLimit};

fn load(name: &str) -> Mesh {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    subsurf::io::read_path(dir.join(format!("{name}.obj"))).unwrap()
}

/// Every crease of `mesh` at `s` (its own values for `None`).
fn creases(mesh: &Mesh, s: Option<f32>) -> Vec<SharpnessEdit> {
    SharpnessEdit::creases(&mesh.creases, s)
}

/// Positions and normals at three samples in every ptex face.
fn evaluate(ctx: &GpuContext, gpu: &mut GpuLimit, table: &PatchTable, mesh: &Mesh) -> Vec<f32> {
    let queries: Vec<(u32, f32, f32)> = (0..table.num_ptex_faces() as u32)
        .flat_map(|f| [(f, 0.5, 0.5), (f, 0.1, 0.8), (f, 1.0, 0.0)])
        .collect();
    let samples = gpu.samples(ctx, &queries, false).unwrap();
    gpu.update(ctx, &mesh.positions).unwrap();
    gpu.eval(ctx, &samples).unwrap();
    samples.download(ctx).unwrap()
}

/// The car's creases from 3.5 to their own sharpness and back, the table updated in place
/// and the upload edited: the same bits as fresh uploads of fresh builds, with fewer bytes
/// written than the tables hold; a structural edit's table is refused.
#[test]
fn edited_upload_evaluates_as_a_fresh_upload() {
    let Some(ctx) = context_or_skip("edited_upload_evaluates_as_a_fresh_upload") else {
        return;
    };
    let mesh = load("catmark_car");
    // Level 4: the creases' decay (3.5 -> 0 at level 4, 6 -> 2) changes refinement
    // stencils, not only the single-crease patches' sharpness.
    let o = PatchOptions::default();
    let mut table = PatchTable::build(&Topology::new(&mesh).unwrap(), &o).unwrap();
    // The first edit keeps the levels (a rebuild); then the upload.
    assert_eq!(
        table.apply_sharpness(&creases(&mesh, Some(3.5))).unwrap(),
        EditOutcome::Rebuilt
    );
    let mut gpu = GpuLimit::new(&ctx, &table).unwrap();
    let mut edited = mesh.clone();
    for s in [None, Some(3.5)] {
        assert_eq!(
            table.apply_sharpness(&creases(&mesh, s)).unwrap(),
            EditOutcome::Updated
        );
        let up = gpu.apply_edit(&ctx, &table).unwrap();
        let whole = table.stencil_bytes() + table.size_bytes();
        assert!(up.levels > 0 && up.patch_words > 0, "{up:?}");
        assert!((up.bytes as usize) < whole, "{up:?} of {whole} bytes");
        for (c, e) in edited.creases.iter_mut().zip(creases(&mesh, s)) {
            if let SharpnessEdit::Edge { sharpness, .. } = e {
                c.sharpness = sharpness;
            }
        }
        let fresh = PatchTable::build(&Topology::new(&edited).unwrap(), &o).unwrap();
        let mut fresh_gpu = GpuLimit::new(&ctx, &fresh).unwrap();
        let want = evaluate(&ctx, &mut fresh_gpu, &fresh, &mesh);
        let got = evaluate(&ctx, &mut gpu, &table, &mesh);
        assert!(bits(&got) == bits(&want), "creases at {s:?}");
    }
    // Creases at 1 are isolated less deep: the table is rebuilt (below level 1, whose faces
    // are decided differently) and the upload refused.
    assert_eq!(
        table.apply_sharpness(&creases(&mesh, Some(1.0))).unwrap(),
        EditOutcome::RebuiltFrom { level: 1 }
    );
    assert!(matches!(
        gpu.apply_edit(&ctx, &table),
        Err(GpuError::BufferMismatch(_))
    ));

    // One crease smoothed: a change of structure made locally (the patches of the faces
    // around it spliced in, their points in segments of local points): refused by the
    // upload's edit and by a fresh upload (its segments are not computed on the GPU yet).
    let c = mesh.creases[0];
    let one = [SharpnessEdit::Edge {
        v0: c.v0,
        v1: c.v1,
        sharpness: 0.0,
    }];
    let outcome = table.apply_sharpness(&one).unwrap();
    assert!(matches!(outcome, EditOutcome::Local { .. }), "{outcome:?}");
    assert!(table.local_segments().len() > 2);
    assert!(matches!(
        gpu.apply_edit(&ctx, &table),
        Err(GpuError::BufferMismatch(_))
    ));
    assert!(matches!(
        GpuLimit::new(&ctx, &table),
        Err(GpuError::BufferMismatch(_))
    ));
}
