/* Internal: the piecewise linear complex handed to TetGen and TetGen's
 * result, as plain C arrays, so that the only C++ (tetgen_shim.cpp) is a thin
 * copy into tetgenio, the call and a copy back. */
#ifndef SESSILE_TETGEN_PLC_H
#define SESSILE_TETGEN_PLC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tg_plc {
  int npoints;
  double *xyz;  /* 3 npoints */
  double *size; /* npoints target edge lengths (TetGen -m point metric), or NULL */
  int nfacets;
  int *facet_poly; /* nfacets + 1: polygons of facet f are facet_poly[f] .. facet_poly[f+1] */
  int *poly_vert;  /* npolys + 1: vertices of polygon p are verts[poly_vert[p] .. poly_vert[p+1]] */
  int *verts;
  int *facet_hole; /* nfacets + 1: facet hole points (3 doubles each) */
  double *fholes;
  int *facet_marker; /* nfacets */
  int nholes;
  double *holes; /* 3 nholes: volume hole seeds */
} tg_plc;

typedef struct tg_result {
  int npoints, ntets, nfaces;
  double *xyz;      /* 3 npoints */
  int *tet;         /* 4 ntets */
  int *face;        /* 3 nfaces: boundary (facet) subfaces */
  int *face_marker; /* nfaces */
} tg_result;

/* Runs tetrahedralize(switches, plc) in a child process (tetgen_shim.cpp
 * says why) and copies the output into malloc'd arrays.  Returns 0, or
 * TetGen's error code (1 out of memory, std::bad_alloc included; 2 internal
 * error; 3 self-intersection, 4 small feature, 5 close facets, 10 input
 * error: the input rejected), -1 for another exception or an output without
 * tetrahedra, -2 when copying the output ran out of memory, -3 when TetGen's
 * process died (a failed assert() in TetGen: its message is in msg); msg
 * receives a sentence saying which. Never throws. */
int tg_tetrahedralize(const tg_plc *plc, const char *switches, tg_result *out, char *msg,
                      size_t msglen);

/* Test-only fault injection (tests/mesh/test_tetgen.c,
 * tests/growth/test_grow_fallback.c): while non-zero, tg_tetrahedralize
 * builds TetGen's input and then fails as if TetGen had thrown this error
 * code, or std::bad_alloc for TG_FAULT_BAD_ALLOC, through the same catch
 * clauses as a real failure, or calls abort() for TG_FAULT_ABORT.  0 (the default) in every normal use; not
 * thread-safe, set it only from a test's main thread. */
enum { TG_FAULT_BAD_ALLOC = -100, TG_FAULT_ABORT = -101 /* abort() inside the call */ };
extern int tg_fault_inject;
void tg_result_free(tg_result *r);

#ifdef __cplusplus
}
#endif
#endif
