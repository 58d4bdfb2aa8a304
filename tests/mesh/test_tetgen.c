/* The conforming water domain (TetGen): for the box minus an icosphere, a
 * dome flattened onto the substratum and one flattened onto the inlet,
 * checks every tet is positively oriented, the volumes sum to the box volume
 * minus the sponge's (divergence theorem on the surface), the tagged boundary
 * faces cover each box face (minus the footprint) and the sponge, face
 * outward (divergence theorem on the boundary), the mesh is graded; bad
 * input (a self-intersecting surface, a sponge outside the box) fails with a
 * message.  `--measure` times the default box minus the initial dome and a
 * 20 k-triangle sponge (docs/conforming.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/locate.h"
#include "sessile/mesh/tetgen.h"
#include "mesh/tetgen_plc.h"
#include "testutil.h"

static double tri_area(const double *a, const double *b, const double *c, double n[3]) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = (u[1] * v[2] - u[2] * v[1]) / 2, n[1] = (u[2] * v[0] - u[0] * v[2]) / 2, n[2] = (u[0] * v[1] - u[1] * v[0]) / 2;
  return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Flattens the part of s beyond the plane x[axis] = at (on the side sign)
 * onto the plane, as the growth loop does on the substratum. */
static void flatten(sessile_surface *s, int axis, double at, int sign) {
  for (uint32_t v = 0; v < s->nv; v++)
    if (sign * (s->pos[3 * v + axis] - at) < 0) s->pos[3 * v + axis] = at;
}

/* Area of the sponge triangles lying in the plane x[axis] = at. */
static double footprint(const sessile_surface *s, int axis, double at) {
  double area = 0, n[3];
  for (uint32_t t = 0; t < s->nf; t++) {
    const double *p[3];
    int on = 1;
    for (int q = 0; q < 3; q++) p[q] = s->pos + 3 * s->tri[3 * t + q], on &= p[q][axis] == at;
    if (on) area += tri_area(p[0], p[1], p[2], n);
  }
  return area;
}

/* Checks m against the box minus sponge s whose footprint (area fp) lies on
 * the box face with tag fp_tag; returns nothing, records checks. */
static void check_mesh(const char *name, const sessile_box *box, const sessile_surface *s,
                       const sessile_tetmesh *m, uint32_t fp_tag, double fp) {
  char what[160];
  double mx[3];
  sessile_box_max(box, mx);
  double l[3] = {mx[0] - box->origin[0], mx[1] - box->origin[1], mx[2] - box->origin[2]};
  double vbox = l[0] * l[1] * l[2];
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  double vwater = vbox - st.volume;
  double vmin = INFINITY, vsum = 0;
  for (uint32_t t = 0; t < m->ntets; t++) {
    double v = sessile_tetmesh_tet_volume(m, t);
    vsum += v;
    if (v < vmin) vmin = v;
  }
  printf("%s: %u nodes, %u tets, %u boundary faces; smallest tet volume %.3g cm^3\n", name, m->nnodes,
         m->ntets, m->nbfaces, vmin);
  snprintf(what, sizeof what, "%s: every tet positively oriented (volume > 0)", name);
  t_true(what, vmin > 0);
  snprintf(what, sizeof what, "%s: tet volumes sum to box minus sponge volume (relative)", name);
  t_check(what, fabs(vsum - vwater) / vwater, 1e-9);
  double area[6] = {0}, nsum[3] = {0}, flux = 0, n[3];
  int bad_tag = 0;
  for (uint32_t f = 0; f < m->nbfaces; f++) {
    const double *a = m->xyz + 3 * m->bface[3 * f], *b = m->xyz + 3 * m->bface[3 * f + 1],
                 *c = m->xyz + 3 * m->bface[3 * f + 2];
    double ar = tri_area(a, b, c, n);
    for (int k = 0; k < 3; k++) nsum[k] += n[k];
    flux += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 3;
    uint32_t tag = m->bface_tag[f];
    int slot = tag == SESSILE_TAG_INLET ? 0 : tag == SESSILE_TAG_OUTLET ? 1 : tag == SESSILE_TAG_SUBSTRATUM ? 2
             : tag == SESSILE_TAG_SIDE ? 3 : tag == SESSILE_TAG_TOP ? 4 : tag == SESSILE_TAG_SPONGE ? 5 : -1;
    if (slot < 0) bad_tag = 1;
    else area[slot] += ar;
    for (int q = 0; q < 3; q++)
      if (!(m->node_tags[m->bface[3 * f + q]] & tag)) bad_tag = 1;
  }
  snprintf(what, sizeof what, "%s: every boundary face has one known tag, its nodes carry it", name);
  t_true(what, !bad_tag);
  double scale = l[0] * l[1];
  snprintf(what, sizeof what, "%s: boundary sum of n dA is zero (relative to the box face)", name);
  t_check(what, (fabs(nsum[0]) + fabs(nsum[1]) + fabs(nsum[2])) / scale, 1e-12);
  snprintf(what, sizeof what, "%s: boundary divergence theorem gives the water volume", name);
  t_check(what, fabs(flux - vwater) / vwater, 1e-9);
  double expect[6] = {l[1] * l[2], l[1] * l[2], l[0] * l[1], 2 * l[0] * l[2], l[0] * l[1], st.area - fp};
  const char *names[6] = {"inlet", "outlet", "substratum", "side walls", "top", "sponge"};
  if (fp_tag == SESSILE_TAG_SUBSTRATUM) expect[2] -= fp;
  if (fp_tag == SESSILE_TAG_INLET) expect[0] -= fp;
  for (int k = 0; k < 6; k++) {
    snprintf(what, sizeof what, "%s: %s area (relative)", name, names[k]);
    t_check(what, fabs(area[k] - expect[k]) / expect[k], 1e-9);
  }
}

/* Mean edge length of the tets whose centroid is nearer than d0 to the
 * sphere |x - c| = r, and of those farther than d1. */
static void grading(const sessile_tetmesh *m, const double c[3], double r, double d0, double d1,
                    double *near, double *far) {
  double sn = 0, sf = 0;
  long nn = 0, nf = 0;
  for (uint32_t t = 0; t < m->ntets; t++) {
    double g[3] = {0, 0, 0}, e = 0;
    const uint32_t *v = m->tet + 4 * t;
    for (int q = 0; q < 4; q++)
      for (int k = 0; k < 3; k++) g[k] += m->xyz[3 * v[q] + k] / 4;
    for (int a = 0; a < 4; a++)
      for (int b = a + 1; b < 4; b++) {
        const double *p = m->xyz + 3 * v[a], *q = m->xyz + 3 * v[b];
        e += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2])) / 6;
      }
    double d = fabs(sqrt((g[0] - c[0]) * (g[0] - c[0]) + (g[1] - c[1]) * (g[1] - c[1]) + (g[2] - c[2]) * (g[2] - c[2])) - r);
    if (d < d0) sn += e, nn++;
    if (d > d1) sf += e, nf++;
  }
  *near = nn ? sn / nn : NAN;
  *far = nf ? sf / nf : NAN;
}

static void measure(int level, double radius, const char *what) {
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {32, 32, 24};
  sessile_box box;
  t_ok("default box", sessile_box_make(origin, 1.2, cells, 2, &box));
  double c[3] = {19.2, 19.2, 0};
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(level, radius, c, &s));
  flatten(&s, 2, 0, 1);
  sessile_tetgen_options o;
  sessile_tetgen_options_default(&o);
  for (int pass = 0; pass < 2; pass++) {
    if (pass) o.radius_edge = 2.0;
    sessile_tetmesh m = {0};
    double t0 = sessile_wall_seconds();
    sessile_status st = sessile_tetgen_conforming(&box, &s, &o, &m);
    double t1 = sessile_wall_seconds();
    t_ok(what, st);
    printf("MEASURE %s (%u vertices, %u triangles), -q%.3g: %.2f s, %u nodes, %u tets, %u boundary faces\n",
           what, s.nv, s.nf, o.radius_edge, t1 - t0, m.nnodes, m.ntets, m.nbfaces);
    if (!pass) {
      check_mesh(what, &box, &s, &m, SESSILE_TAG_SUBSTRATUM, footprint(&s, 2, 0));
      /* the locator on it: build time and host queries per second */
      sessile_locator *l = NULL;
      t0 = sessile_wall_seconds();
      t_ok("locator", sessile_locator_build(&m, 0, &l));
      t1 = sessile_wall_seconds();
      sessile_locator_grid g;
      sessile_locator_grid_of(l, &g);
      uint64_t r = 12345;
      int found = 0, nq = 200000;
      double t2 = sessile_wall_seconds();
      for (int i = 0; i < nq; i++) {
        double p[3], w[4];
        for (int k = 0; k < 3; k++) {
          r ^= r << 13, r ^= r >> 7, r ^= r << 17;
          p[k] = (double)(r >> 11) / 9007199254740992.0 * 38.4 * (k == 2 ? 0.75 : 1.0);
        }
        found += sessile_locator_find(l, p, w) != SESSILE_LOCATE_OUTSIDE;
      }
      double t3 = sessile_wall_seconds();
      printf("MEASURE locator: build %.3f s, %u bins, %.1f tets per bin (max %u); %d host queries %.3f s "
             "(%.2f M/s), %d found\n", t1 - t0, g.nbins, g.mean_per_bin, g.max_per_bin, nq, t3 - t2,
             nq / (t3 - t2) / 1e6, found);
      sessile_locator_destroy(l);
    }
    sessile_tetmesh_free(&m);
  }
  sessile_surface_free(&s);
}

int main(int argc, char **argv) {
  const double origin[3] = {-1.0, 0.5, 0.0};
  const uint32_t cells[3] = {10, 10, 8};
  sessile_box box;
  t_ok("box", sessile_box_make(origin, 1.2, cells, 1, &box)); /* 12 x 12 x 9.6 cm */
  double mx[3];
  sessile_box_max(&box, mx);
  double mid[3] = {(origin[0] + mx[0]) / 2, (origin[1] + mx[1]) / 2, (origin[2] + mx[2]) / 2};
  sessile_tetgen_options o;
  sessile_tetgen_options_default(&o);

  /* 1. a free-floating icosphere (a volume hole) */
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(3, 2.5, mid, &s));
  sessile_tetmesh m = {0};
  t_ok("conforming mesh of the box minus an icosphere", sessile_tetgen_conforming(&box, &s, &o, &m));
  check_mesh("sphere", &box, &s, &m, 0, 0);
  double near, far;
  grading(&m, mid, 2.5, 0.3, 3.0, &near, &far);
  printf("grading: mean tet edge %.3f cm within 0.3 cm of the sponge, %.3f cm farther than 3 cm\n", near, far);
  t_true("grading: tets near the sponge are smaller than far away", near < far);
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);

  /* 2. a dome flattened onto the substratum (the growth loop's start) */
  double base[3] = {mid[0], mid[1], origin[2]};
  t_ok("icosphere", sessile_surface_icosphere(3, 3.0, base, &s));
  flatten(&s, 2, origin[2], 1);
  double fp = footprint(&s, 2, origin[2]);
  printf("dome footprint %.4f cm^2 (disc %.4f)\n", fp, 3.14159265358979 * 9);
  t_ok("conforming mesh of the box minus a dome on the substratum", sessile_tetgen_conforming(&box, &s, &o, &m));
  check_mesh("dome", &box, &s, &m, SESSILE_TAG_SUBSTRATUM, fp);
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);

  /* 3. a dome flattened onto the inlet face (x = xmin) */
  double side[3] = {origin[0], mid[1], mid[2]};
  t_ok("icosphere", sessile_surface_icosphere(3, 2.0, side, &s));
  flatten(&s, 0, origin[0], 1);
  fp = footprint(&s, 0, origin[0]);
  t_ok("conforming mesh of the box minus a dome on the inlet", sessile_tetgen_conforming(&box, &s, &o, &m));
  check_mesh("inlet dome", &box, &s, &m, SESSILE_TAG_INLET, fp);
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);

  /* 4. self-intersecting: two overlapping icospheres in one surface */
  sessile_surface a = {0}, b = {0};
  double c1[3] = {mid[0] - 1, mid[1], mid[2]}, c2[3] = {mid[0] + 1, mid[1], mid[2]};
  t_ok("icosphere a", sessile_surface_icosphere(2, 2.0, c1, &a));
  t_ok("icosphere b", sessile_surface_icosphere(2, 2.0, c2, &b));
  t_ok("reserve", sessile_surface_reserve(&a, a.nv + b.nv, a.nf + b.nf));
  memcpy(a.pos + 3 * a.nv, b.pos, 3 * b.nv * sizeof *b.pos);
  for (uint32_t i = 0; i < 3 * b.nf; i++) a.tri[3 * a.nf + i] = b.tri[i] + a.nv;
  a.nv += b.nv, a.nf += b.nf;
  sessile_error_clear();
  sessile_status st = sessile_tetgen_conforming(&box, &a, &o, &m);
  printf("self-intersecting surface: %s: %s\n", sessile_status_name(st), sessile_error_message());
  t_true("self-intersecting surface: SESSILE_ERR_NUMERIC with a message",
         st == SESSILE_ERR_NUMERIC && strlen(sessile_error_message()) > 0);
  t_true("self-intersecting surface: output left empty", m.nnodes == 0 && m.xyz == NULL && m.tet == NULL);
  /* 5. a sponge poking out of the box */
  for (uint32_t v = 0; v < b.nv; v++) b.pos[3 * v + 2] += mx[2];
  st = sessile_tetgen_conforming(&box, &b, &o, &m);
  printf("sponge outside the box: %s: %s\n", sessile_status_name(st), sessile_error_message());
  t_true("sponge outside the box: SESSILE_ERR_USAGE", st == SESSILE_ERR_USAGE && m.xyz == NULL);
  sessile_surface_free(&a);
  sessile_surface_free(&b);

  /* 6. TetGen's failures told apart (tg_fault_inject, mesh/tetgen_plc.h:
   * the input is built, then TetGen "throws" through the real catch
   * clauses): only verdicts on the input geometry are SESSILE_ERR_NUMERIC,
   * which callers may answer with a fallback; out of memory and internal
   * errors are not, and must stop them. */
  static const struct { int fault; sessile_status want; const char *name; } faults[] = {
      {TG_FAULT_BAD_ALLOC, SESSILE_ERR_NO_MEMORY, "std::bad_alloc"},
      {1, SESSILE_ERR_NO_MEMORY, "TetGen error 1 (out of memory)"},
      {2, SESSILE_ERR_INTERNAL, "TetGen error 2 (internal error)"},
      {3, SESSILE_ERR_NUMERIC, "TetGen error 3 (self-intersection)"},
      {4, SESSILE_ERR_NUMERIC, "TetGen error 4 (small feature)"},
      {10, SESSILE_ERR_NUMERIC, "TetGen error 10 (invalid input)"},
      /* TetGen's process dies (Debian's libtet keeps its assert()s): a
       * verdict on the input, and this process goes on */
      {TG_FAULT_ABORT, SESSILE_ERR_NUMERIC, "abort() in TetGen (a failed assertion)"},
      {7, SESSILE_ERR_INTERNAL, "an unknown TetGen error code"}};
  t_ok("icosphere", sessile_surface_icosphere(3, 2.5, mid, &s));
  for (size_t k = 0; k < sizeof faults / sizeof faults[0]; k++) {
    tg_fault_inject = faults[k].fault;
    sessile_error_clear();
    st = sessile_tetgen_conforming(&box, &s, &o, &m);
    tg_fault_inject = 0;
    printf("injected %s: %s: %s\n", faults[k].name, sessile_status_name(st), sessile_error_message());
    char what[160];
    snprintf(what, sizeof what, "injected %s: %s, message, output empty", faults[k].name,
             sessile_status_name(faults[k].want));
    t_true(what, st == faults[k].want && strlen(sessile_error_message()) > 0 && m.xyz == NULL && m.tet == NULL);
  }
  tg_fault_inject = TG_FAULT_ABORT;
  st = sessile_tetgen_conforming(&box, &s, &o, &m);
  tg_fault_inject = 0;
  t_true("injected abort(): the message names the signal", strstr(sessile_error_message(), "signal 6") != NULL);
  t_ok("after the injected faults, the same surface meshes", sessile_tetgen_conforming(&box, &s, &o, &m));
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);

  if (argc > 1 && !strcmp(argv[1], "--measure")) {
    measure(4, 6.0, "default box minus the initial dome");
    measure(6, 12.0, "default box minus a grown-size dome");
  }
  return t_finish(NULL);
}
