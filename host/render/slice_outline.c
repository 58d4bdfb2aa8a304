/* sessile render — the sponge's outline on a slice: marching squares on an
 * outline channel of the slice, or the exact cut of the surface mesh (PLY or
 * OBJ, read by the mesh renderer's reader) by the slice's plane. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/render/render_mesh.h"
#include "slice_internal.h"

void seg_list_free(seg_list *s) {
  free(s->p);
  s->p = NULL;
  s->n = s->cap = 0;
}

static sessile_status seg_add(seg_list *s, double u0, double v0, double u1, double v1) {
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 256;
    double *p = realloc(s->p, cap * 4 * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of memory for %zu outline segments", cap);
    s->p = p, s->cap = cap;
  }
  double *q = s->p + 4 * s->n++;
  q[0] = u0, q[1] = v0, q[2] = u1, q[3] = v1;
  return SESSILE_OK;
}

sessile_status slice_contour(const slice_image *im, const float *f, double level, seg_list *out) {
  /* corners of cell (i, j) counter-clockwise: 0 (i, j), 1 (i+1, j), 2 (i+1, j+1), 3 (i, j+1);
   * edge k runs from corner k to corner k+1 */
  static const int ci[4] = {0, 1, 1, 0}, cj[4] = {0, 0, 1, 1};
  for (int j = 0; j + 1 < im->h; j++)
    for (int i = 0; i + 1 < im->w; i++) {
      double d[4];
      int nan = 0;
      for (int k = 0; k < 4; k++) {
        d[k] = f[(size_t)(j + cj[k]) * im->w + i + ci[k]] - level;
        nan |= isnan(d[k]);
      }
      if (nan) continue;
      double pu[4], pv[4];
      int cross[4], nc = 0;
      for (int k = 0; k < 4; k++) {
        int l = (k + 1) & 3;
        cross[k] = (d[k] >= 0) != (d[l] >= 0);
        if (!cross[k]) continue;
        nc++;
        double t = d[k] / (d[k] - d[l]);
        pu[k] = im->u0 + im->su * (i + ci[k] + t * (ci[l] - ci[k]));
        pv[k] = im->v0 + im->sv * (j + cj[k] + t * (cj[l] - cj[k]));
      }
      if (nc == 2) {
        int a = -1, b = -1;
        for (int k = 0; k < 4; k++)
          if (cross[k]) {
            if (a < 0) a = k;
            else b = k;
          }
        SESSILE_CALL(seg_add(out, pu[a], pv[a], pu[b], pv[b]));
      } else if (nc == 4) {
        /* a saddle: the cell's mean decides which corners connect */
        double mean = 0.25 * (d[0] + d[1] + d[2] + d[3]);
        if ((mean >= 0) == (d[0] >= 0)) { /* 0 and 2 connect: cut off corners 1 and 3 */
          SESSILE_CALL(seg_add(out, pu[0], pv[0], pu[1], pv[1]));
          SESSILE_CALL(seg_add(out, pu[2], pv[2], pu[3], pv[3]));
        } else { /* cut off corners 0 and 2 */
          SESSILE_CALL(seg_add(out, pu[3], pv[3], pu[0], pv[0]));
          SESSILE_CALL(seg_add(out, pu[1], pv[1], pu[2], pv[2]));
        }
      }
    }
  return SESSILE_OK;
}

/* --- the mesh cut ------------------------------------------------------------ */
/* The surface is read by the mesh renderer's reader (sessile/render/render_mesh.h:
 * ascii and binary PLY of either byte order, OBJ), which checks counts,
 * indices and coordinates; its normals are not needed here. */
sessile_status slice_cut_ply(const slice_image *im, const char *ply_path, seg_list *out) {
  sessile_render_mesh *m = NULL;
  sessile_status st = sessile_render_mesh_read(ply_path, &m);
  if (st != SESSILE_OK) {
    char msg[1100];
    snprintf(msg, sizeof msg, "%s", sessile_error_message());
    return sessile_error_set(st, "the outline mesh: %s", msg);
  }
  for (size_t t = 0; st == SESSILE_OK && t < m->nf; t++) {
    double p[3][3], d[3];
    for (int k = 0; k < 3; k++) {
      const float *q = m->pos + (size_t)m->tri[3 * t + k] * 3;
      d[k] = 0;
      for (int a = 0; a < 3; a++) {
        p[k][a] = q[a] - im->origin[a];
        d[k] += p[k][a] * im->normal[a];
      }
    }
    double pu[2], pv[2];
    int n = 0;
    for (int k = 0; k < 3; k++) {
      int l = (k + 1) % 3;
      if ((d[k] >= 0) == (d[l] >= 0)) continue;
      double s = d[k] / (d[k] - d[l]), x[3];
      for (int a = 0; a < 3; a++) x[a] = p[k][a] + s * (p[l][a] - p[k][a]);
      if (n < 2) {
        pu[n] = im->u0 + x[0] * im->axis_u[0] + x[1] * im->axis_u[1] + x[2] * im->axis_u[2];
        pv[n] = im->v0 + x[0] * im->axis_v[0] + x[1] * im->axis_v[1] + x[2] * im->axis_v[2];
      }
      n++;
    }
    if (n == 2) st = seg_add(out, pu[0], pv[0], pu[1], pv[1]);
  }
  sessile_render_mesh_destroy(m);
  return st;
}
