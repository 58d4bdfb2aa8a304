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
 *                    solid = (z < 0.5); series timesteps 0 and 5
 *   parts.ply/.obj   a union of 3 parts: "small" (icosphere level 1, 12
 *                    vertices, 20 triangles, radius 0.5 about the origin),
 *                    "empty" (nothing) and "big" (level 2, 42 vertices, 80
 *                    triangles, radius 1 about (2.5, -1, 0.5)), unit normals;
 *                    PLY fields c = 1 + 2x + 3y + 4z and part = 0 or 2
 *   tets.vtu         a general tet mesh: the 4 x 3 x 2 cube box (h 0.25) with
 *                    its 60 nodes moved by (x + 0.1 y^2, y, z + 0.05 x); point
 *                    data c = 1 + 2x + 3y + 4z; cell data volume (Float64),
 *                    centroid (Float64 x 3), id = tet - 5 (Int32), kind =
 *                    tet % 6 (UInt8)
 *   plane.exr        an oblique plane: origin (-0.5, 0.25, 1), u along
 *                    (1, 1, 0), v along z, spacing (0.125, 0.25), 8 x 4
 *                    pixels, label "oblique", iteration 4; channels
 *                    c = 1 + 2x + 3y + 4z and d = x - y from a sampler
 *   signed.exr       the same plane, label "signed", one channel s = (i - 2)
 *                    (j + 1) at pixel (i, j) (-8..20: the colour view's
 *                    coolwarm), NaN at (7, 0) (the view's grey) */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include "sessile/io/io.h"
#include "sessile/mesh/tetmesh.h"

static double lin(const double p[3]) { return 1 + 2 * p[0] + 3 * p[1] + 4 * p[2]; }

static double plane_sample(void *user, int channel, const double p[3]) {
  (void)user;
  return channel == 0 ? lin(p) : p[0] - p[1];
}

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

  /* parts.ply / parts.obj */
  sessile_surface sa = {0}, sb = {0};
  double ca[3] = {0, 0, 0}, cb[3] = {2.5, -1, 0.5};
  CALL(sessile_surface_icosphere(1, 0.5, ca, &sa));
  CALL(sessile_surface_icosphere(2, 1.0, cb, &sb));
  double *na = malloc(3 * (size_t)sa.nv * sizeof *na), *nb = malloc(3 * (size_t)sb.nv * sizeof *nb);
  sessile_surface_normals(&sa, na);
  sessile_surface_normals(&sb, nb);
  double *fa[2] = {malloc(sa.nv * sizeof(double)), malloc(sa.nv * sizeof(double))};
  double *fb[2] = {malloc(sb.nv * sizeof(double)), malloc(sb.nv * sizeof(double))};
  for (uint32_t v = 0; v < sa.nv; v++) fa[0][v] = lin(sa.pos + 3 * v), fa[1][v] = 0;
  for (uint32_t v = 0; v < sb.nv; v++) fb[0][v] = lin(sb.pos + 3 * v), fb[1][v] = 2;
  const double *const fpa[2] = {fa[0], fa[1]}, *const fpb[2] = {fb[0], fb[1]};
  sessile_mesh_part parts[3] = {{"small", sa.pos, sa.nv, sa.tri, sa.nf, na, fpa},
                                {"empty", NULL, 0, NULL, 0, NULL, NULL},
                                {"big", sb.pos, sb.nv, sb.tri, sb.nf, nb, fpb}};
  const char *pnames[2] = {"c", "part"};
  snprintf(path, sizeof path, "%s/parts.ply", dir);
  CALL(sessile_write_ply_parts(path, 3, parts, 2, pnames));
  snprintf(path, sizeof path, "%s/parts.obj", dir);
  CALL(sessile_write_obj_parts(path, 3, parts));
  for (int q = 0; q < 2; q++) free(fa[q]), free(fb[q]);
  free(na);
  free(nb);
  sessile_surface_free(&sa);
  sessile_surface_free(&sb);

  /* tets.vtu */
  double o3[3] = {0, 0, 0};
  uint32_t cells3[3] = {4, 3, 2};
  CALL(sessile_box_make(o3, 0.25, cells3, 1, &box));
  sessile_tetmesh m = {0};
  CALL(sessile_tetmesh_from_box(&box, &m));
  for (uint32_t i = 0; i < m.nnodes; i++) {
    double *p = m.xyz + 3 * i, x = p[0], y = p[1];
    p[0] = x + 0.1 * y * y;
    p[2] += 0.05 * x;
  }
  double *pc = malloc(m.nnodes * sizeof *pc), *vol = malloc(m.ntets * sizeof *vol),
         *cen = malloc(3 * (size_t)m.ntets * sizeof *cen);
  int32_t *id = malloc(m.ntets * sizeof *id);
  uint8_t *kind = malloc(m.ntets);
  for (uint32_t i = 0; i < m.nnodes; i++) pc[i] = lin(m.xyz + 3 * i);
  for (uint32_t t = 0; t < m.ntets; t++) {
    vol[t] = sessile_tetmesh_tet_volume(&m, t);
    for (int a = 0; a < 3; a++) {
      cen[3 * t + a] = 0;
      for (int q = 0; q < 4; q++) cen[3 * t + a] += 0.25 * m.xyz[3 * m.tet[4 * t + q] + a];
    }
    id[t] = (int32_t)t - 5;
    kind[t] = (uint8_t)(t % 6);
  }
  sessile_vtu_field pf[1] = {{.name = "c", .f64 = pc, .components = 1}};
  sessile_vtu_field cf[4] = {{.name = "volume", .f64 = vol, .components = 1},
                             {.name = "centroid", .f64 = cen, .components = 3},
                             {.name = "id", .i32 = id, .components = 1},
                             {.name = "kind", .u8 = kind, .components = 1}};
  snprintf(path, sizeof path, "%s/tets.vtu", dir);
  CALL(sessile_write_vtu_tets(path, m.xyz, m.nnodes, m.tet, m.ntets, 1, pf, 4, cf));
  free(pc), free(vol), free(cen), free(id), free(kind);
  sessile_tetmesh_free(&m);

  /* plane.exr */
  sessile_plane pl = {{-0.5, 0.25, 1}, {1, 1, 0}, {0, 0, 1}, {0.125, 0.25}, 8, 4};
  const char *enames[2] = {"c", "d"};
  snprintf(path, sizeof path, "%s/plane.exr", dir);
  CALL(sessile_write_plane_exr(path, &pl, "oblique", 2, enames, plane_sample, NULL, 4));

  /* signed.exr */
  double sv[32];
  for (int j = 0; j < 4; j++)
    for (int i = 0; i < 8; i++) sv[i + 8 * j] = i == 7 && j == 0 ? NAN : (i - 2.0) * (j + 1);
  const char *sname[1] = {"s"};
  const double *const svals[1] = {sv};
  snprintf(path, sizeof path, "%s/signed.exr", dir);
  CALL(sessile_write_plane_exr_values(path, &pl, "signed", 1, sname, svals, 0));
  return 0;
}
