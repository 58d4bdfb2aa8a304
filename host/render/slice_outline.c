/* sessile render — the sponge's outline on a slice: marching squares on an
 * outline channel of the slice, or the exact cut of the surface mesh (a
 * sessile PLY) by the slice's plane. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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
/* sessile's PLY (host/io/mesh_write.c): binary little-endian, float vertex
 * properties (x y z first), faces as "list uchar uint|int".  Only that is
 * read here; the mesh renderer's general reader can replace this one. */
typedef struct ply_mesh {
  float *v; /* nv x nprop */
  uint32_t nv, nprop;
  uint32_t *tri; /* nt x 3 (polygons fanned) */
  size_t nt;
} ply_mesh;

static void ply_free(ply_mesh *m) {
  free(m->v);
  free(m->tri);
}

#define PLY_FAIL(...)                                        \
  do {                                                       \
    st = sessile_error_set(SESSILE_ERR_USAGE, __VA_ARGS__);  \
    goto done;                                               \
  } while (0)

static sessile_status ply_read(const char *path, ply_mesh *m) {
  memset(m, 0, sizeof *m);
  FILE *f = fopen(path, "rb");
  SESSILE_CHECK(f, SESSILE_ERR_USAGE, "cannot read the outline mesh '%s': %s", path, strerror(errno));
  sessile_status st = SESSILE_OK;
  char line[512];
  int in_vertex = 0, in_face = 0, face_ok = 0, xyz = 0;
  unsigned long long nv = 0, nf = 0;
  if (!fgets(line, sizeof line, f) || strcmp(line, "ply\n")) PLY_FAIL("'%s' is not a PLY file", path);
  for (;;) {
    if (!fgets(line, sizeof line, f)) PLY_FAIL("'%s': the PLY header has no end_header", path);
    char a[64], b[64], c[64], d[64];
    if (!strcmp(line, "end_header\n")) break;
    if (sscanf(line, "format %63s", a) == 1) {
      if (strcmp(a, "binary_little_endian")) PLY_FAIL("'%s': only binary little-endian PLY is read for outlines (got %s)", path, a);
    } else if (!strncmp(line, "element ", 8)) {
      unsigned long long cnt = 0;
      if (sscanf(line, "element %63s %llu", a, &cnt) != 2) PLY_FAIL("'%s': a bad PLY element line", path);
      in_vertex = !strcmp(a, "vertex"), in_face = !strcmp(a, "face");
      if (!in_vertex && !in_face) PLY_FAIL("'%s': a PLY element other than vertex and face", path);
      if (in_vertex) nv = cnt;
      else nf = cnt;
    } else if (in_vertex && sscanf(line, "property %63s %63s", a, b) == 2) {
      if (strcmp(a, "float")) PLY_FAIL("'%s': vertex property '%s' is not float", path, b);
      if (m->nprop < 3 && !strcmp(b, (const char *[]){"x", "y", "z"}[m->nprop])) xyz++;
      m->nprop++;
    } else if (in_face && sscanf(line, "property list %63s %63s %63s", a, c, d) == 3) {
      face_ok = !strcmp(a, "uchar") && (!strcmp(c, "uint") || !strcmp(c, "int"));
    }
  }
  if (xyz != 3 || !face_ok || nv == 0 || nv > (1u << 28) || nf > (1u << 28))
    PLY_FAIL("'%s': not a sessile PLY surface (float x y z, faces as list uchar uint; %llu vertices)", path, nv);
  m->nv = (uint32_t)nv;
  m->v = malloc((size_t)nv * m->nprop * sizeof(float));
  m->tri = malloc((size_t)nf * 3 * sizeof(uint32_t));
  if (!m->v || (nf && !m->tri)) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory reading '%s'", path);
    goto done;
  }
  if (fread(m->v, sizeof(float) * m->nprop, m->nv, f) != m->nv) PLY_FAIL("'%s': the PLY is truncated", path);
  size_t cap = nf;
  for (unsigned long long k = 0; k < nf; k++) {
    unsigned char cnt;
    uint32_t idx[256];
    if (fread(&cnt, 1, 1, f) != 1 || fread(idx, 4, cnt, f) != cnt) PLY_FAIL("'%s': the PLY is truncated", path);
    for (int q = 0; q < cnt; q++)
      if (idx[q] >= m->nv) PLY_FAIL("'%s': face %llu names vertex %u of %u", path, k, idx[q], m->nv);
    for (int q = 1; q + 1 < cnt; q++) {
      if (m->nt == cap) {
        uint32_t *t = realloc(m->tri, (cap = 2 * cap + 16) * 3 * sizeof *t);
        if (!t) {
          st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory reading '%s'", path);
          goto done;
        }
        m->tri = t;
      }
      uint32_t *t = m->tri + 3 * m->nt++;
      t[0] = idx[0], t[1] = idx[q], t[2] = idx[q + 1];
    }
  }
done:
  fclose(f);
  if (st != SESSILE_OK) ply_free(m);
  return st;
}

sessile_status slice_cut_ply(const slice_image *im, const char *ply_path, seg_list *out) {
  ply_mesh m;
  SESSILE_CALL(ply_read(ply_path, &m));
  sessile_status st = SESSILE_OK;
  for (size_t t = 0; st == SESSILE_OK && t < m.nt; t++) {
    double p[3][3], d[3];
    for (int k = 0; k < 3; k++) {
      const float *q = m.v + (size_t)m.tri[3 * t + k] * m.nprop;
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
  ply_free(&m);
  return st;
}
