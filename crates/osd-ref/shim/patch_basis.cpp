// Far::internal::EvaluatePatchBasis (OpenSubdiv 3.5) behind a C ABI: the basis weights of
// one patch of a given type at (u, v) for a packed PatchParam. No mesh is involved.
//
// The function is internal to Far (its header is not installed), but libosdCPU exports
// its double instantiation; the declaration below matches far/patchBasis.h.

#include <opensubdiv/far/patchDescriptor.h>
#include <opensubdiv/far/patchParam.h>

#include <cstdint>

namespace OpenSubdiv {
namespace OPENSUBDIV_VERSION {
namespace Far {
namespace internal {
template <typename REAL>
int EvaluatePatchBasis(int patchType, PatchParam const &param, REAL s, REAL t, REAL wP[],
                       REAL wDs[], REAL wDt[], REAL wDss[], REAL wDst[], REAL wDtt[]);
extern template int EvaluatePatchBasis<double>(int, PatchParam const &, double, double,
                                               double[], double[], double[], double[],
                                               double[], double[]);
}  // namespace internal
}  // namespace Far
}  // namespace OPENSUBDIV_VERSION
}  // namespace OpenSubdiv

using namespace OpenSubdiv;

extern "C" {

// Patch types: 0 regular B-spline, 1 Loop box spline, 2 Gregory basis, 3 Gregory triangle.
// `out` holds 6 arrays of 20 weights (P, Ds, Dt, Dss, Dst, Dtt). Returns the number of
// points, or -1 for an unknown type.
int osd_patch_basis(int type, uint32_t field0, uint32_t field1, double u, double v,
                    double *out) {
    static const Far::PatchDescriptor::Type types[4] = {
        Far::PatchDescriptor::REGULAR, Far::PatchDescriptor::LOOP,
        Far::PatchDescriptor::GREGORY_BASIS, Far::PatchDescriptor::GREGORY_TRIANGLE};
    if (type < 0 || type > 3) return -1;
    Far::PatchParam param;
    param.field0 = field0;
    param.field1 = field1;
    for (int i = 0; i < 6 * 20; ++i) out[i] = 0.0;
    return Far::internal::EvaluatePatchBasis<double>(types[type], param, u, v, out, out + 20,
                                                     out + 40, out + 60, out + 80, out + 100);
}

}  // extern "C"
