/* Writes sample files with known, analytic content for test_readers.sh, which
 * reads them with independent readers (VTK, meshio, exrheader, OpenImageIO).
 *
 *   io_samples DIR            small samples (formulas below; the script
 *                             recomputes the expected values itself)
 *   io_samples --default DIR  the default box (65 x 65 x 49 nodes): one .vtu
 *                             and one .exr, with sizes and times on stdout
 *
 * Samples:
 *   sponge.ply/.obj  icosphere level 3 (162 vertices, 320 triangles), radius
 *                    0.75 about (0.5, -0.25, 1.0), unit normals, PLY extra
 *                    property c = 1 + 2x + 3y + 4z
 *   slice_z.exr      box origin (-1, 0.5, 0), h 0.25, 9 x 7 x 5 nodes; plane
 *                    z = 0.6, iteration 12; channels c = 1 + 2x + 3y + 4z and
 *                    ux = x - y (linear, so the slice is exact)
 *   fields_0000.vtu, fields_0005.vtu, series.pvd
 *                    box origin (0, 0, 0), h 0.125, 17 x 13 x 9 nodes; point
 *                    data c = 1 + 2x + 3y + 4z (+ step), u = (y, -x, z),
 *                    solid = (z < 0.5); series timesteps 0 and 5 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include "sessile/io.h"

static double lin(const double p[3]) { return 1 + 2 * p[0] + 3 * p[1] + 4 * p[2]; }

#define CALL(e)                                                                   \
  do {                                                                            \
    if ((e) != SESSILE_OK) {                                                      \
      fprintf(stderr, "io_samples: %s\n", sessile_error_message());               \
      return 1;                                                                   \
    }                                                                             \
  } while (0)

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static long file_size(const char *p) {
  struct stat st;
  return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

/* The default box with smooth stand-ins for the run's fields (c, u, p, solid). */
static int default_box(const char *dir) {
  CALL(sessile_mkdirs(dir));
  sessile_box box;
  double origin[3] = {0, 0, 0};
  uint32_t cells[3] = {32, 32, 24};
  CALL(sessile_box_make(origin, 0.25, cells, 2, &box));
  size_t nn = sessile_box_nodes(&box);
  double *c = malloc(nn * sizeof *c), *u = malloc(3 * nn * sizeof *u), *pr = malloc(nn * sizeof *pr);
  uint8_t *solid = malloc(nn);
  for (size_t i = 0; i < nn; i++) {
    double p[3];
    sessile_box_node_pos(&box, (uint32_t)i, p);
    double r = sqrt((p[0] - 4) * (p[0] - 4) + (p[1] - 4) * (p[1] - 4) + p[2] * p[2]);
    solid[i] = r < 2.0;
    c[i] = solid[i] ? 0 : tanh(r - 2.0);
    u[3 * i] = solid[i] ? 0 : 0.05 * (1 - exp(-p[2])) * (1 - 4 / (r * r));
    u[3 * i + 1] = solid[i] ? 0 : 0.01 * sin(p[0]) * cos(p[1]);
    u[3 * i + 2] = solid[i] ? 0 : 0.01 * (p[2] - 3) / (r + 1);
    pr[i] = 0.1 * (8 - p[0]) + 0.01 * cos(p[1]);
  }
  sessile_point_data d[4] = {{"c", c, NULL, 1}, {"u", u, NULL, 3}, {"p", pr, NULL, 1}, {"solid", NULL, solid, 1}};
  char path[1024];
  snprintf(path, sizeof path, "%s/default.vtu", dir);
  double t0 = now();
  CALL(sessile_write_vtu(path, &box, 4, d));
  double t1 = now();
  printf("default box %u x %u x %u nodes, %llu tets\n", box.n[0], box.n[1], box.n[2],
         6ull * (box.n[0] - 1) * (box.n[1] - 1) * (box.n[2] - 1));
  printf("vtu (c, u, p, solid): %ld bytes, %.3f s\n", file_size(path), t1 - t0);
  snprintf(path, sizeof path, "%s/default_y.exr", dir);
  double *ux = malloc(nn * sizeof *ux), *uy = malloc(nn * sizeof *uy), *uz = malloc(nn * sizeof *uz),
         *um = malloc(nn * sizeof *um);
  for (size_t i = 0; i < nn; i++) {
    ux[i] = u[3 * i], uy[i] = u[3 * i + 1], uz[i] = u[3 * i + 2];
    um[i] = sqrt(ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i]);
  }
  sessile_slice_channel ch[6] = {{"c", c}, {"ux", ux}, {"uy", uy}, {"uz", uz}, {"umag", um}, {"p", pr}};
  t0 = now();
  CALL(sessile_write_slice_exr(path, &box, SESSILE_AXIS_Y, 4.0, 6, ch, 0));
  t1 = now();
  printf("exr y=4 (c ux uy uz umag p): %ld bytes, %.3f s\n", file_size(path), t1 - t0);
  free(c), free(u), free(pr), free(solid), free(ux), free(uy), free(uz), free(um);
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 3 && !strcmp(argv[1], "--default")) return default_box(argv[2]);
  if (argc != 2) {
    fprintf(stderr, "usage: io_samples [--default] DIR\n");
    return 2;
  }
  const char *dir = argv[1];
  char path[1024];
  CALL(sessile_mkdirs(dir));

  sessile_surface s = {0};
  double center[3] = {0.5, -0.25, 1.0};
  CALL(sessile_surface_icosphere(3, 0.75, center, &s));
  double *nrm = malloc(3 * (size_t)s.nv * sizeof *nrm), *c = malloc(s.nv * sizeof *c);
  sessile_surface_normals(&s, nrm);
  for (uint32_t v = 0; v < s.nv; v++) c[v] = lin(s.pos + 3 * v);
  const char *names[1] = {"c"};
  const double *extra[1] = {c};
  snprintf(path, sizeof path, "%s/sponge.ply", dir);
  CALL(sessile_write_ply(path, &s, nrm, 1, names, extra));
  snprintf(path, sizeof path, "%s/sponge.obj", dir);
  CALL(sessile_write_obj(path, &s, nrm));
  free(c);
  free(nrm);
  sessile_surface_free(&s);

  sessile_box box;
  double o1[3] = {-1, 0.5, 0};
  uint32_t cells1[3] = {8, 6, 4};
  CALL(sessile_box_make(o1, 0.25, cells1, 1, &box));
  size_t nn = sessile_box_nodes(&box);
  double *fc = malloc(nn * sizeof *fc), *fu = malloc(nn * sizeof *fu);
  for (size_t i = 0; i < nn; i++) {
    double p[3];
    sessile_box_node_pos(&box, (uint32_t)i, p);
    fc[i] = lin(p);
    fu[i] = p[0] - p[1];
  }
  sessile_slice_channel ch[2] = {{"c", fc}, {"ux", fu}};
  snprintf(path, sizeof path, "%s/slice_z.exr", dir);
  CALL(sessile_write_slice_exr(path, &box, SESSILE_AXIS_Z, 0.6, 2, ch, 12));
  free(fc);
  free(fu);

  double o2[3] = {0, 0, 0};
  uint32_t cells2[3] = {16, 12, 8};
  CALL(sessile_box_make(o2, 0.125, cells2, 1, &box));
  nn = sessile_box_nodes(&box);
  fc = malloc(nn * sizeof *fc);
  double *u = malloc(3 * nn * sizeof *u);
  uint8_t *solid = malloc(nn);
  int steps[2] = {0, 5};
  const char *files[2] = {"fields_0000.vtu", "fields_0005.vtu"};
  for (int q = 0; q < 2; q++) {
    for (size_t i = 0; i < nn; i++) {
      double p[3];
      sessile_box_node_pos(&box, (uint32_t)i, p);
      fc[i] = lin(p) + steps[q];
      u[3 * i] = p[1], u[3 * i + 1] = -p[0], u[3 * i + 2] = p[2];
      solid[i] = p[2] < 0.5;
    }
    sessile_point_data d[3] = {{"c", fc, NULL, 1}, {"u", u, NULL, 3}, {"solid", NULL, solid, 1}};
    snprintf(path, sizeof path, "%s/%s", dir, files[q]);
    CALL(sessile_write_vtu(path, &box, 3, d));
  }
  snprintf(path, sizeof path, "%s/series.pvd", dir);
  CALL(sessile_write_pvd(path, 2, steps, files));
  free(fc);
  free(u);
  free(solid);
  return 0;
}
