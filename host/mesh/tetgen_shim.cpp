// The project's only C++: copies a tg_plc into TetGen's tetgenio, calls
// tetrahedralize and copies the mesh back into malloc'd arrays.  TetGen 1.5
// (Debian's libtet, built with TETLIBRARY) reports every failure by
// terminatetetgen() -> `throw int`; allocations throw std::bad_alloc.  All of
// it is caught here: no exception crosses into C.  tetgenio's destructor frees
// its arrays with delete[], so the input is filled with new[] and both
// tetgenio objects clean up on every path, the exceptional ones included.
#define TETLIBRARY
#define terminatetetgen tetgen_header_terminatetetgen /* the header's copy, unused */
#include <tetgen.h>
#undef terminatetetgen

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "tetgen_plc.h"

// TetGen 1.5.0 (Debian 12) frees the mesh's memory pools in
// terminatetetgen() and then throws; tetrahedralize()'s local tetgenmesh is
// destroyed while the exception unwinds and frees the same pools again: a
// double free that crashes on every error (self-intersecting input
// included).  libtet calls terminatetetgen through its PLT (a weak, default
// visibility symbol), so this definition in the executable takes its place:
// it only throws, and the unwinding destructor frees the mesh once.
void terminatetetgen(tetgenmesh *, int x) { throw x; }

namespace {

const char *tetgen_reason(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen hit an internal error";
    case 3: return "TetGen found a self-intersection in the input surface (sponge facets cross "
                   "each other or a box face)";
    case 4: return "TetGen found an input feature smaller than its tolerance (nearly coincident "
                   "vertices or a vertex almost on a facet)";
    case 5: return "TetGen found two input facets very close to each other";
    case 10: return "TetGen rejected the input (invalid PLC)";
    default: return "TetGen failed";
  }
}

void fill_input(const tg_plc *p, tetgenio &in) {
  in.firstnumber = 0;
  in.numberofpoints = p->npoints;
  in.pointlist = new REAL[3 * (size_t)p->npoints];
  std::memcpy(in.pointlist, p->xyz, 3 * (size_t)p->npoints * sizeof(double));
  if (p->size) {
    in.numberofpointmtrs = 1;
    in.pointmtrlist = new REAL[(size_t)p->npoints];
    std::memcpy(in.pointmtrlist, p->size, (size_t)p->npoints * sizeof(double));
  }
  in.numberoffacets = p->nfacets;
  in.facetlist = new tetgenio::facet[(size_t)p->nfacets];
  for (int f = 0; f < p->nfacets; f++) tetgenio::init(&in.facetlist[f]);
  in.facetmarkerlist = new int[(size_t)p->nfacets];
  for (int f = 0; f < p->nfacets; f++) {
    tetgenio::facet &fc = in.facetlist[f];
    in.facetmarkerlist[f] = p->facet_marker[f];
    int np = p->facet_poly[f + 1] - p->facet_poly[f];
    fc.polygonlist = new tetgenio::polygon[(size_t)np];
    fc.numberofpolygons = np;
    for (int q = 0; q < np; q++) tetgenio::init(&fc.polygonlist[q]);
    for (int q = 0; q < np; q++) {
      int pg = p->facet_poly[f] + q, nv = p->poly_vert[pg + 1] - p->poly_vert[pg];
      fc.polygonlist[q].vertexlist = new int[(size_t)nv];
      fc.polygonlist[q].numberofvertices = nv;
      std::memcpy(fc.polygonlist[q].vertexlist, p->verts + p->poly_vert[pg], (size_t)nv * sizeof(int));
    }
    int nh = p->facet_hole[f + 1] - p->facet_hole[f];
    if (nh > 0) {
      fc.holelist = new REAL[3 * (size_t)nh];
      fc.numberofholes = nh;
      std::memcpy(fc.holelist, p->fholes + 3 * (size_t)p->facet_hole[f], 3 * (size_t)nh * sizeof(double));
    }
  }
  if (p->nholes > 0) {
    in.numberofholes = p->nholes;
    in.holelist = new REAL[3 * (size_t)p->nholes];
    std::memcpy(in.holelist, p->holes, 3 * (size_t)p->nholes * sizeof(double));
  }
}

template <typename T> T *copy_out(const T *src, size_t n) {
  T *d = static_cast<T *>(std::malloc(n ? n * sizeof(T) : 1));
  if (d && n) std::memcpy(d, src, n * sizeof(T));
  return d;
}

}  // namespace

extern "C" {
int tg_fault_inject = 0;
}

extern "C" void tg_result_free(tg_result *r) {
  if (!r) return;
  std::free(r->xyz);
  std::free(r->tet);
  std::free(r->face);
  std::free(r->face_marker);
  std::memset(r, 0, sizeof *r);
}

extern "C" int tg_tetrahedralize(const tg_plc *plc, const char *switches, tg_result *out, char *msg,
                                 size_t msglen) {
  std::memset(out, 0, sizeof *out);
  if (msglen) msg[0] = '\0';
  int code = 0;
  try {
    tetgenio in, res;
    fill_input(plc, in);
    if (tg_fault_inject == TG_FAULT_BAD_ALLOC) throw std::bad_alloc();
    if (tg_fault_inject) throw int(tg_fault_inject);
    std::vector<char> sw(switches, switches + std::strlen(switches) + 1);
    tetrahedralize(sw.data(), &in, &res);
    if (res.numberofcorners != 4 || !res.tetrahedronlist || !res.trifacelist ||
        !res.trifacemarkerlist) {
      std::snprintf(msg, msglen, "TetGen returned no tetrahedra, boundary faces or face markers "
                                 "(switches '%s')", switches);
      return -1;
    }
    out->npoints = res.numberofpoints;
    out->ntets = res.numberoftetrahedra;
    out->nfaces = res.numberoftrifaces;
    out->xyz = copy_out(res.pointlist, 3 * (size_t)res.numberofpoints);
    out->tet = copy_out(res.tetrahedronlist, 4 * (size_t)res.numberoftetrahedra);
    out->face = copy_out(res.trifacelist, 3 * (size_t)res.numberoftrifaces);
    out->face_marker = copy_out(res.trifacemarkerlist, (size_t)res.numberoftrifaces);
    if (!out->xyz || !out->tet || !out->face || !out->face_marker) {
      tg_result_free(out);
      std::snprintf(msg, msglen, "out of host memory copying TetGen's mesh");
      return -2;
    }
    return 0;
  } catch (int e) {
    code = e;
    std::snprintf(msg, msglen, "%s (TetGen error code %d)", tetgen_reason(e), e);
  } catch (const std::bad_alloc &) {
    code = 1;
    std::snprintf(msg, msglen, "%s (std::bad_alloc)", tetgen_reason(1));
  } catch (...) {
    code = -1;
    std::snprintf(msg, msglen, "TetGen threw an unexpected exception");
  }
  tg_result_free(out);
  return code ? code : -1;
}
