/* Internal to host/sds/topo*.c: face keys, cavities (sets of tets and their
 * outward hull), TetGen filling of a hull and the rebuild of the tet array. */
#ifndef SESSILE_SDS_TOPO_INTERNAL_H
#define SESSILE_SDS_TOPO_INTERNAL_H

#include <stdint.h>
#include "sessile/sds/sds_topo.h"

/* Outward faces of a positively oriented tet (v0, v1, v2, v3): face q is
 * opposite vertex q, counter-clockwise seen from outside. */
extern const int topo_face_of[4][3];

/* A triangle: o = its nodes sorted (the key), v = the oriented nodes, t = the
 * tet it came from. */
typedef struct topo_face {
  uint32_t o[3], v[3], t;
} topo_face;
void topo_face_make(topo_face *f, uint32_t a, uint32_t b, uint32_t c, uint32_t t);
int topo_face_cmp(const void *x, const void *y);
int topo_face_same(const topo_face *a, const topo_face *b);

/* All 4 nt faces sorted by key (caller frees).  NULL when out of memory. */
topo_face *topo_all_faces(uint32_t nt, const uint32_t *tet);

/* The faces of the tets list[0..n) that occur once among them, oriented
 * outward of the set, as 3 nf indices (malloc'd into *faces). */
sessile_status topo_cavity_hull(const uint32_t *tet, const uint32_t *list, uint32_t n, uint32_t **faces, uint32_t *nf);

/* Is face (a, b, c) (any order) a face of exactly one tet of the complex? */
int topo_face_on_boundary(uint32_t nt, const uint32_t *tet, uint32_t a, uint32_t b, uint32_t c);

/* Tetrahedralises the closed polyhedron bounded by faces (3 nf global
 * indices, oriented outward) plus the interior points pts (global indices)
 * with TetGen -pY: no Steiner point anywhere (refused with
 * SESSILE_ERR_NUMERIC), the hull's faces kept exactly (checked).  *out gets 4
 * nout global indices, positively oriented. */
sessile_status topo_fill_hull(const double *x, const uint32_t *faces, uint32_t nf, const uint32_t *pts, uint32_t npts,
                              uint32_t **out, uint32_t *nout);

/* Replaces the tets flagged in remove (nt flags) by add (4 nadd): kept tets in
 * order, then the new ones; *tet_from as in sessile_sds_topo_division. */
sessile_status topo_replace(sessile_sds_topo_complex *cx, const uint8_t *remove, const uint32_t *add, uint32_t nadd,
                            uint32_t **tet_from, uint32_t *n_removed);

/* The tangential division of surface cell c along dir (unit), its star's
 * hull and removal flags given (sessile_sds_topo_divide's first steps, x
 * already with room for b): both daughters on the boundary, the enclosed
 * volume kept.  SESSILE_ERR_UNSUPPORTED or _NUMERIC, with x[c] restored and
 * the complex untouched, when the fan cannot be split cleanly. */
sessile_status topo_divide_tangential(sessile_sds_topo_complex *cx, uint32_t c, const double *dir, double eps_max,
                                      const uint32_t *hull, uint32_t nf, const uint8_t *rm,
                                      sessile_sds_topo_division *div);

static inline double topo_vol4(const double *x, const uint32_t *t) {
  return sessile_sds_topo_volume(x + 3 * t[0], x + 3 * t[1], x + 3 * t[2], x + 3 * t[3]);
}
#endif
