/* OBJ reader: "v x y z [w]" and "f a b c ..." lines (a as v, v/t, v//n or
 * v/t/n; negative indices count back from the last vertex); every other
 * line (vn, vt, o, g, s, usemtl, mtllib, comments) is ignored.  Normals are
 * not taken from vn: OBJ indexes them per face corner, and the renderer
 * needs one per vertex, so they are computed (mesh_finish_). */
#include <stdlib.h>
#include <string.h>
#include "mesh_internal.h"

static const char *skip_ws(const char *p, const char *end) {
  while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
  return p;
}

sessile_status mesh_read_obj_(const char *what, const char *text, size_t bytes,
                              sessile_render_mesh *m) {
  const char *p = text, *end = text + bytes;
  size_t nv = 0, cap = 0, line = 0;
  float *pos = NULL;
  tri_list tl = {0};
  uint32_t poly[256];
  sessile_status s = SESSILE_OK;
  while (p < end && s == SESSILE_OK) {
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    line++;
    const char *q = skip_ws(p, eol);
    if (eol - q >= 2 && q[0] == 'v' && (q[1] == ' ' || q[1] == '\t')) {
      if (nv == cap) {
        cap = cap ? 2 * cap : 4096;
        float *np = realloc(pos, cap * 3 * sizeof(float));
        if (!np) { s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory", what); break; }
        pos = np;
      }
      char buf[256];
      size_t len = (size_t)(eol - q) < sizeof buf - 1 ? (size_t)(eol - q) : sizeof buf - 1;
      memcpy(buf, q, len);
      buf[len] = 0;
      char *c = buf + 1, *e2 = NULL;
      for (int k = 0; k < 3; k++) {
        double x = strtod(c, &e2);
        if (e2 == c) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "%s: line %zu: a vertex needs x y z", what, line);
          break;
        }
        pos[3 * nv + k] = (float)x;
        c = e2;
      }
      nv++;
      if (nv >= UINT32_MAX) s = sessile_error_set(SESSILE_ERR_USAGE, "%s: too many vertices", what);
    } else if (eol - q >= 2 && q[0] == 'f' && (q[1] == ' ' || q[1] == '\t')) {
      uint32_t n = 0;
      const char *c = q + 1;
      for (;;) {
        c = skip_ws(c, eol);
        if (c >= eol) break;
        char *e2 = NULL;
        long long idx = strtoll(c, &e2, 10);
        if (e2 == c || idx == 0) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "%s: line %zu: bad face index", what, line);
          break;
        }
        long long v = idx > 0 ? idx - 1 : (long long)nv + idx;
        if (v < 0 || v >= (long long)nv) {
          s = sessile_error_set(SESSILE_ERR_USAGE,
                                "%s: line %zu: face index %lld refers to no vertex (%zu so far)", what,
                                line, idx, nv);
          break;
        }
        if (n == 256) {
          s = sessile_error_set(SESSILE_ERR_USAGE, "%s: line %zu: a face of more than 256 vertices",
                                what, line);
          break;
        }
        poly[n++] = (uint32_t)v;
        c = e2;
        while (c < eol && *c != ' ' && *c != '\t' && *c != '\r') c++; /* /t/n */
      }
      if (s == SESSILE_OK && n >= 3 && tri_list_fan(&tl, poly, n) != 0)
        s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory", what);
    }
    p = eol + 1;
  }
  if (s == SESSILE_OK && tl.n > UINT32_MAX / 3)
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s: %zu triangles (too many)", what, tl.n);
  if (s != SESSILE_OK) {
    free(pos);
    free(tl.tri);
    return s;
  }
  m->pos = pos;
  m->nv = (uint32_t)nv;
  m->tri = tl.tri;
  m->nf = (uint32_t)tl.n;
  return SESSILE_OK;
}
