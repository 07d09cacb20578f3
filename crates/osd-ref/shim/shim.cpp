// Thin C ABI over OpenSubdiv 3.5 Far: uniform refinement, primvar interpolation,
// limit positions, stencil tables, and adaptive patch evaluation. See shim.h.
// Every entry point catches C++ exceptions and reports through osd_last_error.

#include "shim.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

thread_local std::string g_error;

void set_error(const std::string &msg) { g_error = msg; }

// Far reports topology problems through a callback; keep the latest message.
void far_error_cb(Far::ErrorType, const char *message) { g_error = message; }
void far_warning_cb(const char *) {}

void install_callbacks() {
    static std::once_flag once;
    std::call_once(once, [] {
        Far::SetErrorCallback(far_error_cb);
        Far::SetWarningCallback(far_warning_cb);
    });
}

// Primvar types for PrimvarRefiner / StencilTable / PatchTable: they only need
// Clear() and AddWithWeight(). Both are layout-compatible with packed floats.
template <int N> struct Vec {
    float v[N];
    void Clear() {
        for (int k = 0; k < N; ++k) v[k] = 0.0f;
    }
    void AddWithWeight(const Vec &src, float w) {
        for (int k = 0; k < N; ++k) v[k] += w * src.v[k];
    }
};
typedef Vec<3> Vec3;
typedef Vec<2> Vec2;
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be packed");
static_assert(sizeof(Vec2) == 2 * sizeof(float), "Vec2 must be packed");

// Double-precision position for the double-precision evaluation path.
struct Vec3d {
    double v[3];
    void Clear() { v[0] = v[1] = v[2] = 0.0; }
    void AddWithWeight(const Vec3d &src, double w) {
        for (int k = 0; k < 3; ++k) v[k] += w * src.v[k];
    }
};

Far::TopologyRefiner *create_refiner(const osd_mesh_desc &m) {
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation((Sdc::Options::VtxBoundaryInterpolation)m.boundary);
    sdc.SetFVarLinearInterpolation((Sdc::Options::FVarLinearInterpolation)m.fvar_interp);
    sdc.SetCreasingMethod((Sdc::Options::CreasingMethod)m.crease_method);
    sdc.SetTriangleSubdivision((Sdc::Options::TriangleSubdivision)m.triangle_smooth);

    Far::TopologyDescriptor desc;
    desc.numVertices = m.num_vertices;
    desc.numFaces = m.num_faces;
    desc.numVertsPerFace = m.face_counts;
    desc.vertIndicesPerFace = m.face_indices;
    desc.numCreases = m.num_creases;
    desc.creaseVertexIndexPairs = m.crease_pairs;
    desc.creaseWeights = m.crease_weights;
    desc.numCorners = m.num_corners;
    desc.cornerVertexIndices = m.corner_vertices;
    desc.cornerWeights = m.corner_weights;
    desc.numHoles = m.num_holes;
    desc.holeIndices = m.holes;

    Far::TopologyDescriptor::FVarChannel channel;
    if (m.uv_indices) {
        channel.numValues = m.num_uvs;
        channel.valueIndices = m.uv_indices;
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
    }

    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    g_error.clear();
    Far::TopologyRefiner *r =
        Factory::Create(desc, Factory::Options((Sdc::SchemeType)m.scheme, sdc));
    if (!r && g_error.empty()) set_error("TopologyRefinerFactory::Create failed");
    return r;
}

// Interpolates positions through levels 1..max of `r`; `all` holds level 0 first.
void interpolate_levels(const Far::TopologyRefiner &r, Vec3 *all) {
    Far::PrimvarRefiner pr(r);
    Vec3 *src = all;
    for (int level = 1; level <= r.GetMaxLevel(); ++level) {
        Vec3 *dst = src + r.GetLevel(level - 1).GetNumVertices();
        pr.Interpolate(level, src, dst);
        src = dst;
    }
}

template <class F> int guarded(F f) {
    try {
        return f();
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return -1;
}

}  // namespace

struct osd_uniform {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<Vec3> scratch;  // levels 0..max-1, for interpolate_last
};

struct osd_stencils {
    std::unique_ptr<const Far::StencilTable> table;
};

struct osd_adaptive {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> patches;
    std::unique_ptr<Far::PatchMap> map;
    int num_ptex = 0;
    int scheme = 1;
    std::vector<Vec3> points;  // all refined vertices, then local points
};

extern "C" {

size_t osd_last_error(char *buf, size_t len) {
    if (buf && len > 0) {
        size_t n = g_error.size() < len - 1 ? g_error.size() : len - 1;
        std::memcpy(buf, g_error.data(), n);
        buf[n] = '\0';
    }
    return g_error.size();
}

// `full_last`: build the last level's full topology (`fullTopologyInLastLevel`), needed by
// `osd_uniform_level_topology` and `osd_uniform_limit` on that level.
osd_uniform *osd_uniform_new(const osd_mesh_desc *mesh, int level, int full_last) {
    install_callbacks();
    try {
        std::unique_ptr<Far::TopologyRefiner> r(create_refiner(*mesh));
        if (!r) return nullptr;
        Far::TopologyRefiner::UniformOptions opts(level);
        opts.fullTopologyInLastLevel = full_last != 0;
        r->RefineUniform(opts);
        osd_uniform *u = new osd_uniform;
        u->refiner = std::move(r);
        return u;
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return nullptr;
}

void osd_uniform_free(osd_uniform *u) { delete u; }

int osd_uniform_level_sizes(const osd_uniform *u, int level, int *sizes) {
    if (level < 0 || level > u->refiner->GetMaxLevel()) {
        set_error("level out of range");
        return -1;
    }
    const Far::TopologyLevel &l = u->refiner->GetLevel(level);
    sizes[0] = l.GetNumVertices();
    sizes[1] = l.GetNumFaces();
    sizes[2] = l.GetNumEdges();
    sizes[3] = l.GetNumFaceVertices();
    sizes[4] = u->refiner->GetNumFVarChannels() > 0 ? l.GetNumFVarValues(0) : -1;
    return 0;
}

int osd_uniform_level_topology(const osd_uniform *u, int level, int *face_counts,
                               int *face_verts, int *edge_verts, uint8_t *face_is_hole,
                               int *fvar_indices) {
    return guarded([&] {
        const Far::TopologyLevel &l = u->refiner->GetLevel(level);
        bool fvar = fvar_indices && u->refiner->GetNumFVarChannels() > 0;
        int k = 0;
        for (int f = 0; f < l.GetNumFaces(); ++f) {
            Far::ConstIndexArray fv = l.GetFaceVertices(f);
            face_counts[f] = fv.size();
            face_is_hole[f] = l.IsFaceHole(f) ? 1 : 0;
            Far::ConstIndexArray fvv;
            if (fvar) fvv = l.GetFaceFVarValues(f, 0);
            for (int i = 0; i < fv.size(); ++i, ++k) {
                face_verts[k] = fv[i];
                if (fvar) fvar_indices[k] = fvv[i];
            }
        }
        for (int e = 0; e < l.GetNumEdges(); ++e) {
            Far::ConstIndexArray ev = l.GetEdgeVertices(e);
            edge_verts[2 * e] = ev[0];
            edge_verts[2 * e + 1] = ev[1];
        }
        return 0;
    });
}

int osd_uniform_interpolate_all(const osd_uniform *u, const float *coarse, float *all) {
    return guarded([&] {
        const Far::TopologyRefiner &r = *u->refiner;
        std::memcpy(all, coarse, sizeof(Vec3) * r.GetLevel(0).GetNumVertices());
        interpolate_levels(r, reinterpret_cast<Vec3 *>(all));
        return 0;
    });
}

int osd_uniform_interpolate_last_f64(const osd_uniform *u, const double *coarse, double *last) {
    return guarded([&] {
        const Far::TopologyRefiner &r = *u->refiner;
        int max = r.GetMaxLevel();
        std::vector<Vec3d> all(r.GetNumVerticesTotal());
        std::memcpy(all.data(), coarse, sizeof(Vec3d) * r.GetLevel(0).GetNumVertices());
        Far::PrimvarRefinerReal<double> pr(r);
        Vec3d *src = all.data();
        for (int level = 1; level <= max; ++level) {
            Vec3d *dst = src + r.GetLevel(level - 1).GetNumVertices();
            pr.Interpolate(level, src, dst);
            src = dst;
        }
        std::memcpy(last, src, sizeof(Vec3d) * r.GetLevel(max).GetNumVertices());
        return 0;
    });
}

int osd_uniform_interpolate_last(osd_uniform *u, const float *coarse, float *last) {
    return guarded([&] {
        const Far::TopologyRefiner &r = *u->refiner;
        int max = r.GetMaxLevel();
        if (max == 0) {
            std::memcpy(last, coarse, sizeof(Vec3) * r.GetLevel(0).GetNumVertices());
            return 0;
        }
        // Level 0 is read in place; levels 1..max-1 go to scratch; max goes to `last`.
        Far::PrimvarRefiner pr(r);
        u->scratch.resize(r.GetNumVerticesTotal());
        const Vec3 *src = reinterpret_cast<const Vec3 *>(coarse);
        Vec3 *next = u->scratch.data();
        for (int level = 1; level <= max; ++level) {
            Vec3 *dst = level == max ? reinterpret_cast<Vec3 *>(last) : next;
            pr.Interpolate(level, src, dst);
            src = dst;
            next = dst + r.GetLevel(level).GetNumVertices();
        }
        return 0;
    });
}

int osd_uniform_interpolate_fvar_all(const osd_uniform *u, const float *coarse, float *all) {
    return guarded([&] {
        const Far::TopologyRefiner &r = *u->refiner;
        if (r.GetNumFVarChannels() < 1) {
            set_error("mesh has no face-varying channel");
            return -1;
        }
        std::memcpy(all, coarse, sizeof(Vec2) * r.GetLevel(0).GetNumFVarValues(0));
        Far::PrimvarRefiner pr(r);
        Vec2 *src = reinterpret_cast<Vec2 *>(all);
        for (int level = 1; level <= r.GetMaxLevel(); ++level) {
            Vec2 *dst = src + r.GetLevel(level - 1).GetNumFVarValues(0);
            pr.InterpolateFaceVarying(level, src, dst, 0);
            src = dst;
        }
        return 0;
    });
}

int osd_uniform_limit(const osd_uniform *u, const float *last_level, float *limit) {
    return guarded([&] {
        Far::PrimvarRefiner pr(*u->refiner);
        const Vec3 *src = reinterpret_cast<const Vec3 *>(last_level);
        Vec3 *dst = reinterpret_cast<Vec3 *>(limit);
        pr.Limit(src, dst);
        return 0;
    });
}

int osd_uniform_limit_fvar(const osd_uniform *u, const float *last_level, float *limit) {
    return guarded([&] {
        if (u->refiner->GetNumFVarChannels() < 1) {
            set_error("mesh has no face-varying channel");
            return -1;
        }
        Far::PrimvarRefiner pr(*u->refiner);
        const Vec2 *src = reinterpret_cast<const Vec2 *>(last_level);
        Vec2 *dst = reinterpret_cast<Vec2 *>(limit);
        pr.LimitFaceVarying(src, dst, 0);
        return 0;
    });
}

osd_stencils *osd_stencils_new(const osd_uniform *u) {
    try {
        Far::StencilTableFactory::Options opts;
        opts.generateIntermediateLevels = false;
        opts.factorizeIntermediateLevels = true;
        opts.generateOffsets = true;
        osd_stencils *s = new osd_stencils;
        s->table.reset(Far::StencilTableFactory::Create(*u->refiner, opts));
        return s;
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return nullptr;
}

void osd_stencils_free(osd_stencils *s) { delete s; }

int osd_stencils_num(const osd_stencils *s) { return s->table->GetNumStencils(); }

int osd_stencils_update(const osd_stencils *s, const float *coarse, float *out) {
    return guarded([&] {
        s->table->UpdateValues(reinterpret_cast<const Vec3 *>(coarse),
                               reinterpret_cast<Vec3 *>(out));
        return 0;
    });
}

osd_adaptive *osd_adaptive_new(const osd_mesh_desc *mesh, int isolation, int single_crease,
                               int inf_sharp, int end_cap) {
    install_callbacks();
    try {
        std::unique_ptr<osd_adaptive> a(new osd_adaptive);
        a->scheme = mesh->scheme;
        a->refiner.reset(create_refiner(*mesh));
        if (!a->refiner) return nullptr;

        Far::PatchTableFactory::Options popts(isolation);
        popts.useSingleCreasePatch = single_crease != 0;
        popts.useInfSharpPatch = inf_sharp != 0;
        popts.SetEndCapType((Far::PatchTableFactory::Options::EndCapType)end_cap);
        a->refiner->RefineAdaptive(popts.GetRefineAdaptiveOptions());
        a->patches.reset(Far::PatchTableFactory::Create(*a->refiner, popts));
        if (!a->patches) {
            set_error("PatchTableFactory::Create failed");
            return nullptr;
        }
        a->map.reset(new Far::PatchMap(*a->patches));
        a->num_ptex = Far::PtexIndices(*a->refiner).GetNumFaces();

        // Positions of every refined vertex (all levels), then the end-cap local points.
        int nref = a->refiner->GetNumVerticesTotal();
        int nlocal = a->patches->GetNumLocalPoints();
        a->points.resize(nref + nlocal);
        std::memcpy(a->points.data(), mesh->positions, sizeof(Vec3) * mesh->num_vertices);
        interpolate_levels(*a->refiner, a->points.data());
        if (nlocal > 0) a->patches->ComputeLocalPointValues(a->points.data(), &a->points[nref]);
        return a.release();
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return nullptr;
}

void osd_adaptive_free(osd_adaptive *a) { delete a; }

int osd_patch_table_only(const osd_mesh_desc *mesh, int isolation, int single_crease,
                         int inf_sharp, int end_cap, int64_t *counts) {
    install_callbacks();
    try {
        std::unique_ptr<Far::TopologyRefiner> refiner(create_refiner(*mesh));
        if (!refiner) return -1;
        Far::PatchTableFactory::Options popts(isolation);
        popts.useSingleCreasePatch = single_crease != 0;
        popts.useInfSharpPatch = inf_sharp != 0;
        popts.SetEndCapType((Far::PatchTableFactory::Options::EndCapType)end_cap);
        refiner->RefineAdaptive(popts.GetRefineAdaptiveOptions());
        std::unique_ptr<Far::PatchTable> pt(Far::PatchTableFactory::Create(*refiner, popts));
        if (!pt) {
            set_error("PatchTableFactory::Create failed");
            return -1;
        }
        counts[0] = pt->GetNumPatchesTotal();
        counts[1] = (int64_t)(pt->GetPatchControlVerticesTable().size() * sizeof(Far::Index) +
                              pt->GetPatchParamTable().size() * sizeof(Far::PatchParam));
        counts[2] = refiner->GetNumVerticesTotal();
        return 0;
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return -1;
}

int osd_adaptive_counts(const osd_adaptive *a, int64_t *counts) {
    const Far::PatchTable &pt = *a->patches;
    counts[0] = pt.GetNumPatchesTotal();
    counts[1] = (int64_t)(pt.GetPatchControlVerticesTable().size() * sizeof(Far::Index) +
                          pt.GetPatchParamTable().size() * sizeof(Far::PatchParam));
    counts[2] = a->num_ptex;
    counts[3] = pt.GetNumLocalPoints();
    // Regular patches: the arrays of the scheme's regular patch type (B-spline for Catmark,
    // quartic box-spline for Loop); every other array holds end caps.
    int64_t regular = 0;
    for (int i = 0; i < pt.GetNumPatchArrays(); ++i) {
        Far::PatchDescriptor::Type t = pt.GetPatchArrayDescriptor(i).GetType();
        if (t == Far::PatchDescriptor::REGULAR || t == Far::PatchDescriptor::LOOP) {
            regular += pt.GetNumPatches(i);
        }
    }
    counts[4] = regular;
    return 0;
}

}  // extern "C"

// Samples an n x n grid of every ptex face (u, v = i/(n-1), v the outer loop; only u + v <= 1
// for triangles), skipping holes, into `out`: position and derivatives w.r.t. the ptex face's
// own (u, v), weights and sums in `Real`. Shared by the f32 and the f64 evaluation.
template <class Real, class Point, class Sample>
static int64_t sample_grid(const Far::PatchTable &pt, const Far::PatchMap &map, int num_ptex,
                           bool triangles, const Point *points, int n, Sample *out, size_t cap) {
    if (n < 2) {
        set_error("need at least 2 samples per side");
        return -1;
    }
    Real wP[20], wDu[20], wDv[20];
    size_t count = 0;
    for (int face = 0; face < num_ptex; ++face) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                float u = (float)i / (float)(n - 1), v = (float)j / (float)(n - 1);
                if (triangles && i + j > n - 1) continue;  // triangular ptex domain u + v <= 1
                const Far::PatchTable::PatchHandle *h = map.FindPatch(face, u, v);
                if (!h) continue;  // hole, or no limit surface here
                Far::PatchDescriptor::Type t = pt.GetPatchDescriptor(*h).GetType();
                if (t == Far::PatchDescriptor::GREGORY ||
                    t == Far::PatchDescriptor::GREGORY_BOUNDARY) {
                    set_error("legacy Gregory patches cannot be evaluated on the CPU");
                    return -1;
                }
                if (count >= cap) {
                    set_error("sample buffer too small");
                    return -1;
                }
                // EvaluateBasis takes the ptex (u,v), normalises it to the patch and scales the
                // derivative weights by 2^depth. On the sub-faces of an n-gon that depth counts
                // the split into quads too (the parameter fraction is 2^-(depth-1)), so halve
                // them: du/dv are then w.r.t. the ptex face's own (u,v), as for quads.
                pt.EvaluateBasis(*h, (Real)u, (Real)v, wP, wDu, wDv);
                Real dscale = pt.GetPatchParam(*h).NonQuadRoot() ? Real(0.5) : Real(1);
                Far::ConstIndexArray cvs = pt.GetPatchVertices(*h);
                Sample &s = out[count++];
                s.face = (uint32_t)face;
                s.u = u;
                s.v = v;
                for (int k = 0; k < 3; ++k) s.p[k] = s.du[k] = s.dv[k] = Real(0);
                for (int c = 0; c < cvs.size(); ++c) {
                    const Point &x = points[cvs[c]];
                    for (int k = 0; k < 3; ++k) {
                        s.p[k] += wP[c] * x.v[k];
                        s.du[k] += dscale * wDu[c] * x.v[k];
                        s.dv[k] += dscale * wDv[c] * x.v[k];
                    }
                }
            }
        }
    }
    return (int64_t)count;
}

extern "C" {

int64_t osd_adaptive_eval_grid(const osd_adaptive *a, int n, osd_limit_sample *out,
                               size_t cap) {
    try {
        return sample_grid<float>(*a->patches, *a->map, a->num_ptex,
                                  a->scheme == Sdc::SCHEME_LOOP, a->points.data(), n, out, cap);
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return -1;
}

int64_t osd_adaptive_eval_grid_f64(const osd_mesh_desc *mesh, int isolation, int single_crease,
                                   int inf_sharp, int end_cap, int n, osd_limit_sample_f64 *out,
                                   size_t cap) {
    install_callbacks();
    try {
        if (n < 2) {
            set_error("need at least 2 samples per side");
            return -1;
        }
        std::unique_ptr<Far::TopologyRefiner> refiner(create_refiner(*mesh));
        if (!refiner) return -1;
        Far::PatchTableFactory::Options popts(isolation);
        popts.useSingleCreasePatch = single_crease != 0;
        popts.useInfSharpPatch = inf_sharp != 0;
        popts.SetEndCapType((Far::PatchTableFactory::Options::EndCapType)end_cap);
        popts.SetPatchPrecision<double>();
        refiner->RefineAdaptive(popts.GetRefineAdaptiveOptions());
        std::unique_ptr<Far::PatchTable> pt(Far::PatchTableFactory::Create(*refiner, popts));
        if (!pt) {
            set_error("PatchTableFactory::Create failed");
            return -1;
        }
        Far::PatchMap map(*pt);
        int num_ptex = Far::PtexIndices(*refiner).GetNumFaces();

        int nref = refiner->GetNumVerticesTotal();
        int nlocal = pt->GetNumLocalPoints();
        std::vector<Vec3d> points(nref + nlocal);
        for (int i = 0; i < mesh->num_vertices; ++i)
            for (int k = 0; k < 3; ++k)
                points[i].v[k] = mesh->positions_f64 ? mesh->positions_f64[3 * i + k]
                                                     : (double)mesh->positions[3 * i + k];
        Far::PrimvarRefinerReal<double> pr(*refiner);
        Vec3d *src = points.data();
        for (int level = 1; level <= refiner->GetMaxLevel(); ++level) {
            Vec3d *dst = src + refiner->GetLevel(level - 1).GetNumVertices();
            pr.Interpolate(level, src, dst);
            src = dst;
        }
        // ComputeLocalPointValues is float-only in 3.5; the double table is reached directly.
        if (nlocal > 0)
            pt->GetLocalPointStencilTable<double>()->UpdateValues(points.data(), &points[nref]);

        return sample_grid<double>(*pt, map, num_ptex, mesh->scheme == Sdc::SCHEME_LOOP,
                                   points.data(), n, out, cap);
    } catch (const std::exception &e) {
        set_error(e.what());
    } catch (...) {
        set_error("unknown C++ exception");
    }
    return -1;
}

}  // extern "C"
