/* The movement transformations of §3.1.2: case 1 (vertex through face, the
 * 2-3 flip of Figure 4) and case 2 (edge through edge, the hull of U ∪ L
 * re-tetrahedralised by TetGen, Figure 5). */
#include <stdlib.h>
#include <string.h>
#include "topo_internal.h"

static int tet_has(const uint32_t *v, uint32_t a) { return v[0] == a || v[1] == a || v[2] == a || v[3] == a; }

/* Is vertex a on the boundary (in a face of exactly one tet)? */
static sessile_status vertex_on_boundary(const sessile_sds_topo_complex *cx, uint32_t a, int *on) {
  uint32_t *list = malloc(((size_t)cx->nt + 1) * sizeof *list), n = 0, *hull = NULL, nf = 0;
  SESSILE_CHECK(list, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t t = 0; t < cx->nt; t++)
    if (tet_has(cx->tet + 4 * (size_t)t, a)) list[n++] = t;
  sessile_status st = topo_cavity_hull(cx->tet, list, n, &hull, &nf);
  free(list);
  if (st != SESSILE_OK) return st;
  *on = 0;
  for (uint32_t i = 0; i < 3 * nf; i++) *on |= hull[i] == a; /* a face of a's star with a in it: boundary */
  free(hull);
  return SESSILE_OK;
}

sessile_status sessile_sds_topo_case1(sessile_sds_topo_complex *cx, uint32_t t, uint32_t v,
                                      sessile_sds_topo_transform *tr) {
  memset(tr, 0, sizeof *tr);
  SESSILE_CHECK(t < cx->nt, SESSILE_ERR_USAGE, "case 1: tet %u out of range (%u tets)", t, cx->nt);
  const uint32_t *tv = cx->tet + 4 * (size_t)t;
  int q = -1;
  for (int i = 0; i < 4; i++)
    if (tv[i] == v) q = i;
  SESSILE_CHECK(q >= 0, SESSILE_ERR_USAGE, "case 1: vertex %u is not in tet %u", v, t);
  uint32_t f[3] = {tv[topo_face_of[q][0]], tv[topo_face_of[q][1]], tv[topo_face_of[q][2]]}; /* outward of t */
  uint32_t t2 = UINT32_MAX;
  for (uint32_t u = 0; u < cx->nt; u++) {
    const uint32_t *w = cx->tet + 4 * (size_t)u;
    if (u != t && tet_has(w, f[0]) && tet_has(w, f[1]) && tet_has(w, f[2])) t2 = u;
  }
  uint8_t *rm = calloc((size_t)cx->nt + 1, 1);
  SESSILE_CHECK(rm, SESSILE_ERR_NO_MEMORY, "out of host memory");
  rm[t] = 1;
  uint32_t add[12], nadd = 0;
  sessile_status st;
  if (t2 == UINT32_MAX) {
    /* f on the boundary: drop t; refused when v is on the boundary too. */
    int von = 0;
    st = vertex_on_boundary(cx, v, &von);
    if (st == SESSILE_OK && von)
      st = sessile_error_set(SESSILE_ERR_UNSUPPORTED,
                             "case 1 refused: vertex %u and its opposite face (%u %u %u) in tet %u are both on the "
                             "surface (the transformation would leave an infinitely thin section)",
                             v, f[0], f[1], f[2], t);
  } else {
    const uint32_t *w = cx->tet + 4 * (size_t)t2;
    uint32_t vp = w[0] + w[1] + w[2] + w[3] - f[0] - f[1] - f[2];
    rm[t2] = 1;
    /* the new edge (v, v') must not exist already: it would be a second
     * edge between the same cells, the complex folded over itself */
    st = SESSILE_OK;
    for (uint32_t u = 0; u < cx->nt && st == SESSILE_OK; u++)
      if (tet_has(cx->tet + 4 * (size_t)u, v) && tet_has(cx->tet + 4 * (size_t)u, vp))
        st = sessile_error_set(SESSILE_ERR_UNSUPPORTED,
                               "case 1 refused: the new edge (%u %u) exists already (in tet %u)", v, vp, u);
    /* (f0, f1, f2, v') is positive (f faces away from t, toward v'); the
     * three new tets put v in place of one corner of f. */
    for (int i = 0; i < 3; i++) {
      uint32_t *n = add + 4 * nadd++;
      n[0] = f[0], n[1] = f[1], n[2] = f[2], n[3] = vp;
      n[i] = v;
    }
    for (uint32_t i = 0; i < nadd && st == SESSILE_OK; i++) {
      double vol = topo_vol4(cx->x, add + 4 * i);
      if (!(vol > 0))
        st =
            sessile_error_set(SESSILE_ERR_UNSUPPORTED,
                              "case 1 refused: new tet (%u %u %u %u) would have volume %g (vertex %u is not over "
                              "face (%u %u %u) seen from %u)",
                              add[4 * i], add[4 * i + 1], add[4 * i + 2], add[4 * i + 3], vol, v, f[0], f[1], f[2], vp);
    }
  }
  if (st == SESSILE_OK) st = topo_replace(cx, rm, add, nadd, &tr->tet_from, &tr->n_removed);
  if (st == SESSILE_OK) tr->n_added = nadd;
  free(rm);
  return st;
}

/* The edge (e0, e1) is on the boundary: the covering tet (e0, e1, p, q)
 * spanned with the two boundary faces through it, outside the body.  It
 * exists where the boundary is concave at the edge (a valley: what a
 * boundary edge moving into the body makes); at a ridge that tet would
 * overlap the body, refused. */
static sessile_status cover_edge(const sessile_sds_topo_complex *cx, const uint32_t *hull, uint32_t nf, uint32_t e0,
                                 uint32_t e1, uint32_t *cover) {
  /* boundary faces of the whole complex through the edge, oriented outward */
  uint32_t bf[2][3], nb = 0;
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *h = hull + 3 * (size_t)f;
    int has0 = h[0] == e0 || h[1] == e0 || h[2] == e0, has1 = h[0] == e1 || h[1] == e1 || h[2] == e1;
    if (!has0 || !has1 || !topo_face_on_boundary(cx->nt, cx->tet, h[0], h[1], h[2])) continue;
    if (nb < 2) memcpy(bf[nb], h, sizeof bf[0]);
    nb++;
  }
  SESSILE_CHECK(nb == 2, SESSILE_ERR_INTERNAL, "case 2: the boundary edge (%u %u) is in %u boundary faces", e0, e1, nb);
  /* rotate bf[0] to (e0', e1', p) keeping its orientation */
  uint32_t *a = bf[0];
  while (!(a[2] != e0 && a[2] != e1)) {
    uint32_t s = a[0];
    a[0] = a[1], a[1] = a[2], a[2] = s;
  }
  uint32_t p = a[2], qv = bf[1][0] + bf[1][1] + bf[1][2] - e0 - e1;
  SESSILE_CHECK(p != qv, SESSILE_ERR_UNSUPPORTED, "case 2 refused: the boundary folds onto itself at edge (%u %u)", e0,
                e1);
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *w = cx->tet + 4 * (size_t)t;
    SESSILE_CHECK(!(tet_has(w, p) && tet_has(w, qv)), SESSILE_ERR_UNSUPPORTED,
                  "case 2 refused: covering boundary edge (%u %u) would add edge (%u %u), which exists", e0, e1, p, qv);
  }
  cover[0] = a[0], cover[1] = a[1], cover[2] = p, cover[3] = qv;
  double vol = topo_vol4(cx->x, cover);
  SESSILE_CHECK(vol > 0, SESSILE_ERR_UNSUPPORTED,
                "case 2 refused: the surface is convex at boundary edge (%u %u), so no tet covers it from "
                "outside (covering tet volume %g)",
                e0, e1, vol);
  return SESSILE_OK;
}

sessile_status sessile_sds_topo_case2(sessile_sds_topo_complex *cx, uint32_t eu0, uint32_t eu1, uint32_t el0,
                                      uint32_t el1, sessile_sds_topo_transform *tr) {
  memset(tr, 0, sizeof *tr);
  uint32_t e[2][2] = {{eu0, eu1}, {el0, el1}};
  for (int i = 0; i < 2; i++)
    SESSILE_CHECK(e[i][0] < cx->nv && e[i][1] < cx->nv && e[i][0] != e[i][1], SESSILE_ERR_USAGE,
                  "case 2: bad edge (%u %u)", e[i][0], e[i][1]);
  uint8_t *rm = calloc((size_t)cx->nt + 1, 1);
  uint32_t *tmp = malloc((4 * ((size_t)cx->nt + 2)) * sizeof *tmp), *list = malloc(((size_t)cx->nt + 2) * sizeof *list);
  uint32_t *hull = NULL, nf = 0, *add = NULL, nadd = 0, n = 0, nu[2] = {0, 0};
  uint32_t *inner = NULL, ninner = 0;
  sessile_status st = SESSILE_OK;
  if (!rm || !tmp || !list) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    goto done;
  }
  memcpy(tmp, cx->tet, 4 * (size_t)cx->nt * sizeof *tmp);
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *w = cx->tet + 4 * (size_t)t;
    for (int i = 0; i < 2; i++)
      if (tet_has(w, e[i][0]) && tet_has(w, e[i][1])) {
        nu[i]++;
        if (!rm[t]) rm[t] = 1, list[n++] = t;
      }
  }
  if (!nu[0] || !nu[1]) {
    st =
        sessile_error_set(SESSILE_ERR_USAGE, "case 2: edge (%u %u) is in no tet", nu[0] ? el0 : eu0, nu[0] ? el1 : eu1);
    goto done;
  }
  /* A boundary edge in one tet only (the flat tet, two of its faces on the
   * boundary): removing that tet flips the boundary edge e_u -> e_l, as
   * case 1 on the boundary; nothing is added. */
  for (int i = 0; i < 2; i++) {
    if (nu[i] != 1) continue;
    uint32_t t1 = UINT32_MAX;
    for (uint32_t k = 0; k < n; k++) {
      const uint32_t *w = cx->tet + 4 * (size_t)list[k];
      if (tet_has(w, e[i][0]) && tet_has(w, e[i][1])) t1 = list[k];
    }
    const uint32_t *w = cx->tet + 4 * (size_t)t1;
    if (!tet_has(w, e[1 - i][0]) || !tet_has(w, e[1 - i][1])) continue;
    memset(rm, 0, (size_t)cx->nt);
    rm[t1] = 1;
    st = topo_replace(cx, rm, NULL, 0, &tr->tet_from, &tr->n_removed);
    goto done;
  }
  st = topo_cavity_hull(cx->tet, list, n, &hull, &nf);
  if (st != SESSILE_OK) goto done;
  /* An edge whose faces in the hull are boundary faces: cover it. */
  uint32_t ncov = 0;
  for (int i = 0; i < 2; i++) {
    int on = 0;
    for (uint32_t f = 0; f < nf && !on; f++) {
      const uint32_t *h = hull + 3 * (size_t)f;
      int h0 = h[0] == e[i][0] || h[1] == e[i][0] || h[2] == e[i][0];
      int h1 = h[0] == e[i][1] || h[1] == e[i][1] || h[2] == e[i][1];
      on = h0 && h1;
    }
    if (!on) continue;
    st = cover_edge(cx, hull, nf, e[i][0], e[i][1], tmp + 4 * ((size_t)cx->nt + ncov));
    if (st != SESSILE_OK) goto done;
    list[n++] = cx->nt + ncov++;
  }
  if (ncov) {
    free(hull), hull = NULL;
    st = topo_cavity_hull(tmp, list, n, &hull, &nf);
    if (st != SESSILE_OK) goto done;
  }
  /* cavity vertices off the hull (their whole star is in the cavity) go in as interior points */
  inner = malloc((4 * (size_t)n + 1) * sizeof *inner);
  if (!inner) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    goto done;
  }
  for (uint32_t i = 0; i < n; i++)
    for (int q = 0; q < 4; q++) {
      uint32_t a = tmp[4 * (size_t)list[i] + q];
      int seen = 0;
      for (uint32_t k = 0; k < 3 * nf && !seen; k++) seen = hull[k] == a;
      for (uint32_t k = 0; k < ninner && !seen; k++) seen = inner[k] == a;
      if (!seen) inner[ninner++] = a;
    }
  st = topo_fill_hull(cx->x, hull, nf, inner, ninner, &add, &nadd);
  if (st != SESSILE_OK) goto done;
  st = topo_replace(cx, rm, add, nadd, &tr->tet_from, &tr->n_removed);
  if (st == SESSILE_OK) tr->n_added = nadd;
done:
  free(rm), free(tmp), free(list), free(hull), free(add), free(inner);
  return st;
}

sessile_status sessile_sds_topo_apply_inversion(sessile_sds_topo_complex *cx, uint32_t t,
                                                const sessile_sds_topo_inversion *inv, sessile_sds_topo_transform *tr) {
  memset(tr, 0, sizeof *tr);
  SESSILE_CHECK(t < cx->nt, SESSILE_ERR_USAGE, "inversion: tet %u out of range (%u tets)", t, cx->nt);
  const uint32_t *v = cx->tet + 4 * (size_t)t;
  if (inv->kind == SESSILE_SDS_TOPO_VERTEX_FACE) {
    SESSILE_CHECK(inv->vertex >= 0 && inv->vertex < 4, SESSILE_ERR_USAGE, "inversion: bad local vertex %d",
                  inv->vertex);
    return sessile_sds_topo_case1(cx, t, v[inv->vertex], tr);
  }
  SESSILE_CHECK(inv->kind == SESSILE_SDS_TOPO_EDGE_EDGE, SESSILE_ERR_USAGE, "inversion: no case to apply");
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 2; k++)
      SESSILE_CHECK(inv->edge[i][k] >= 0 && inv->edge[i][k] < 4, SESSILE_ERR_USAGE, "inversion: bad local edge");
  return sessile_sds_topo_case2(cx, v[inv->edge[0][0]], v[inv->edge[0][1]], v[inv->edge[1][0]], v[inv->edge[1][1]], tr);
}
