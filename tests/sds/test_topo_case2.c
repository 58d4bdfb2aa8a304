/* Case 2 (Figure 5): two opposite edges of a tet of a TetGen ball moved
 * linearly until they cross at their midpoints (the time known: the volume
 * is linear in the relative translation); interior edges (the hull of U ∪ L
 * re-tetrahedralised), a boundary edge covered first, a boundary edge in the
 * flat tet only (the tet dropped). */
#include "test_topo_fixture.h"

#define K 1.05 /* the edges cross at s = 1/K and move 5% past */

typedef struct scene {
  double *x0, w[3];
  uint32_t mv[4];  /* moving vertices */
  double share[4]; /* fraction of w each moves by */
} scene;

static void place(sessile_sds_topo_complex *cx, const scene *sc, double s) {
  memcpy(cx->x, sc->x0, 3 * (size_t)cx->nv * sizeof *cx->x);
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) cx->x[3 * sc->mv[i] + k] += s * K * sc->share[i] * sc->w[k];
}
static void tet_pts(const sessile_sds_topo_complex *cx, uint32_t t, double *p) {
  for (int q = 0; q < 4; q++) memcpy(p + 3 * q, cx->x + 3 * cx->tet[4 * t + q], 3 * sizeof *p);
}
static int has(const uint32_t *w, uint32_t a) { return w[0] == a || w[1] == a || w[2] == a || w[3] == a; }

/* boundary faces through edge (a, b) and their third vertices */
static int edge_faces(const uint32_t *bnd, uint32_t nb, uint32_t a, uint32_t b, uint32_t third[2]) {
  int n = 0;
  for (uint32_t i = 0; i < nb; i++) {
    const uint32_t *f = bnd + 3 * i;
    int ha = f[0] == a || f[1] == a || f[2] == a, hb = f[0] == b || f[1] == b || f[2] == b;
    if (ha && hb) {
      if (n < 2) third[n] = f[0] + f[1] + f[2] - a - b;
      n++;
    }
  }
  return n;
}

/* kind 0: both edges interior; 1: e_u on the boundary, in several tets
 * (covered); 2: e_u on the boundary in the flat tet only.  Runs up to
 * `want` events on fresh copies of the ball; returns how many ran. */
static int run_kind(int kind, int want, const char *label) {
  sessile_sds_topo_complex ball = {0};
  fx_ball(3, 0.005, &ball);
  uint32_t nb, *bnd = fx_boundary(&ball, &nb);
  int done = 0;
  double tsum = 0;
  static const int pairs[6][4] = {{0, 1, 2, 3}, {2, 3, 0, 1}, {0, 2, 1, 3}, {1, 3, 0, 2}, {0, 3, 1, 2}, {1, 2, 0, 3}};
  printf("%s:\n", label);
  for (uint32_t t = 0; t < ball.nt && done < want; t++)
    for (int pi = 0; pi < 6 && done < want; pi++) {
      const uint32_t *tv = ball.tet + 4 * t;
      uint32_t a = tv[pairs[pi][0]], b = tv[pairs[pi][1]], c = tv[pairs[pi][2]], d = tv[pairs[pi][3]];
      uint32_t tu[2], tl[2];
      int bu = edge_faces(bnd, nb, a, b, tu) > 0, bl = edge_faces(bnd, nb, c, d, tl) > 0;
      int nu = 0;
      for (uint32_t u = 0; u < ball.nt; u++) nu += has(ball.tet + 4 * u, a) && has(ball.tet + 4 * u, b);
      if (kind == 0 && (bu || bl)) continue;
      if (kind == 1 && (!bu || bl || nu < 2 || tu[0] == c || tu[0] == d || tu[1] == c || tu[1] == d)) continue;
      if (kind == 2 && (!bu || nu != 1)) continue;
      scene sc = {ball.x, {0, 0, 0}, {a, b, c, d}, {0, 0, 0, 0}};
      for (int k = 0; k < 3; k++)
        sc.w[k] = 0.5 * (ball.x[3 * a + k] + ball.x[3 * b + k]) - 0.5 * (ball.x[3 * c + k] + ball.x[3 * d + k]);
      /* interior: the edges meet halfway; boundary edge e_u fixed, e_l comes */
      sessile_sds_topo_complex cx;
      fx_copy(&ball, &cx);
      sc.x0 = ball.x;
      /* precondition: no other tet of a moving vertex inverts on [0, 1];
       * with a boundary edge, also a valley there at the event (at a ridge
       * the refusal, tested apart); the split of the motion between the two
       * edges tried from even to e_l only */
      int clean = 0;
      double p[12], q[12];
      sessile_sds_topo_inversion inv;
      for (double lam = 0.5; lam <= 1.0 + 1e-9 && !clean; lam += 0.1) {
        sc.share[0] = sc.share[1] = -(1 - lam), sc.share[2] = sc.share[3] = lam;
        if (kind == 0 && lam > 0.5) break;
        clean = 1;
        for (uint32_t u = 0; u < cx.nt && clean; u++) {
          const uint32_t *w = cx.tet + 4 * u;
          if (u == t || !(has(w, a) || has(w, b) || has(w, c) || has(w, d))) continue;
          place(&cx, &sc, 0), tet_pts(&cx, u, p);
          place(&cx, &sc, 1), tet_pts(&cx, u, q);
          clean = !sessile_sds_topo_inversion_time(p, q, 0, 1, &inv);
        }
        if (clean && kind == 1) {
          place(&cx, &sc, 1 / K);
          double *X = cx.x;
          /* a valley at ab: q on the outer side of the boundary face a b p */
          uint32_t f0[3] = {a, b, tu[0]};
          for (uint32_t i = 0; i < nb; i++) {
            const uint32_t *f = bnd + 3 * i;
            int m = 0;
            for (int z = 0; z < 3; z++) m += f[z] == a || f[z] == b || f[z] == tu[0];
            if (m == 3) memcpy(f0, f, sizeof f0);
          }
          clean = sessile_sds_topo_volume(X + 3 * f0[0], X + 3 * f0[1], X + 3 * f0[2], X + 3 * tu[1]) > 0;
        }
      }
      if (!clean) {
        sessile_sds_topo_complex_free(&cx);
        continue;
      }
      place(&cx, &sc, 0), tet_pts(&cx, t, p);
      place(&cx, &sc, 1), tet_pts(&cx, t, q);
      t_true("inversion found", sessile_sds_topo_inversion_time(p, q, 0, 1, &inv));
      t_check("inversion time = 1/K", fabs(inv.s - 1 / K), 1e-12);
      int lu0 = pairs[pi][0], lu1 = pairs[pi][1];
      int match = (inv.edge[0][0] == lu0 && inv.edge[0][1] == lu1) ||
                  (inv.edge[0][0] == lu1 && inv.edge[0][1] == lu0) ||
                  (inv.edge[1][0] == lu0 && inv.edge[1][1] == lu1) || (inv.edge[1][0] == lu1 && inv.edge[1][1] == lu0);
      t_true("case 2 with the moved edges", inv.kind == SESSILE_SDS_TOPO_EDGE_EDGE && match);
      place(&cx, &sc, inv.s);
      double v0 = fx_volume(&cx), cover = 0;
      if (kind == 1) {
        double *X = cx.x;
        cover = fabs(sessile_sds_topo_volume(X + 3 * a, X + 3 * b, X + 3 * tu[0], X + 3 * tu[1]));
      }
      sessile_sds_topo_transform tr;
      double t0 = fx_now();
      sessile_status st = sessile_sds_topo_apply_inversion(&cx, t, &inv, &tr); /* = case2 on (a b), (c d) */
      double dt = fx_now() - t0;
      tsum += dt;
      t_ok("case 2 transformation", st);
      if (st == SESSILE_OK) {
        printf("  tet %u edges (%u %u) (%u %u): %u tets out, %u in, %.3f ms\n", t, a, b, c, d, tr.n_removed, tr.n_added,
               1e3 * dt);
        sessile_sds_topo_report rep;
        t_ok("valid at the event time", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0.0, &rep));
        t_check(kind == 1 ? "volume grows by the covering tet's (rel)" : "volume unchanged by the transformation (rel)",
                fabs(rep.volume - v0 - cover) / v0, 1e-12);
        if (kind == 2) t_true("flat tet dropped, nothing added", tr.n_removed == 1 && tr.n_added == 0);
        int both = 0; /* no tet holds both crossing edges any more */
        for (uint32_t u = 0; u < cx.nt; u++)
          both |= has(cx.tet + 4 * u, a) && has(cx.tet + 4 * u, b) && has(cx.tet + 4 * u, c) && has(cx.tet + 4 * u, d);
        t_true("no tet spans both edges", !both);
        place(&cx, &sc, 1);
        t_ok("valid after moving on (no inverted tet)", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0.0, &rep));
        free(tr.tet_from);
      } else {
        printf("  %s\n", sessile_error_message());
      }
      sessile_sds_topo_complex_free(&cx);
      done++;
    }
  if (done) printf("  %d events, mean %.3f ms per transformation\n", done, 1e3 * tsum / done);
  free(bnd);
  sessile_sds_topo_complex_free(&ball);
  return done;
}

int main(void) {
  t_true("interior edges: events found", run_kind(0, 10, "interior edges") > 0);
  t_true("boundary edge covered: events found", run_kind(1, 5, "boundary edge in a valley, covered") > 0);
  int n2 = run_kind(2, 5, "boundary edge in the flat tet only");
  if (!n2) printf("  (the ball has no clean event of this kind)\n");
  {
    /* hand-made: edge ab (on the surface, in t only) comes down through the
     * edge cd; t2 = (c d a e), t3 = (c d b e) below.  Vertices a b c d e. */
    double x0[15] = {0.5, -0.5, 1, 0.5, 0.5, 1, 0, 0, 0, 1, 0, 0, 0.5, 0, -1}, xs[15];
    uint32_t tt[12] = {0, 1, 2, 3, 2, 3, 0, 4, 2, 3, 1, 4};
    for (int i = 0; i < 3; i++)
      if (sessile_sds_topo_volume(x0 + 3 * tt[4 * i], x0 + 3 * tt[4 * i + 1], x0 + 3 * tt[4 * i + 2],
                                  x0 + 3 * tt[4 * i + 3]) < 0) {
        uint32_t z = tt[4 * i + 1];
        tt[4 * i + 1] = tt[4 * i + 2], tt[4 * i + 2] = z;
      }
    sessile_sds_topo_complex hm = {5, 3, t_xalloc(sizeof x0), t_xalloc(sizeof tt)};
    memcpy(hm.x, x0, sizeof x0), memcpy(hm.tet, tt, sizeof tt);
    sessile_sds_topo_report rep;
    t_ok("hand-made: valid at the start", sessile_sds_topo_check(5, hm.x, 3, hm.tet, 0.0, &rep));
    double p[12], q[12];
    for (int v = 0; v < 4; v++) memcpy(p + 3 * v, x0 + 3 * tt[v], 3 * sizeof(double));
    memcpy(xs, x0, sizeof xs), xs[2] = xs[5] = 1 - K; /* z of a, b at s = 1 */
    for (int v = 0; v < 4; v++) memcpy(q + 3 * v, xs + 3 * tt[v], 3 * sizeof(double));
    sessile_sds_topo_inversion inv;
    t_true("hand-made: inversion found", sessile_sds_topo_inversion_time(p, q, 0, 1, &inv));
    t_check("hand-made: inversion time 1/K", fabs(inv.s - 1 / K), 1e-12);
    t_true("hand-made: case 2", inv.kind == SESSILE_SDS_TOPO_EDGE_EDGE);
    hm.x[2] = hm.x[5] = 1 - K * inv.s;
    double v0 = fx_volume(&hm);
    sessile_sds_topo_transform tr;
    t_ok("hand-made: case 2 transformation", sessile_sds_topo_case2(&hm, 0, 1, 2, 3, &tr));
    t_true("hand-made: the flat tet dropped, nothing added", tr.n_removed == 1 && tr.n_added == 0 && hm.nt == 2);
    t_ok("hand-made: valid at the event", sessile_sds_topo_check(5, hm.x, hm.nt, hm.tet, 0.0, &rep));
    t_check("hand-made: volume unchanged (rel)", fabs(rep.volume - v0) / v0, 1e-12);
    hm.x[2] = hm.x[5] = 1 - K;
    t_ok("hand-made: valid after moving on", sessile_sds_topo_check(5, hm.x, hm.nt, hm.tet, 0.0, &rep));
    free(tr.tet_from);
    sessile_sds_topo_complex_free(&hm);
  }
  {
    /* refusal: a boundary edge ab on a ridge (the faces a b p and a b q fall
     * away from it): the tet (a b p q) would overlap the body.  Vertices
     * a b p q e f; tets (a b p e), (a b e q) and (p e a f), so that neither
     * edge lies in one tet only.  (Valleys are covered: the ball above.) */
    double x0[18] = {0.5, -0.5, 0, 0.5, 0.5, 0, -1, 0, -0.5, 2, 0, -0.5, 0.5, 0, -1, 0.2, -1.5, -0.3};
    uint32_t tt[12] = {0, 1, 2, 4, 0, 1, 4, 3, 2, 4, 0, 5};
    for (int i = 0; i < 3; i++)
      if (sessile_sds_topo_volume(x0 + 3 * tt[4 * i], x0 + 3 * tt[4 * i + 1], x0 + 3 * tt[4 * i + 2],
                                  x0 + 3 * tt[4 * i + 3]) < 0) {
        uint32_t z = tt[4 * i + 1];
        tt[4 * i + 1] = tt[4 * i + 2], tt[4 * i + 2] = z;
      }
    uint32_t keep[12];
    memcpy(keep, tt, sizeof tt);
    sessile_sds_topo_complex hm = {6, 3, t_xalloc(sizeof x0), t_xalloc(sizeof tt)};
    memcpy(hm.x, x0, sizeof x0), memcpy(hm.tet, tt, sizeof tt);
    t_ok("ridge: valid", sessile_sds_topo_check(6, hm.x, 3, hm.tet, 0.0, NULL));
    sessile_sds_topo_transform tr;
    sessile_status st = sessile_sds_topo_case2(&hm, 0, 1, 2, 4, &tr);
    printf("ridge refusal: %s\n", sessile_error_message());
    t_true("ridge: SESSILE_ERR_UNSUPPORTED", st == SESSILE_ERR_UNSUPPORTED);
    t_true("ridge: the message names edge (0 1) and says why",
           strstr(sessile_error_message(), "edge (0 1)") && strstr(sessile_error_message(), "no tet covers it"));
    t_true("ridge: untouched", hm.nt == 3 && !memcmp(hm.tet, keep, sizeof keep));
    if (st == SESSILE_OK) free(tr.tet_from);
    sessile_sds_topo_complex_free(&hm);
  }
  /* bad input */
  sessile_sds_topo_complex ball = {0};
  fx_ball(2, 0.02, &ball);
  sessile_sds_topo_transform tr;
  t_true("edge in no tet: SESSILE_ERR_USAGE", sessile_sds_topo_case2(&ball, 0, 0, 1, 2, &tr) == SESSILE_ERR_USAGE);
  sessile_sds_topo_complex_free(&ball);
  return t_finish(NULL);
}
