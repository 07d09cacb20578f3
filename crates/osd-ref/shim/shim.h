/*
 * C ABI over OpenSubdiv 3.5's Far API, used by the `osd-ref` Rust crate.
 *
 * Conventions: counts are `int`; arrays of points are packed floats (xyz or uv);
 * functions returning a pointer give NULL on failure, functions returning `int`
 * give 0 on success and -1 on failure. After a failure `osd_last_error` copies a
 * message describing it (thread-local).
 */
#ifndef OSD_REF_SHIM_H
#define OSD_REF_SHIM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A polygon mesh with tags and options, borrowed for the duration of a call. */
typedef struct osd_mesh_desc {
    int num_vertices;
    const float *positions; /* 3 * num_vertices */
    int num_faces;
    const int *face_counts;  /* num_faces */
    const int *face_indices; /* sum(face_counts) */
    int num_creases;
    const int *crease_pairs;     /* 2 * num_creases */
    const float *crease_weights; /* num_creases */
    int num_corners;
    const int *corner_vertices;
    const float *corner_weights;
    int num_holes;
    const int *holes;
    int num_uvs;           /* 0 and uv_indices == NULL: no face-varying channel */
    const float *uvs;      /* 2 * num_uvs */
    const int *uv_indices; /* parallel to face_indices */
    int scheme;            /* Sdc::SchemeType: 0 bilinear, 1 catmark, 2 loop */
    int boundary;          /* Sdc::Options::VtxBoundaryInterpolation */
    int crease_method;     /* Sdc::Options::CreasingMethod */
    int triangle_smooth;   /* Sdc::Options::TriangleSubdivision */
    int fvar_interp;       /* Sdc::Options::FVarLinearInterpolation */
    const double *positions_f64; /* 3 * num_vertices, or NULL: the positions as given, read
                                    by the double-precision paths instead of `positions` */
} osd_mesh_desc;

/* One limit-surface sample; layout shared with the Rust `LimitSample`. */
typedef struct osd_limit_sample {
    uint32_t face; /* ptex face index */
    float u, v;
    float p[3], du[3], dv[3];
} osd_limit_sample;

/* The same in double precision (OpenSubdiv's double-precision path). */
typedef struct osd_limit_sample_f64 {
    uint32_t face;
    float u, v;
    double p[3], du[3], dv[3];
} osd_limit_sample_f64;

size_t osd_last_error(char *buf, size_t len);

/* ---- uniform refinement ------------------------------------------------ */
typedef struct osd_uniform osd_uniform;

osd_uniform *osd_uniform_new(const osd_mesh_desc *mesh, int level, int full_last);
void osd_uniform_free(osd_uniform *u);
/* sizes[5] = vertices, faces, edges, face-vertex indices, fvar values (-1 if none) */
int osd_uniform_level_sizes(const osd_uniform *u, int level, int *sizes);
/* Writes topology of one level; fvar_indices may be NULL. face_is_hole: 0/1 bytes. */
int osd_uniform_level_topology(const osd_uniform *u, int level, int *face_counts,
                               int *face_verts, int *edge_verts, uint8_t *face_is_hole,
                               int *fvar_indices);
/* coarse: 3 * V0 floats. all: 3 * total vertices, levels concatenated. */
int osd_uniform_interpolate_all(const osd_uniform *u, const float *coarse, float *all);
/* last: 3 * V(max level) floats. Not thread-safe on one handle (internal scratch). */
int osd_uniform_interpolate_last(osd_uniform *u, const float *coarse, float *last);
/* The last level in double precision (PrimvarRefinerReal<double>) from double positions. */
int osd_uniform_interpolate_last_f64(const osd_uniform *u, const double *coarse, double *last);
/* coarse: 2 * fvar values of level 0; all: 2 * total fvar values. */
int osd_uniform_interpolate_fvar_all(const osd_uniform *u, const float *coarse, float *all);
/* last_level: 3 * V(max level) floats, limit: same size. */
int osd_uniform_limit(const osd_uniform *u, const float *last_level, float *limit);
/* last_level: 2 * fvar values of the max level, limit: same size (LimitFaceVarying). */
int osd_uniform_limit_fvar(const osd_uniform *u, const float *last_level, float *limit);

/* ---- stencil table (last level only, intermediate levels factorized) --- */
typedef struct osd_stencils osd_stencils;

osd_stencils *osd_stencils_new(const osd_uniform *u);
void osd_stencils_free(osd_stencils *s);
int osd_stencils_num(const osd_stencils *s);
int osd_stencils_update(const osd_stencils *s, const float *coarse, float *out);

/* ---- adaptive refinement + patch table --------------------------------- */
typedef struct osd_adaptive osd_adaptive;

/* end_cap: Far::PatchTableFactory::Options::EndCapType (2 bspline, 3 gregory, 4 legacy) */
osd_adaptive *osd_adaptive_new(const osd_mesh_desc *mesh, int isolation, int single_crease,
                               int inf_sharp, int end_cap);
void osd_adaptive_free(osd_adaptive *a);
/* counts[5] = patches, bytes of control-vertex + param arrays, ptex faces, local points,
 * regular patches (B-spline or Loop box-spline; the others are end caps) */
int osd_adaptive_counts(const osd_adaptive *a, int64_t *counts);
/* Adaptive refinement and the patch table only (no patch map, no points), for timing:
 * counts[3] = patches, bytes of control-vertex + param arrays, refined vertices (all levels).
 * Returns 0 or -1. */
int osd_patch_table_only(const osd_mesh_desc *mesh, int isolation, int single_crease,
                         int inf_sharp, int end_cap, int64_t *counts);
/* Samples an n x n grid on every ptex face with a patch; returns the count written
 * (at most cap) or -1. */
int64_t osd_adaptive_eval_grid(const osd_adaptive *a, int n, osd_limit_sample *out, size_t cap);

/* osd_adaptive_new + osd_adaptive_eval_grid in double precision throughout: the positions
 * (widened from float), every refined level (PrimvarRefinerReal<double>), the end-cap
 * local points (double stencils, SetPatchPrecision<double>) and the basis
 * (EvaluateBasis<double>). Same samples as osd_adaptive_eval_grid. */
int64_t osd_adaptive_eval_grid_f64(const osd_mesh_desc *mesh, int isolation, int single_crease,
                                   int inf_sharp, int end_cap, int n, osd_limit_sample_f64 *out,
                                   size_t cap);

#ifdef __cplusplus
}
#endif

#endif
