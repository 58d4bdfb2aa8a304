/* The validity check of an SDS tetrahedral complex (docs/sds_topology.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/surface.h"
#include "topo_internal.h"

static uint32_t uf_find(uint32_t *p, uint32_t a) {
  while (p[a] != a) a = p[a] = p[p[a]];
  return a;
}

/* Vertex-manifold: the boundary faces around each vertex, joined through
 * shared edges at that vertex, form one fan. */
static sessile_status check_fans(uint32_t nv, const uint32_t *tri, uint32_t nf) {
  uint32_t *off = calloc((size_t)nv + 2, sizeof *off), *lst = malloc((3 * (size_t)nf + 1) * sizeof *lst);
  uint32_t *p = malloc((3 * (size_t)nf + 1) * sizeof *p);
  sessile_status st = SESSILE_OK;
  if (!off || !lst || !p) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory checking the boundary");
    goto done;
  }
  for (size_t i = 0; i < 3 * (size_t)nf; i++) off[tri[i] + 2]++;
  for (uint32_t v = 0; v < nv; v++) off[v + 2] += off[v + 1];
  for (uint32_t f = 0; f < nf; f++)
    for (int k = 0; k < 3; k++) lst[off[tri[3 * f + k] + 1]++] = f;
  for (uint32_t v = 0; v < nv && st == SESSILE_OK; v++) {
    uint32_t b = off[v], e = off[v + 1];
    for (uint32_t i = b; i < e; i++) p[i] = i;
    for (uint32_t i = b; i < e; i++)
      for (uint32_t j = i + 1; j < e; j++) {
        const uint32_t *f = tri + 3 * (size_t)lst[i], *g = tri + 3 * (size_t)lst[j];
        int shared = 0; /* vertices other than v in common */
        for (int a = 0; a < 3; a++)
          for (int c = 0; c < 3; c++) shared += f[a] == g[c] && f[a] != v;
        if (shared) {
          uint32_t ri = uf_find(p, i), rj = uf_find(p, j);
          if (ri != rj) p[ri] = rj;
        }
      }
    uint32_t roots = 0;
    for (uint32_t i = b; i < e; i++) roots += uf_find(p, i) == i;
    if (roots > 1)
      st = sessile_error_set(SESSILE_ERR_INTERNAL,
                             "boundary vertex %u is not manifold: its %u boundary faces form %u fans", v, e - b, roots);
  }
done:
  free(off), free(lst), free(p);
  return st;
}

sessile_status sessile_sds_topo_check(uint32_t nv, const double *x, uint32_t nt, const uint32_t *tet, double min_volume,
                                      sessile_sds_topo_report *report) {
  sessile_sds_topo_report rep;
  memset(&rep, 0, sizeof rep);
  rep.min_volume = INFINITY;
  SESSILE_CHECK(nt > 0, SESSILE_ERR_INTERNAL, "the complex has no tetrahedra");
  uint8_t *used = calloc((size_t)nv + 1, 1);
  SESSILE_CHECK(used, SESSILE_ERR_NO_MEMORY, "out of host memory checking %u tets", nt);
  for (uint32_t t = 0; t < nt; t++) {
    const uint32_t *v = tet + 4 * (size_t)t;
    for (int q = 0; q < 4; q++) {
      if (v[q] >= nv) {
        free(used);
        return sessile_error_set(SESSILE_ERR_INTERNAL, "tet %u has vertex %u out of range (%u vertices)", t, v[q], nv);
      }
      used[v[q]] = 1;
      for (int r = 0; r < q; r++)
        if (v[r] == v[q]) {
          free(used);
          return sessile_error_set(SESSILE_ERR_INTERNAL, "tet %u repeats vertex %u", t, v[q]);
        }
    }
    double vol = topo_vol4(x, v);
    rep.volume += vol;
    if (vol < rep.min_volume) rep.min_volume = vol, rep.min_tet = t;
    if (!(vol > min_volume)) {
      free(used);
      return sessile_error_set(SESSILE_ERR_INTERNAL, "tet %u (%u %u %u %u) has volume %.17g <= %g", t, v[0], v[1], v[2],
                               v[3], vol, min_volume);
    }
  }
  for (uint32_t i = 0; i < nv; i++)
    if (!used[i]) {
      free(used);
      return sessile_error_set(SESSILE_ERR_INTERNAL, "vertex %u is in no tet", i);
    }
  free(used);
  topo_face *f = topo_all_faces(nt, tet);
  SESSILE_CHECK(f, SESSILE_ERR_NO_MEMORY, "out of host memory checking %u tets", nt);
  sessile_surface s;
  memset(&s, 0, sizeof s);
  sessile_status st = SESSILE_OK;
  uint32_t nb = 0;
  size_t n4 = 4 * (size_t)nt;
  for (size_t i = 0; i < n4;) {
    size_t j = i + 1;
    while (j < n4 && topo_face_same(f + i, f + j)) j++;
    if (j - i > 2) {
      st = sessile_error_set(SESSILE_ERR_INTERNAL, "face (%u %u %u) is in %zu tets", f[i].o[0], f[i].o[1], f[i].o[2],
                             j - i);
      goto done;
    }
    if (j - i == 2) {
      /* opposite orientations: the two tets lie on both sides of the face */
      const uint32_t *a = f[i].v, *b = f[i + 1].v;
      int k = b[0] == a[0] ? 0 : b[1] == a[0] ? 1 : 2;
      if (b[(k + 1) % 3] == a[1]) {
        st = sessile_error_set(SESSILE_ERR_INTERNAL,
                               "tets %u and %u lie on the same side of their shared face (%u %u %u)", f[i].t,
                               f[i + 1].t, a[0], a[1], a[2]);
        goto done;
      }
      if (f[i].t == f[i + 1].t) {
        st = sessile_error_set(SESSILE_ERR_INTERNAL, "tet %u has a repeated face", f[i].t);
        goto done;
      }
      rep.n_interior_faces++;
    } else {
      f[nb++] = f[i];
    }
    i = j;
  }
  /* Duplicate tets share all four faces with the same orientation: caught above. */
  rep.n_boundary_faces = nb;
  /* The boundary as a sessile_surface on its own vertices. */
  {
    uint32_t *map = malloc(((size_t)nv + 1) * sizeof *map);
    if (!map || sessile_surface_reserve(&s, nv, nb) != SESSILE_OK) {
      free(map);
      st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory checking the boundary");
      goto done;
    }
    for (uint32_t v = 0; v < nv; v++) map[v] = UINT32_MAX;
    for (uint32_t b = 0; b < nb; b++)
      for (int k = 0; k < 3; k++) {
        uint32_t v = f[b].v[k];
        if (map[v] == UINT32_MAX) {
          map[v] = s.nv;
          memcpy(s.pos + 3 * (size_t)s.nv++, x + 3 * (size_t)v, 3 * sizeof(double));
        }
        s.tri[3 * (size_t)b + k] = map[v];
      }
    s.nf = nb;
    free(map);
  }
  /* Euler characteristic computed here (the boundary may have several
   * components or handles); the check is for closed, oriented manifoldness. */
  {
    uint32_t ne = 3 * nb / 2;
    rep.boundary_euler = (int)s.nv - (int)ne + (int)nb;
    st = (3 * nb) % 2 ? sessile_error_set(SESSILE_ERR_INTERNAL, "the boundary has an odd number (%u) of faces", nb)
                      : sessile_surface_check(&s, rep.boundary_euler, 0.0);
    if (st != SESSILE_OK) {
      if (st != SESSILE_ERR_NO_MEMORY) /* no memory to check is no verdict on the complex */
        st = sessile_error_set(SESSILE_ERR_INTERNAL, "the boundary is not a closed oriented 2-manifold: %s",
                               sessile_error_message());
      goto done;
    }
    st = check_fans(s.nv, s.tri, s.nf);
  }
done:
  free(f);
  sessile_surface_free(&s);
  if (st == SESSILE_OK && report) *report = rep;
  return st;
}

sessile_status sessile_sds_topo_check_kept(const double *x0, uint32_t nt0, const uint32_t *tet0,
                                           const sessile_sds_topo_complex *cx, const uint32_t *tet_from) {
  SESSILE_CALL(sessile_sds_topo_check(cx->nv, cx->x, cx->nt, cx->tet, -INFINITY, NULL));
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *v = cx->tet + 4 * (size_t)t;
    double vol = topo_vol4(cx->x, v);
    if (vol > 0) continue;
    uint32_t o = tet_from[t];
    SESSILE_CHECK(o != SESSILE_SDS_TOPO_NEW_TET && o < nt0, SESSILE_ERR_INTERNAL,
                  "new tet %u (%u %u %u %u) has volume %.17g <= 0", t, v[0], v[1], v[2], v[3], vol);
    double vol0 = topo_vol4(x0, tet0 + 4 * (size_t)o);
    SESSILE_CHECK(!(vol0 > 0), SESSILE_ERR_INTERNAL,
                  "tet %u (%u %u %u %u) has volume %.17g <= 0, and %.17g before the transformation", t, v[0], v[1],
                  v[2], v[3], vol, vol0);
  }
  return SESSILE_OK;
}
