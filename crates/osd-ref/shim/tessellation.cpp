// Bfr::Tessellation (OpenSubdiv 3.5) behind a C ABI: the (u, v) samples and facets of one
// face's tessellation pattern for given outer and inner rates. No mesh is involved.

#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/tessellation.h>

using namespace OpenSubdiv;

extern "C" {

// Tessellation pattern of a face of `face_size` corners with parameterization `param`
// (0: quad, 1: triangle, 2: quad sub-faces) and `num_rates` rates (Bfr's conventions: N
// outer rates, then up to two inner rates). `facet_size` is 3 or 4; `preserve_quads` keeps
// quads when it is 4. Writes `counts[0]` = number of coords, `counts[1]` = number of facets,
// `counts[2]` = number of boundary coords; fills `coords` (2 per coord) and `facets`
// (`facet_size` per facet) when their capacities (in coords and facets) suffice.
// Returns 0, or -1 when Bfr rejects the arguments, or -2 when a buffer is too small.
int osd_bfr_tessellation(int param, int face_size, int num_rates, const int *rates,
                         int facet_size, int preserve_quads, float *coords, int coord_cap,
                         int *facets, int facet_cap, int *counts) {
    // Bfr derives the parameterization from the scheme and face size: quads of Catmark and
    // Bilinear are QUAD, triangles of Loop are TRI, other Catmark faces QUAD_SUBFACES.
    Sdc::SchemeType scheme = param == 1 ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
    if ((param == 0 && face_size != 4) || (param == 1 && face_size != 3) ||
        (param == 2 && face_size == 4))
        return -1;
    Bfr::Parameterization p(scheme, face_size);
    if (!p.IsValid()) return -1;
    Bfr::Tessellation::Options options;
    options.SetFacetSize(facet_size);
    options.PreserveQuads(preserve_quads != 0);
    Bfr::Tessellation t(p, num_rates, rates, options);
    if (!t.IsValid()) return -1;
    counts[0] = t.GetNumCoords();
    counts[1] = t.GetNumFacets();
    counts[2] = t.GetNumBoundaryCoords();
    if (coords == nullptr || facets == nullptr) return 0;
    if (counts[0] > coord_cap || counts[1] > facet_cap) return -2;
    t.GetCoords(coords);
    t.GetFacets(facets);
    return 0;
}

}  // extern "C"
