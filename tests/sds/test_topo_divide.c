/* Division (§3.1.1) on a TetGen ball: an interior and a surface cell, then
 * a sequence of random divisions.  Each leaves a valid complex with the same
 * volume and boundary, daughters where promised, the other tets unchanged. */
#include "sessile/rng.h"
#include "test_topo_fixture.h"

/* c's outward boundary normal (area-weighted) in cx, from its boundary faces. */
static void boundary_normal(const sessile_sds_topo_complex *cx, uint32_t c, double n[3]) {
  uint32_t nb, *b = fx_boundary(cx, &nb);
  n[0] = n[1] = n[2] = 0;
  for (uint32_t f = 0; f < nb; f++) {
    const uint32_t *v = b + 3 * f;
    if (v[0] != c && v[1] != c && v[2] != c) continue;
    const double *p0 = cx->x + 3 * v[0], *p1 = cx->x + 3 * v[1], *p2 = cx->x + 3 * v[2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
    n[0] += e1[1] * e2[2] - e1[2] * e2[1], n[1] += e1[2] * e2[0] - e1[0] * e2[2], n[2] += e1[0] * e2[1] - e1[1] * e2[0];
  }
  double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int k = 0; k < 3; k++) n[k] /= l;
  free(b);
}

static int tangential_seen, tangential_expected;

/* One division with every check; returns the seconds it took. */
static double divide_checked(sessile_sds_topo_complex *cx, uint32_t c, const double d[3], int expect_surface,
                             int verbose) {
  sessile_sds_topo_complex old;
  fx_copy(cx, &old);
  uint32_t nb0, *b0 = fx_boundary(cx, &nb0);
  double v0 = fx_volume(cx), nrm[3] = {0, 0, 0};
  sessile_sds_topo_report rep0;
  t_ok("the complex before division passes the check",
       sessile_sds_topo_check(cx->nv, cx->x, cx->nt, cx->tet, 0.0, &rep0));
  double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), cosn = 1;
  if (expect_surface) {
    boundary_normal(cx, c, nrm);
    cosn = (d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]) / len;
  }
  /* the documented rule: a surface cell splits along the surface when d is
   * within 45° of the tangent plane (it may fall back to the inward split) */
  int tangent_dir = expect_surface && fabs(cosn) < sqrt(0.5);
  sessile_sds_topo_division div;
  double t0 = fx_now();
  sessile_status st = sessile_sds_topo_divide(cx, c, d, 0.0, &div);
  double dt = fx_now() - t0;
  t_ok("divide", st);
  if (st != SESSILE_OK) exit(t_finish(NULL));
  tangential_expected += tangent_dir, tangential_seen += div.tangential;
  t_true("a tangential split only for a surface cell and a direction within 45 degrees of the tangent plane",
         !div.tangential || tangent_dir);
  sessile_sds_topo_report rep;
  t_ok("the complex after division passes the check",
       sessile_sds_topo_check(cx->nv, cx->x, cx->nt, cx->tet, 0.0, &rep));
  double rel = fabs(rep.volume - v0) / v0;
  if (verbose || rel > 1e-12)
    printf("  cell %u (%s%s%s): %u tets out, %u in, eps %.3g, volume change %.2e rel, %.2f ms\n", c,
           div.surface ? "surface" : "interior", div.tangential ? ", tangential" : "",
           div.fallback ? ", cone fallback" : "", div.n_removed, div.n_added, div.eps, rel, 1e3 * dt);
  t_true("TetGen used unless a fault was injected", div.fallback == (tg_fault_inject != 0 && !div.tangential));
  t_check("volume unchanged (rel)", rel, 1e-12);
  t_true("surface flag as expected", div.surface == expect_surface);
  t_true("daughters: a = c, b appended", div.a == c && div.b == old.nv && cx->nv == old.nv + 1);
  t_true("boundary Euler characteristic unchanged", rep.boundary_euler == rep0.boundary_euler);
  double err = 0;
  uint32_t nb1, *b1 = fx_boundary(cx, &nb1);
  if (div.tangential) {
    /* a - b = 2 eps t (t: d projected on the tangent plane, unit); the
     * midpoint moved along the normal only; both on the boundary, which
     * keeps every face not through c and gains two */
    double t[3], tl = 0, mid[3], crs;
    for (int k = 0; k < 3; k++) t[k] = d[k] / len - cosn * nrm[k], tl += t[k] * t[k];
    tl = sqrt(tl);
    for (int k = 0; k < 3; k++) {
      double xa = cx->x[3 * c + k], xb = cx->x[3 * div.b + k];
      err = fmax(err, fabs((xa - xb) - 2 * div.eps * t[k] / tl));
      mid[k] = 0.5 * (xa + xb) - old.x[3 * c + k];
    }
    crs = sqrt(pow(mid[1] * nrm[2] - mid[2] * nrm[1], 2) + pow(mid[2] * nrm[0] - mid[0] * nrm[2], 2) +
               pow(mid[0] * nrm[1] - mid[1] * nrm[0], 2));
    t_check("tangential: a - b = 2 eps t", err, 1e-12);
    t_check("tangential: the daughters' midpoint moved along the normal only", crs, 1e-12);
    t_true("tangential: the lift is below eps", sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]) < div.eps);
    t_true("tangential: both daughters on the boundary", fx_on_boundary(cx, div.a) && fx_on_boundary(cx, div.b));
    int kept = 1;
    uint32_t nold = 0, j = 0;
    for (uint32_t f = 0; f < nb0; f++) {
      const uint32_t *v = b0 + 3 * f;
      if (v[0] == c || v[1] == c || v[2] == c) continue;
      nold++;
      while (j < nb1 && fx_u3cmp(b1 + 3 * j, v) < 0) j++;
      kept &= j < nb1 && !fx_u3cmp(b1 + 3 * j, v);
    }
    t_true("tangential: every boundary face not through c kept", kept);
    t_true("tangential: the boundary gains two faces", nb1 == nb0 + 2);
  } else {
    for (int k = 0; k < 3; k++) {
      double u = d[k] / len, xc = old.x[3 * c + k];
      if (!expect_surface) {
        err = fmax(err, fabs(cx->x[3 * c + k] - (xc + div.eps * u)));
        err = fmax(err, fabs(cx->x[3 * div.b + k] - (xc - div.eps * u)));
      } else {
        err = fmax(err, fabs(cx->x[3 * c + k] - xc)); /* a stays on the surface */
      }
    }
    t_check("daughter positions (a = c + eps d, b = c - eps d; surface: a = c)", err, 1e-15);
    /* b strictly inside: not on the boundary */
    t_true("daughter b is not on the boundary", !fx_on_boundary(cx, div.b));
    if (!expect_surface) t_true("daughter a is not on the boundary", !fx_on_boundary(cx, div.a));
    t_true("boundary faces unchanged", nb0 == nb1 && !memcmp(b0, b1, 3 * (size_t)nb0 * sizeof *b0));
  }
  t_true("eps > 0", div.eps > 0);
  int adjacent = 0; /* "the new cells are neighbours" (§3.1.1) */
  for (uint32_t t = 0; t < cx->nt && !adjacent; t++) {
    const uint32_t *v = cx->tet + 4 * t;
    int ha = v[0] == div.a || v[1] == div.a || v[2] == div.a || v[3] == div.a;
    int hb = v[0] == div.b || v[1] == div.b || v[2] == div.b || v[3] == div.b;
    adjacent = ha && hb;
  }
  t_true("the daughters are neighbours (share an edge)", adjacent);
  /* kept tets identical and in order; removed = exactly the tets around c */
  int same = 1;
  uint8_t *kept = calloc(old.nt, 1);
  uint32_t nnew = 0, prev = 0;
  for (uint32_t t = 0; t < cx->nt; t++) {
    uint32_t f = div.tet_from[t];
    if (f == SESSILE_SDS_TOPO_NEW_TET) {
      nnew++;
      continue;
    }
    same &= f < old.nt && !memcmp(cx->tet + 4 * t, old.tet + 4 * f, 4 * sizeof *cx->tet) && (t == 0 || f >= prev);
    kept[f] = 1, prev = f;
  }
  for (uint32_t t = 0; t < old.nt; t++) {
    const uint32_t *v = old.tet + 4 * t;
    int has = v[0] == c || v[1] == c || v[2] == c || v[3] == c;
    same &= kept[t] == !has;
  }
  t_true("other tets unchanged, removed = the star of c", same);
  t_true("new tets counted", nnew == div.n_added && cx->nt == old.nt - div.n_removed + div.n_added);
  /* the new tets all contain a daughter? not required; they fill the hull */
  free(kept), free(b0), free(b1), free(div.tet_from);
  sessile_sds_topo_complex_free(&old);
  return dt;
}

int main(void) {
  sessile_sds_topo_complex cx = {0};
  fx_ball(3, 0.005, &cx);
  printf("ball: %u vertices, %u tets\n", cx.nv, cx.nt);
  /* interior cell nearest the centre, surface cell = vertex 0 (icosphere) */
  uint32_t ci = 0;
  double best = INFINITY;
  for (uint32_t v = 0; v < cx.nv; v++) {
    double r = sqrt(cx.x[3 * v] * cx.x[3 * v] + cx.x[3 * v + 1] * cx.x[3 * v + 1] + cx.x[3 * v + 2] * cx.x[3 * v + 2]);
    if (r < best) best = r, ci = v;
  }
  t_true("the central vertex is interior", !fx_on_boundary(&cx, ci));
  t_true("vertex 0 is on the surface", fx_on_boundary(&cx, 0));
  double d1[3] = {1, 0.3, -0.2};
  divide_checked(&cx, ci, d1, 0, 1);
  /* surface cell: tangential, outward and inward directions */
  /* on the unit icosphere a vertex's position is its outward normal */
  double *p0 = cx.x, *p1 = cx.x + 3, *p2 = cx.x + 6;
  double tang[3] = {-p0[1], p0[0], 0}, outw[3] = {p1[0], p1[1], p1[2]}, inw[3] = {-p2[0], -p2[1], -p2[2]};
  if (fabs(tang[0]) + fabs(tang[1]) < 1e-9) tang[0] = 1, tang[1] = tang[2] = 0;
  int seen = tangential_seen;
  divide_checked(&cx, 0, tang, 1, 1);
  t_true("a tangent direction splits a surface cell along the surface", tangential_seen == seen + 1);
  divide_checked(&cx, 1, outw, 1, 1); /* vertex 1 is an icosphere vertex too */
  divide_checked(&cx, 2, inw, 1, 1);
  t_true("outward and inward directions split across the surface", tangential_seen == seen + 1);
  /* the cone fallback, as when TetGen needs a Steiner point (injected) */
  tg_fault_inject = 4;
  double d2[3] = {0.2, -1, 0.5};
  uint32_t ci2 = cx.tet[4 * 7 + 0];
  for (uint32_t v = 0; v < cx.nv; v++)
    if (!fx_on_boundary(&cx, v)) {
      ci2 = v;
      break;
    }
  divide_checked(&cx, ci2, d2, 0, 1);
  divide_checked(&cx, 3, d2, 1, 1);
  tg_fault_inject = 0;
  /* random divisions (interior and surface), the seed fixed */
  uint64_t rng = sessile_rng_stream(13, 1);
  double tsum_i = 0, tsum_s = 0;
  int ni = 0, ns = 0;
  for (int k = 0; k < 60; k++) {
    uint32_t c = (uint32_t)(sessile_rng_uniform(&rng) * cx.nv) % cx.nv;
    double d[3] = {sessile_rng_normal(&rng), sessile_rng_normal(&rng), sessile_rng_normal(&rng)};
    int surf = fx_on_boundary(&cx, c);
    double dt = divide_checked(&cx, c, d, surf, 0);
    if (surf)
      tsum_s += dt, ns++;
    else
      tsum_i += dt, ni++;
  }
  /* the tangential split may fall back to the inward one (no clean fan):
   * rare on a well-shaped ball */
  printf("tangential splits: %d of %d surface divisions with a tangent direction\n", tangential_seen,
         tangential_expected);
  t_true("at least 90%% of tangent-direction surface divisions split along the surface",
         tangential_seen >= 0.9 * tangential_expected);
  printf("random divisions: %d interior, mean %.2f ms; %d surface, mean %.2f ms; now %u vertices, %u tets\n", ni,
         1e3 * tsum_i / (ni ? ni : 1), ns, 1e3 * tsum_s / (ns ? ns : 1), cx.nv, cx.nt);
  /* a sliver elsewhere does not count against a division
   * (sessile_sds_topo_check_kept): push an interior cell far through its
   * neighbours so that some of its tets invert, divide the interior cell
   * farthest from it; the strict check fails on the old slivers, the kept
   * check passes; a daughter pushed out through its own new tets fails it */
  {
    uint32_t vs = UINT32_MAX, vc = UINT32_MAX;
    for (uint32_t v = 0; v < cx.nv && vs == UINT32_MAX; v++)
      if (!fx_on_boundary(&cx, v)) vs = v;
    double far = -1;
    for (uint32_t v = 0; v < cx.nv; v++) {
      double q2 = 0;
      for (int k = 0; k < 3; k++) q2 += (cx.x[3 * v + k] - cx.x[3 * vs + k]) * (cx.x[3 * v + k] - cx.x[3 * vs + k]);
      if (!fx_on_boundary(&cx, v) && q2 > far) far = q2, vc = v;
    }
    sessile_sds_topo_complex bad;
    fx_copy(&cx, &bad);
    for (int k = 0; k < 3; k++) bad.x[3 * vs + k] *= -1; /* through the centre: its tets turn inside out */
    uint32_t ninv = 0;
    for (uint32_t t = 0; t < bad.nt; t++)
      ninv += !(sessile_sds_topo_volume(bad.x + 3 * bad.tet[4 * t], bad.x + 3 * bad.tet[4 * t + 1],
                                        bad.x + 3 * bad.tet[4 * t + 2], bad.x + 3 * bad.tet[4 * t + 3]) > 0);
    printf("cell %u pushed through the centre: %u tets inverted; dividing cell %u, %.2f u away\n", vs, ninv, vc,
           sqrt(far));
    sessile_sds_topo_complex before;
    fx_copy(&bad, &before);
    double dd[3] = {0.3, 1, -0.4};
    sessile_sds_topo_division dv;
    t_ok("divide beside the slivers", sessile_sds_topo_divide(&bad, vc, dd, 0.0, &dv));
    t_true("the strict check fails on the old slivers",
           ninv > 0 && sessile_sds_topo_check(bad.nv, bad.x, bad.nt, bad.tet, 0.0, NULL) != SESSILE_OK);
    t_true("the kept check passes: every inverted tet was inverted before",
           sessile_sds_topo_check_kept(before.x, before.nt, before.tet, &bad, dv.tet_from) == SESSILE_OK);
    for (int k = 0; k < 3; k++) bad.x[3 * dv.b + k] = 3 * bad.x[3 * dv.b + k] - 2 * bad.x[3 * dv.a + k];
    t_true("a daughter pushed out through its new tets fails the kept check",
           sessile_sds_topo_check_kept(before.x, before.nt, before.tet, &bad, dv.tet_from) == SESSILE_ERR_INTERNAL);
    free(dv.tet_from);
    sessile_sds_topo_complex_free(&bad), sessile_sds_topo_complex_free(&before);
  }
  /* bad input */
  sessile_sds_topo_division div;
  double z[3] = {0, 0, 0};
  t_true("zero direction refused", sessile_sds_topo_divide(&cx, 3, z, 0, &div) == SESSILE_ERR_USAGE);
  t_true("cell out of range refused", sessile_sds_topo_divide(&cx, cx.nv, d1, 0, &div) == SESSILE_ERR_USAGE);
  sessile_sds_topo_complex_free(&cx);
  return t_finish(NULL);
}
