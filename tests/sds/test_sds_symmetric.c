/* The symmetric start (docs/sds.md, "A symmetric start"): the n-fold
 * mirror-symmetric ball is a valid complex (positive tets, a closed
 * genus-0 boundary on the sphere, tet volumes summing to the enclosed
 * volume, Euler's ball) whose cells and tets map onto cells and tets under
 * the rotation by 2 pi / n and the mirror y -> -y about its axis, with a
 * surface cell at each tip place 2 pi j / n on the equator; its sphere
 * alone is the same closed surface; bad arguments are usage errors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/sds/sds.h"
#include "testutil.h"

#define PI 3.14159265358979323846

/* The cell at y (within tol), or -1. */
static int find_cell(const sessile_sds *o, const double y[3], double tol) {
  for (uint32_t c = 0; c < o->ncells; c++) {
    const double *x = o->x + 3 * (size_t)c;
    if (fabs(x[0] - y[0]) <= tol && fabs(x[1] - y[1]) <= tol && fabs(x[2] - y[2]) <= tol) return (int)c;
  }
  return -1;
}

static int cmp_u32(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return x < y ? -1 : x > y;
}
static int cmp_tet(const void *a, const void *b) { return memcmp(a, b, 4 * sizeof(uint32_t)); }

/* Every tet's image under the cell map perm is a tet (tets as sorted quadruples). */
static int tets_map_to_tets(const sessile_sds *o, const int *perm) {
  size_t nt = o->ntets;
  uint32_t *a = malloc(4 * nt * sizeof *a), *b = malloc(4 * nt * sizeof *b);
  int ok = a && b;
  for (size_t t = 0; ok && t < nt; t++) {
    for (int k = 0; k < 4; k++) {
      a[4 * t + k] = o->tet[4 * t + k];
      ok = ok && perm[o->tet[4 * t + k]] >= 0;
      b[4 * t + k] = ok ? (uint32_t)perm[o->tet[4 * t + k]] : 0;
    }
    qsort(a + 4 * t, 4, sizeof *a, cmp_u32), qsort(b + 4 * t, 4, sizeof *b, cmp_u32);
  }
  if (ok) {
    qsort(a, nt, 4 * sizeof *a, cmp_tet), qsort(b, nt, 4 * sizeof *b, cmp_tet);
    ok = !memcmp(a, b, 4 * nt * sizeof *a);
  }
  free(a), free(b);
  return ok;
}

/* The boundary faces as a surface (cells renumbered). */
static void boundary_of(const sessile_sds *o, sessile_surface *s) {
  uint32_t *map = malloc(o->ncells * sizeof *map), nv = 0;
  t_must("reserve", sessile_surface_reserve(s, o->ncells, o->nfaces));
  for (uint32_t c = 0; c < o->ncells; c++) map[c] = UINT32_MAX;
  for (uint32_t f = 0; f < 3 * o->nfaces; f++)
    if (map[o->face[f]] == UINT32_MAX) {
      map[o->face[f]] = nv;
      memcpy(s->pos + 3 * nv, o->x + 3 * (size_t)o->face[f], 24);
      nv++;
    }
  for (uint32_t f = 0; f < 3 * o->nfaces; f++) s->tri[f] = map[o->face[f]];
  s->nv = nv, s->nf = o->nfaces;
  free(map);
}

static void ball(int n, double h) {
  const double ctr[3] = {0.5, -1, 2}, r = 1.5, tol = 1e-12 * r;
  char what[96];
  sessile_sds o = {0};
  snprintf(what, sizeof what, "%d-fold ball, edge %g", n, h);
  t_must(what, sessile_sds_symmetric_ball(n, r, h, ctr, 1, 1, 1.0, &o));
  printf("%s: %u cells, %u tets, %u boundary faces\n", what, o.ncells, o.ntets, o.nfaces);
  double vmin = INFINITY, vsum = 0;
  for (uint32_t t = 0; t < o.ntets; t++) {
    double v = sessile_sds_tet_volume(&o, t);
    vmin = fmin(vmin, v), vsum += v;
  }
  t_true("every tet positively oriented", vmin > 0);
  sessile_surface s = {0};
  boundary_of(&o, &s);
  t_ok("boundary: closed, consistently oriented, genus 0", sessile_surface_check(&s, 2, 0));
  sessile_surface_stats st;
  sessile_surface_stats_of(&s, &st);
  t_check("sum of tet volumes = enclosed volume (rel)", fabs(vsum - st.volume) / st.volume, 1e-12);
  /* the inscribed polyhedron: below the ball's volume, near it at this edge */
  double vb = 4.0 / 3.0 * PI * r * r * r;
  t_true("enclosed volume within 10 % below the ball's", st.volume < vb && st.volume > 0.9 * vb);
  double dmax = 0;
  for (uint32_t v = 0; v < s.nv; v++) {
    double d = 0;
    for (int k = 0; k < 3; k++) d += (s.pos[3 * v + k] - ctr[k]) * (s.pos[3 * v + k] - ctr[k]);
    dmax = fmax(dmax, fabs(sqrt(d) - r));
  }
  t_check("boundary cells on the sphere (|distance - r| / r)", dmax / r, 1e-14);
  long F = (4L * o.ntets + o.nfaces) / 2;
  t_true("Euler characteristic of a ball (V - E + F - T = 1)", (long)o.ncells - (long)o.nedges + F - (long)o.ntets == 1);
  /* the tips' places */
  int tips = 0;
  for (int j = 0; j < n; j++) {
    double y[3] = {ctr[0] + r * cos(2 * PI * j / n), ctr[1] + r * sin(2 * PI * j / n), ctr[2]};
    int c = find_cell(&o, y, tol);
    tips += c >= 0 && o.surface[c];
  }
  t_true("a surface cell at each of the n tip places on the equator", tips == n);
  /* the symmetries: rotation by 2 pi / n and the mirror y -> -y */
  int *rot = malloc(o.ncells * sizeof *rot), *mir = malloc(o.ncells * sizeof *mir), unmatched = 0;
  double c = cos(2 * PI / n), sn = sin(2 * PI / n);
  for (uint32_t i = 0; i < o.ncells; i++) {
    const double *x = o.x + 3 * (size_t)i;
    double dx = x[0] - ctr[0], dy = x[1] - ctr[1];
    double yr[3] = {ctr[0] + c * dx - sn * dy, ctr[1] + sn * dx + c * dy, x[2]}, ym[3] = {x[0], ctr[1] - dy, x[2]};
    rot[i] = find_cell(&o, yr, tol), mir[i] = find_cell(&o, ym, tol);
    unmatched += (rot[i] < 0) + (mir[i] < 0);
  }
  t_true("every cell's rotation by 2 pi / n and its mirror image are cells (1e-12 r)", unmatched == 0);
  t_true("the rotation maps tets onto tets", unmatched == 0 && tets_map_to_tets(&o, rot));
  t_true("the mirror maps tets onto tets", unmatched == 0 && tets_map_to_tets(&o, mir));
  /* the sphere alone: the same boundary */
  sessile_surface sp = {0};
  t_must("the symmetric sphere", sessile_sds_symmetric_sphere(n, r, h, ctr, &sp));
  t_ok("sphere: closed, consistently oriented, genus 0", sessile_surface_check(&sp, 2, 0));
  sessile_surface_stats ss;
  sessile_surface_stats_of(&sp, &ss);
  t_true("sphere: the ball's boundary (vertices, triangles)", sp.nv == s.nv && sp.nf == s.nf);
  t_check("sphere: the ball's enclosed volume (rel)", fabs(ss.volume - st.volume) / st.volume, 1e-12);
  free(rot), free(mir);
  sessile_surface_free(&sp), sessile_surface_free(&s);
  sessile_sds_free(&o);
}

int main(void) {
  ball(6, 0.45); /* the rock model's 6 tips at its icosphere's edge, scaled to r = 1.5 */
  ball(4, 0.3);
  ball(3, 0.6);
  const double c0[3] = {0, 0, 0};
  sessile_sds o = {0};
  t_true("one mirror is a usage error", sessile_sds_symmetric_ball(1, 1, 0.3, c0, 0, 0, 1, &o) == SESSILE_ERR_USAGE);
  t_true("13 mirrors are a usage error", sessile_sds_symmetric_ball(13, 1, 0.3, c0, 0, 0, 1, &o) == SESSILE_ERR_USAGE);
  t_true("an edge longer than the radius is a usage error",
         sessile_sds_symmetric_ball(6, 1, 1.5, c0, 0, 0, 1, &o) == SESSILE_ERR_USAGE);
  printf("  (%s)\n", sessile_error_message());
  return t_finish(NULL);
}
