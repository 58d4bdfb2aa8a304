/* Case 1 (Figure 4): a vertex moving linearly through the opposite face of
 * a tet of a TetGen ball, at a time known analytically; interior face (the
 * 2-3 flip), boundary face (the tet dropped) and the refusal (vertex and
 * face both on the surface). */
#include "test_topo_fixture.h"

#define K 1.05 /* v goes to g + 0.05 (g - p): through the face at s = 1/K */

/* Positions at s of all vertices: v moves from p to p + K (g - p). */
static void place(sessile_sds_topo_complex *cx, const double *x0, uint32_t v, const double *g, double s) {
  memcpy(cx->x, x0, 3 * (size_t)cx->nv * sizeof *cx->x);
  for (int k = 0; k < 3; k++) cx->x[3 * v + k] = x0[3 * v + k] + s * K * (g[k] - x0[3 * v + k]);
}

static void tet_pts(const sessile_sds_topo_complex *cx, uint32_t t, double *p) {
  for (int q = 0; q < 4; q++) memcpy(p + 3 * q, cx->x + 3 * cx->tet[4 * t + q], 3 * sizeof *p);
}

/* Does any tet other than t invert on [0, 1] when v moves?  (The
 * precondition of a clean single event.) */
static int others_invert(sessile_sds_topo_complex *cx, const double *x0, uint32_t t, uint32_t v, const double *g) {
  double p[12], q[12];
  sessile_sds_topo_inversion inv;
  for (uint32_t u = 0; u < cx->nt; u++) {
    const uint32_t *w = cx->tet + 4 * u;
    if (u == t || (w[0] != v && w[1] != v && w[2] != v && w[3] != v)) continue;
    place(cx, x0, v, g, 0), tet_pts(cx, u, p);
    place(cx, x0, v, g, 1), tet_pts(cx, u, q);
    if (sessile_sds_topo_inversion_time(p, q, 0, 1, &inv)) return 1;
  }
  return 0;
}

/* Finds tet t and its vertex v with (f_boundary, v_boundary) as asked and a
 * clean single event; runs the event and the transformation with all checks. */
static void run_case(int f_boundary, int v_boundary, const char *label) {
  sessile_sds_topo_complex cx = {0};
  fx_ball(3, 0.005, &cx);
  uint32_t nb, *bnd = fx_boundary(&cx, &nb);
  uint8_t *onb = calloc(cx.nv, 1);
  for (uint32_t i = 0; i < 3 * nb; i++) onb[bnd[i]] = 1;
  double *x0 = t_xalloc(3 * cx.nv * sizeof *x0);
  memcpy(x0, cx.x, 3 * cx.nv * sizeof *x0);
  printf("%s:\n", label);
  for (uint32_t t = 0; t < cx.nt; t++)
    for (int qv = 0; qv < 4; qv++) {
      static const int fo[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
      uint32_t v = cx.tet[4 * t + qv], f[3];
      for (int i = 0; i < 3; i++) f[i] = cx.tet[4 * t + fo[qv][i]];
      int fb = 0;
      for (uint32_t i = 0; i < nb; i++) {
        const uint32_t *b = bnd + 3 * i;
        int m = 0;
        for (int a = 0; a < 3; a++) m += b[a] == f[0] || b[a] == f[1] || b[a] == f[2];
        fb |= m == 3;
      }
      if (fb != f_boundary || onb[v] != v_boundary) continue;
      double g[3];
      for (int k = 0; k < 3; k++) g[k] = (x0[3 * f[0] + k] + x0[3 * f[1] + k] + x0[3 * f[2] + k]) / 3;
      if (f_boundary && v_boundary) {
        /* the refusal: no motion needed */
        sessile_sds_topo_complex keep;
        fx_copy(&cx, &keep);
        sessile_sds_topo_transform tr;
        sessile_status st = sessile_sds_topo_case1(&cx, t, v, &tr);
        printf("  refusal: %s\n", sessile_error_message());
        t_true("vertex and face both on the surface: SESSILE_ERR_UNSUPPORTED", st == SESSILE_ERR_UNSUPPORTED);
        t_true("refusal message says why", strstr(sessile_error_message(), "both on the surface") != NULL);
        t_true("refused: complex untouched", cx.nt == keep.nt && !memcmp(cx.tet, keep.tet, 4 * cx.nt * sizeof *cx.tet));
        sessile_sds_topo_complex_free(&keep);
        goto out;
      }
      if (others_invert(&cx, x0, t, v, g)) continue;
      /* the event: time from the cubic against 1/K */
      double p[12], q[12];
      place(&cx, x0, v, g, 0), tet_pts(&cx, t, p);
      place(&cx, x0, v, g, 1), tet_pts(&cx, t, q);
      sessile_sds_topo_inversion inv;
      t_true("inversion found", sessile_sds_topo_inversion_time(p, q, 0, 1, &inv));
      t_check("inversion time = 1/K", fabs(inv.s - 1 / K), 1e-12);
      t_true("case 1 with the moving vertex", inv.kind == SESSILE_SDS_TOPO_VERTEX_FACE && inv.vertex == qv);
      place(&cx, x0, v, g, inv.s);
      double v0 = fx_volume(&cx);
      uint32_t nt0 = cx.nt;
      sessile_sds_topo_transform tr;
      double t0 = fx_now();
      sessile_status st = sessile_sds_topo_apply_inversion(&cx, t, &inv, &tr); /* = case1(t, v) */
      double dt = fx_now() - t0;
      t_ok("case 1 transformation", st);
      if (st != SESSILE_OK) goto out;
      printf("  tet %u vertex %u: %u tets out, %u in, %.3f ms\n", t, v, tr.n_removed, tr.n_added, 1e3 * dt);
      t_true("tets out/in: interior face 2/3, boundary face 1/0",
             f_boundary ? tr.n_removed == 1 && tr.n_added == 0 : tr.n_removed == 2 && tr.n_added == 3);
      t_true("tet count", cx.nt == nt0 - tr.n_removed + tr.n_added);
      sessile_sds_topo_report rep;
      t_ok("valid at the event time", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0.0, &rep));
      t_check("volume unchanged by the transformation (rel)", fabs(rep.volume - v0) / v0, 1e-12);
      place(&cx, x0, v, g, 1); /* move on past the event */
      t_ok("valid after moving on (no inverted tet)", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0.0, &rep));
      if (f_boundary) t_true("the vertex is on the surface now", fx_on_boundary(&cx, v));
      free(tr.tet_from);
      goto out;
    }
  if (f_boundary && v_boundary)
    printf("  the ball has no tet with a surface face and the opposite vertex on the surface\n");
  else
    t_true("found a tet for this case", 0);
out:
  free(bnd), free(onb), free(x0);
  sessile_sds_topo_complex_free(&cx);
}

/* The 2-3 flip refused where the edge (v, v') exists already. */
static void existing_edge(void) {
  sessile_sds_topo_complex cx = {0};
  fx_ball(3, 0.005, &cx);
  static const int fo[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (uint32_t t = 0; t < cx.nt; t++)
    for (int qv = 0; qv < 4; qv++) {
      uint32_t v = cx.tet[4 * t + qv], f[3], vp = UINT32_MAX;
      for (int i = 0; i < 3; i++) f[i] = cx.tet[4 * t + fo[qv][i]];
      for (uint32_t u = 0; u < cx.nt; u++) {
        const uint32_t *w = cx.tet + 4 * u;
        int m = 0;
        for (int i = 0; i < 4; i++) m += w[i] == f[0] || w[i] == f[1] || w[i] == f[2];
        if (u != t && m == 3) vp = w[0] + w[1] + w[2] + w[3] - f[0] - f[1] - f[2];
      }
      if (vp == UINT32_MAX) continue;
      int adj = 0;
      for (uint32_t u = 0; u < cx.nt && !adj; u++) {
        const uint32_t *w = cx.tet + 4 * u;
        int hv = w[0] == v || w[1] == v || w[2] == v || w[3] == v,
            hp = w[0] == vp || w[1] == vp || w[2] == vp || w[3] == vp;
        adj = hv && hp;
      }
      if (!adj) continue;
      sessile_sds_topo_complex keep;
      fx_copy(&cx, &keep);
      sessile_sds_topo_transform tr;
      sessile_status st = sessile_sds_topo_case1(&cx, t, v, &tr);
      printf("existing edge: %s\n", sessile_error_message());
      t_true("edge (v, v') already there: SESSILE_ERR_UNSUPPORTED", st == SESSILE_ERR_UNSUPPORTED);
      t_true("the message says so", strstr(sessile_error_message(), "exists already") != NULL);
      t_true("untouched", cx.nt == keep.nt && !memcmp(cx.tet, keep.tet, 4 * cx.nt * sizeof *cx.tet));
      sessile_sds_topo_complex_free(&keep);
      sessile_sds_topo_complex_free(&cx);
      return;
    }
  printf("existing edge: no such configuration in the ball\n");
  sessile_sds_topo_complex_free(&cx);
}

int main(void) {
  existing_edge();
  run_case(0, 0, "interior vertex through an interior face");
  run_case(0, 1, "surface vertex through an interior face");
  run_case(1, 0, "interior vertex out through a surface face");
  run_case(1, 1, "surface vertex and surface face (refused), in the ball if it has one");
  {
    /* a single tet: every vertex and face on the surface */
    double x[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1};
    uint32_t tt[4] = {0, 1, 2, 3};
    sessile_sds_topo_complex one = {4, 1, t_xalloc(sizeof x), t_xalloc(sizeof tt)};
    memcpy(one.x, x, sizeof x), memcpy(one.tet, tt, sizeof tt);
    sessile_sds_topo_transform tr;
    sessile_status st = sessile_sds_topo_case1(&one, 0, 3, &tr);
    printf("single tet refusal: %s\n", sessile_error_message());
    t_true("single tet: SESSILE_ERR_UNSUPPORTED", st == SESSILE_ERR_UNSUPPORTED);
    t_true("single tet: untouched", one.nt == 1 && !memcmp(one.tet, tt, sizeof tt));
    t_true("vertex not in the tet: SESSILE_ERR_USAGE", sessile_sds_topo_case1(&one, 0, 7, &tr) == SESSILE_ERR_USAGE);
    sessile_sds_topo_complex_free(&one);
  }
  return t_finish(NULL);
}
