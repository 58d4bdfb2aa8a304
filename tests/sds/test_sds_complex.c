/* The SDS organism: Appendix A's rest volume against the Cayley-Menger
 * determinant; a TetGen import of an icosphere is a valid complex (positive
 * tets, boundary = the input surface, closed and consistently oriented, tet
 * volumes summing to the enclosed volume, every interior face in two tets),
 * at rest (zero energy and force); rebuild keeps spring multipliers, orients
 * tets and gives new ones fresh multipliers. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/sds/sds.h"
#include "testutil.h"

/* Volume from the six edge lengths by the Cayley-Menger determinant:
 * 288 V^2 = det [[0 1 1 1 1], [1 0 d01^2 d02^2 d03^2], ...]. */
static double cayley_menger(const double r[4]) {
  double M[5][5];
  for (int i = 0; i < 5; i++)
    for (int j = 0; j < 5; j++) {
      if (i == j) M[i][j] = 0;
      else if (i == 0 || j == 0) M[i][j] = 1;
      else {
        double d = r[i - 1] + r[j - 1];
        M[i][j] = d * d;
      }
    }
  double det = 1;
  for (int c = 0; c < 5; c++) { /* Gaussian elimination with partial pivoting */
    int p = c;
    for (int i = c + 1; i < 5; i++)
      if (fabs(M[i][c]) > fabs(M[p][c])) p = i;
    if (p != c) {
      for (int j = 0; j < 5; j++) {
        double t = M[c][j];
        M[c][j] = M[p][j], M[p][j] = t;
      }
      det = -det;
    }
    det *= M[c][c];
    for (int i = c + 1; i < 5; i++) {
      double f = M[i][c] / M[c][c];
      for (int j = c; j < 5; j++) M[i][j] -= f * M[c][j];
    }
  }
  return sqrt(det / 288.0);
}

static void rest_formula(void) {
  static const double radii[4][4] = {{1, 1, 1, 1}, {0.5, 1, 1.5, 2}, {0.1, 0.3, 0.2, 0.9}, {3, 0.2, 1, 0.7}};
  double worst = 0;
  for (int k = 0; k < 4; k++) {
    const double *r = radii[k];
    double a = sessile_sds_tet_rest(r[0], r[1], r[2], r[3]), b = cayley_menger(r);
    double e = fabs(a - b) / b;
    if (e > worst) worst = e;
  }
  t_check("Appendix A rest volume vs Cayley-Menger (4 radius sets, rel)", worst, 1e-12);
  double r = 0.7, reg = pow(2 * r, 3) / (6 * sqrt(2.0));
  t_check("equal radii: the regular tet of edge 2r (rel)", fabs(sessile_sds_tet_rest(r, r, r, r) - reg) / reg, 1e-14);
}

static void import_valid(void) {
  const double ctr[3] = {0.5, -1, 2};
  sessile_sds o = {0};
  t_must("icosphere level 3 through TetGen", sessile_sds_from_icosphere(3, 2.0, ctr, 0, 2, 1, 1.0, &o));
  printf("imported: %u cells, %u tets, %u edges, %u boundary faces\n", o.ncells, o.ntets, o.nedges, o.nfaces);
  t_true("boundary faces = the icosphere's 320 triangles (TetGen -Y)", o.nfaces == 320);
  double vmin = INFINITY, vsum = 0;
  for (uint32_t t = 0; t < o.ntets; t++) {
    double v = sessile_sds_tet_volume(&o, t);
    vmin = fmin(vmin, v), vsum += v;
  }
  t_true("every tet positively oriented", vmin > 0);
  /* the boundary as a surface: closed, consistent, genus 0, same volume */
  sessile_surface s = {0};
  uint32_t *map = malloc(o.ncells * sizeof *map);
  t_must("reserve", sessile_surface_reserve(&s, o.ncells, o.nfaces));
  uint32_t nv = 0, nsurf = 0;
  for (uint32_t c = 0; c < o.ncells; c++) {
    map[c] = UINT32_MAX;
    nsurf += o.surface[c];
  }
  for (uint32_t f = 0; f < 3 * o.nfaces; f++)
    if (map[o.face[f]] == UINT32_MAX) {
      map[o.face[f]] = nv;
      memcpy(s.pos + 3 * nv, o.x + 3 * (size_t)o.face[f], 24);
      nv++;
    }
  for (uint32_t f = 0; f < 3 * o.nfaces; f++) s.tri[f] = map[o.face[f]];
  s.nv = nv, s.nf = o.nfaces;
  t_ok("boundary is a closed, consistently oriented genus-0 surface", sessile_surface_check(&s, 2, 0));
  t_true("surface flags = the boundary faces' cells", nsurf == nv);
  sessile_surface_stats st;
  sessile_surface_stats_of(&s, &st);
  t_check("sum of tet volumes = enclosed volume (rel)", fabs(vsum - st.volume) / st.volume, 1e-12);
  t_true("boundary oriented outward (positive enclosed volume)", st.volume > 0);
  /* every tet face in one (boundary) or two tets: count face incidences */
  size_t inc = 0;
  for (uint32_t c = 0; c < o.ncells; c++) inc += o.cell_tet_off[c + 1] - o.cell_tet_off[c];
  t_true("CSR cell->tet holds 4 per tet", inc == 4 * (size_t)o.ntets);
  /* Euler for a ball: V - E + F - T = 1, F = (4T + boundary) / 2 */
  long F = (4L * o.ntets + o.nfaces) / 2;
  t_true("Euler characteristic of a ball (V - E + F - T = 1)",
         (long)o.ncells - (long)o.nedges + F - (long)o.ntets == 1);
  double rmin = INFINITY, rmax = 0;
  for (uint32_t c = 0; c < o.ncells; c++) rmin = fmin(rmin, o.r[c]), rmax = fmax(rmax, o.r[c]);
  printf("radii %.4f .. %.4f u\n", rmin, rmax);
  t_check("mass = 4/3 pi r^3 at density 1 (cell 0, rel)",
          fabs(o.m[0] - 4.0 / 3.0 * 3.14159265358979323846 * pow(o.r[0], 3)) / o.m[0], 1e-14);

  /* at rest: zero energy, zero force (no gravity) */
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.gravity = 0;
  sessile_sds_energy e;
  sessile_sds_energy_of(&o, &p, &e);
  t_check("import: elastic energy (edges + tets)", e.edge + e.vol, 1e-26);
  double *f = malloc(3 * o.ncells * sizeof *f), fmax_ = 0, scale = 0;
  sessile_sds_forces_ref(&o, &p, 1, f);
  for (uint32_t c = 0; c < o.ncells; c++) {
    fmax_ = fmax(fmax_, fabs(f[3 * c]) + fabs(f[3 * c + 1]) + fabs(f[3 * c + 2]));
    scale = fmax(scale, p.k_edge * o.m[c]); /* the force of a unit strain */
  }
  t_check("import: largest force / force of a unit strain", fmax_ / scale, 1e-13);
  free(f);

  /* rebuild keeps multipliers, orients, gives fresh ones */
  double sm_e = o.edge_sm[7], sm_t = o.tet_sm[5];
  o.edge_sm[7] = 1.25;
  uint32_t *q = o.tet + 4 * 3, tmp = q[0];
  q[0] = q[1], q[1] = tmp; /* tet 3 now negative */
  o.tet_sm[9] = 0;         /* tet 9 "new" */
  t_ok("rebuild", sessile_sds_rebuild(&o, SESSILE_SDS_NEW_UNIT));
  t_true("rebuild keeps an edge's s_m", o.edge_sm[7] == 1.25);
  t_true("rebuild keeps a tet's s_m", o.tet_sm[5] == sm_t);
  t_true("rebuild re-orients a negative tet", sessile_sds_tet_volume(&o, 3) > 0);
  t_true("rebuild gives a new tet s_m = 1 (NEW_UNIT)", o.tet_sm[9] == 1.0);
  (void)sm_e;
  /* rebuild_oriented takes the orientation as given: a tet made inverted by
   * moving a cell (a sliver) keeps its vertex order */
  {
    const uint32_t *q4 = o.tet + 4 * 4;
    uint32_t keep[4] = {q4[0], q4[1], q4[2], q4[3]};
    double save[3], *xa = o.x + 3 * (size_t)q4[0], *xb4 = o.x + 3 * (size_t)q4[1], *xc = o.x + 3 * (size_t)q4[2],
                    *xd = o.x + 3 * (size_t)q4[3];
    for (int k = 0; k < 3; k++) save[k] = xa[k], xa[k] = xb4[k] + xc[k] + xd[k] - 2 * xa[k]; /* through the face */
    double v0 = sessile_sds_tet_volume(&o, 4);
    t_ok("rebuild_oriented", sessile_sds_rebuild_oriented(&o, SESSILE_SDS_NEW_UNIT));
    t_true("rebuild_oriented keeps an inverted tet's vertex order",
           v0 < 0 && !memcmp(keep, o.tet + 4 * 4, sizeof keep) && sessile_sds_tet_volume(&o, 4) == v0);
    for (int k = 0; k < 3; k++) xa[k] = save[k];
    t_ok("rebuild_oriented back", sessile_sds_rebuild_oriented(&o, SESSILE_SDS_NEW_UNIT));
  }
  /* a face in three tets is refused */
  sessile_sds bad = {0};
  const double xb[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1};
  const uint32_t tb[12] = {0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 2, 3};
  t_true("a face in three tets is refused", sessile_sds_from_tets(xb, 5, tb, 3, 0, 0, 1, &bad) != SESSILE_OK);
  printf("  (%s)\n", sessile_error_message());
  sessile_sds_free(&bad);
  sessile_surface_free(&s);
  free(map);
  sessile_sds_free(&o);
}

static void copy_equal(void) {
  sessile_sds a = {0}, b = {0};
  const double ctr[3] = {0, 0, 0};
  t_must("icosphere level 2", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 1, 0, 1.0, &a));
  t_must("copy", sessile_sds_copy(&a, &b));
  t_true("copy: same cells, tets, edges, faces and incidence",
         a.ncells == b.ncells && !memcmp(a.x, b.x, 24 * a.ncells) && !memcmp(a.tet, b.tet, 16 * a.ntets) &&
             !memcmp(a.edge_sm, b.edge_sm, 8 * a.nedges) && !memcmp(a.face, b.face, 12 * a.nfaces) &&
             !memcmp(a.cell_tet, b.cell_tet, 16 * a.ntets));
  sessile_sds_free(&a), sessile_sds_free(&b);
  sessile_surface tet4 = {0};
  t_true("an empty surface is refused (usage)",
         sessile_sds_from_surface(&tet4, NULL, 0, 0, 0, 1, &a) == SESSILE_ERR_USAGE);
}

int main(void) {
  rest_formula();
  import_valid();
  copy_equal();
  return t_finish(NULL);
}
