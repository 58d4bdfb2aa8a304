/* A seabed from a user's mesh (docs/reef.md, "Seabed"): a PLY or OBJ read
 * by io's readers, moved so that its bounding box starts at x = y = 0,
 * scaled to metres, and sampled to a heightfield: each sample takes the
 * highest triangle above it.  The reef then uses that heightfield as any
 * other (bilinear heights and normals, the exposure kernel, reef.glb). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "reef/reef_internal.h"
#include "reef/reef_json.h"
#include "sessile/io/io_read.h"

/* The highest z of the triangles over each sample (NAN: none). */
static void rasterise(const sessile_mesh_in *m, const double lo[2], double scale, sessile_reef_scene *s) {
  uint32_t nx = s->res[0], ny = s->res[1];
  double dx = s->extent[0] / (nx - 1), dy = s->extent[1] / (ny - 1);
  for (size_t k = 0; k < (size_t)nx * ny; k++) s->heights[k] = NAN;
  for (uint32_t f = 0; f < m->nf; f++) {
    double p[3][3];
    for (int c = 0; c < 3; c++) {
      const double *q = m->pos + 3 * (size_t)m->tri[3 * f + c];
      p[c][0] = (q[0] - lo[0]) * scale, p[c][1] = (q[1] - lo[1]) * scale, p[c][2] = q[2] * scale;
    }
    double det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (det == 0) continue; /* vertical: no height of its own */
    double x0 = fmin(p[0][0], fmin(p[1][0], p[2][0])), x1 = fmax(p[0][0], fmax(p[1][0], p[2][0]));
    double y0 = fmin(p[0][1], fmin(p[1][1], p[2][1])), y1 = fmax(p[0][1], fmax(p[1][1], p[2][1]));
    uint32_t i0 = (uint32_t)fmax(0, ceil(x0 / dx - 1e-9)), i1 = (uint32_t)fmin(nx - 1, floor(x1 / dx + 1e-9));
    uint32_t j0 = (uint32_t)fmax(0, ceil(y0 / dy - 1e-9)), j1 = (uint32_t)fmin(ny - 1, floor(y1 / dy + 1e-9));
    for (uint32_t j = j0; j <= j1 && j < ny; j++)
      for (uint32_t i = i0; i <= i1 && i < nx; i++) {
        double x = i * dx, y = j * dy;
        double b1 = ((x - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (y - p[0][1])) / det;
        double b2 = ((p[1][0] - p[0][0]) * (y - p[0][1]) - (x - p[0][0]) * (p[1][1] - p[0][1])) / det;
        double eps = -1e-9;
        if (b1 < eps || b2 < eps || 1 - b1 - b2 < eps) continue;
        double z = p[0][2] + b1 * (p[1][2] - p[0][2]) + b2 * (p[2][2] - p[0][2]);
        double *h = &s->heights[(size_t)j * nx + i];
        if (isnan(*h) || z > *h) *h = z;
      }
  }
}

sessile_status reef_seabed_mesh(const rj_obj *o, sessile_reef_scene *s) {
  char *path = NULL;
  double res[2] = {129, 129}, scale = 1;
  SESSILE_CALL(rj_known(o, (const char *const[]){"path", "resolution", "scale", NULL}));
  SESSILE_CALL(rj_nums(o, "resolution", 0, 2, 2, 4097, res));
  SESSILE_CALL(rj_num(o, "scale", 0, 1e-9, 1e9, &scale));
  if (res[0] != floor(res[0]) || res[1] != floor(res[1])) return rj_fail(o, "resolution", "must be integers");
  SESSILE_CALL(rj_str(o, "path", 1, &path));
  sessile_mesh_in m = {0};
  size_t l = strlen(path);
  sessile_mesh_read_opts opts = {.max_vertices = 50000000, .max_faces = 50000000};
  sessile_status st = l > 4 && !strcmp(path + l - 4, ".obj") ? sessile_read_obj(path, &opts, &m)
                                                              : sessile_read_ply(path, &opts, &m);
  free(path);
  if (st != SESSILE_OK) return sessile_error_pass(st, "%s: %s.path", o->where, o->path);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (uint32_t v = 0; v < m.nv; v++)
    for (int a = 0; a < 2; a++) lo[a] = fmin(lo[a], m.pos[3 * v + a]), hi[a] = fmax(hi[a], m.pos[3 * v + a]);
  s->res[0] = (uint32_t)res[0], s->res[1] = (uint32_t)res[1];
  s->extent[0] = (hi[0] - lo[0]) * scale, s->extent[1] = (hi[1] - lo[1]) * scale;
  if (!(m.nf > 0 && s->extent[0] > 1e-3 && s->extent[1] > 1e-3)) {
    sessile_mesh_in_free(&m);
    return rj_fail(o, "path", "is no seabed: it needs triangles spanning at least 1 mm in x and y");
  }
  s->heights = malloc((size_t)s->res[0] * s->res[1] * sizeof *s->heights);
  if (!s->heights) {
    sessile_mesh_in_free(&m);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the seabed");
  }
  rasterise(&m, lo, scale, s);
  sessile_mesh_in_free(&m);
  for (uint32_t j = 0; j < s->res[1]; j++)
    for (uint32_t i = 0; i < s->res[0]; i++)
      if (isnan(s->heights[(size_t)j * s->res[0] + i]))
        return rj_fail(o, "path", "is no heightfield: no triangle lies over (%g, %g) m of its bounding box",
                       i * s->extent[0] / (s->res[0] - 1), j * s->extent[1] / (s->res[1] - 1));
  return SESSILE_OK;
}
