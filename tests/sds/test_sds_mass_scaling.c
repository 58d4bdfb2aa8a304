/* Selective mass scaling (docs/sds.md, "Mass scaling"): a cell whose own
 * stable bound h_c is below mass_scaling_dt H moves with the inertia alpha m,
 * alpha = (w2 H^2 + 2 gam H) / 4, its forces unchanged.  Checked on a ball
 * whose cells differ in size (radii from a level-2 icosphere's edges, some
 * shrunk), against what scaling is for and what it must not change:
 *   1. the scheme is stable at a step where it is not without it: fixed steps
 *      of 0.8 H, H three times the unscaled bound, blow up unscaled (the
 *      kinetic energy grows by 1e6) and stay bounded scaled (host reference);
 *   2. the host's bound is H exactly when a cell is scaled, alpha is 1 where
 *      a cell's bound is H or more, and scaling by a tiny H (no cell scaled)
 *      changes no bit of the device's step;
 *   3. the device's advance step equals the host's step with the same dt
 *      (1e-12 of the speed), and takes 0.8 H when asked for more; batches
 *      (the loop on the device) give the advance steps bit for bit;
 *   4. the rest state is the same: the ball relaxed from the same start,
 *      scaled and not, ends with the same distance between every two cells
 *      (1e-6 of a radius; the drag is -c m v against the inertia alpha m, so
 *      the rigid drift may differ): scaling changes the transients only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/sds/sds.h"
#include "sessile/sds/sds_batch.h"
#include "testutil.h"

/* A ball of cells of different sizes: every fifth cell at 0.6 of its radius
 * (a fifth of the mass: its bound well below the others'), masses from the
 * radii. */
static void ball(const double ctr[3], sessile_sds *o) {
  t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, o));
  for (uint32_t c = 0; c < o->ncells; c += 5) {
    o->r[c] *= 0.6;
    o->m[c] = sessile_sds_mass(1.0, o->r[c]);
  }
}

static void params_of(sessile_sds_params *p) {
  sessile_sds_params_default(p);
  p->gravity = 0, p->damp_visc = 0.05, p->damp_vol = 0.001, p->self_collide = 0;
  p->dt_max = 1, p->max_move = 1; /* neither caps the steps here: the bound does */
}

static double kinetic(const sessile_sds *o) {
  double e = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    const double *v = o->v + 3 * (size_t)c;
    e += 0.5 * o->m[c] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return e;
}

/* Every cell moved along its radius by 3 % of it, at rest: the springs ring. */
static void perturb(sessile_sds *o) {
  for (uint32_t c = 0; c < o->ncells; c++) {
    double *x = o->x + 3 * (size_t)c, s = 1 + 0.03 * ((c * 2654435761u >> 7) % 3 - 1.0);
    for (int i = 0; i < 3; i++) x[i] *= s;
  }
}

int main(int argc, char **argv) {
  int fp32 = 0;
  sessile_gpu *g = t_gpu_args(argc, argv, &fp32);
  (void)fp32;
  const double ctr[3] = {0, 0, 0};
  sessile_sds o = {0};
  ball(ctr, &o);
  sessile_sds_params p;
  params_of(&p);
  double h0 = sessile_sds_stable_dt(&o, &p), H = 3 * h0;
  printf("unscaled bound %.6g s; H = %.6g s\n", h0, H);
  /* 2. the bound and alpha */
  double *al = t_dalloc(o.ncells);
  p.mass_scaling_dt = H;
  t_must("inertia", sessile_sds_inertia(&o, &p, al));
  uint32_t scaled = 0;
  for (uint32_t c = 0; c < o.ncells; c++) scaled += al[c] > 1;
  double hs = sessile_sds_stable_dt(&o, &p);
  char what[200];
  snprintf(what, sizeof what, "some cells scaled, not all (%u of %u)", scaled, o.ncells);
  t_true(what, scaled > 0 && scaled < o.ncells);
  snprintf(what, sizeof what, "the scaled bound is H (%.9g against %.9g; rel)", hs, H);
  t_check(what, fabs(hs - H) / H, 1e-15);
  /* alpha is 1 exactly where a cell's own bound reaches H: with H at the
   * unscaled bound itself no cell is below it */
  p.mass_scaling_dt = h0;
  t_must("inertia at h0", sessile_sds_inertia(&o, &p, al));
  int ones = 1;
  for (uint32_t c = 0; c < o.ncells; c++) ones &= al[c] == 1.0;
  t_true("H at the unscaled bound: every alpha is 1", ones);
  /* 1. stability at 0.8 H, host reference, fixed steps */
  double e_end[2] = {0, 0}, e0 = 0;
  for (int sc = 0; sc < 2; sc++) {
    sessile_sds q = {0};
    ball(ctr, &q);
    perturb(&q);
    p.mass_scaling_dt = sc ? H : 0;
    double emax = 0;
    for (int k = 0; k < 400; k++) {
      double mv = sessile_sds_step_ref(&q, &p, 0.8 * H);
      double e = kinetic(&q);
      if (k == 0) e0 = e;
      if (!(e == e) || !(mv == mv)) {
        emax = INFINITY;
        break;
      }
      emax = fmax(emax, e);
    }
    e_end[sc] = emax;
    sessile_sds_free(&q);
  }
  printf("kinetic energy over 400 steps of 0.8 H: first step %.3g, largest %.3g unscaled, %.3g scaled\n", e0,
         e_end[0], e_end[1]);
  t_true("unscaled, 0.8 H is beyond the scheme's stable step (energy x 1e6 or non-finite)", e_end[0] > 1e6 * e0);
  t_true("scaled, the same steps stay bounded (energy at most 10 x the first step's)", e_end[1] <= 10 * e0);
  /* 3. the device's advance step against the host's */
  {
    sessile_sds h = {0}, d = {0};
    ball(ctr, &h), ball(ctr, &d);
    perturb(&h), perturb(&d);
    p.mass_scaling_dt = H;
    sessile_sds_gpu *s = NULL;
    t_must("gpu create", sessile_sds_gpu_create(g, &h, &p, &s));
    double bd = 0;
    t_must("gpu bound", sessile_sds_gpu_stable_dt(s, &bd));
    snprintf(what, sizeof what, "the device's scaled bound = the host's (%.9g; rel)", bd);
    t_check(what, fabs(bd - hs) / hs, 1e-12);
    double step = 10 * H, t = 0;
    t_must("advance", sessile_sds_gpu_advance(s, 1, &step, &t));
    snprintf(what, sizeof what, "an advance asked for 10 H takes 0.8 H (%.9g; rel)", t);
    t_check(what, fabs(t - p.stable_safety * H) / H, 1e-12);
    t_must("download", sessile_sds_gpu_download(s, &d));
    sessile_sds_step_ref(&h, &p, t);
    double vmax = 0;
    for (size_t k = 0; k < 3 * (size_t)h.ncells; k++) vmax = fmax(vmax, fabs(h.v[k]));
    t_check("device step = host step with scaling (|dv| / max |v|)", t_maxdiff(d.v, h.v, 3 * (size_t)h.ncells) / vmax,
            1e-12);
    t_check("  positions (|dx| / dt max |v|)", t_maxdiff(d.x, h.x, 3 * (size_t)h.ncells) / (t * vmax), 1e-9);
    sessile_sds_gpu_destroy(s);
    sessile_sds_free(&h), sessile_sds_free(&d);
  }
  /* 3'. the loop on the device: a batch of steps with scaling gives the
   * advance steps bit for bit (both read the inertia from the stable kernel) */
  {
    sessile_sds a = {0}, b = {0};
    ball(ctr, &a), ball(ctr, &b);
    perturb(&a), perturb(&b);
    p.mass_scaling_dt = H;
    sessile_sds_gpu *sa = NULL, *sb = NULL;
    t_must("gpu create", sessile_sds_gpu_create(g, &a, &p, &sa));
    t_must("gpu create", sessile_sds_gpu_create(g, &a, &p, &sb));
    double st = H, t = 0;
    t_must("advance", sessile_sds_gpu_advance(sa, 20, &st, &t));
    sessile_sds_batch bt = {.steps = 20, .t_stop = INFINITY, .time = 0, .dt = H};
    uint32_t done = 0;
    while (done < 20) {
      bt.steps = 20 - done;
      t_must("batch", sessile_sds_gpu_batch(sb, &bt));
      done += bt.done;
    }
    t_must("download", sessile_sds_gpu_download(sa, &a));
    t_must("download", sessile_sds_gpu_download(sb, &b));
    size_t n3 = 3 * (size_t)a.ncells;
    snprintf(what, sizeof what, "20 steps with scaling: batches = advance, bit for bit (t = %.6g s)", t);
    t_true(what, t == bt.time && st == bt.dt && !memcmp(a.x, b.x, n3 * sizeof *a.x) &&
                     !memcmp(a.v, b.v, n3 * sizeof *a.v));
    sessile_sds_gpu_destroy(sa), sessile_sds_gpu_destroy(sb);
    sessile_sds_free(&a), sessile_sds_free(&b);
  }
  /* 2'. a tiny H scales no cell: the device's step, bit for bit, as without */
  {
    sessile_sds a = {0}, b = {0};
    ball(ctr, &a), ball(ctr, &b);
    perturb(&a), perturb(&b);
    sessile_sds_gpu *s0 = NULL, *s1 = NULL;
    p.mass_scaling_dt = 0;
    t_must("gpu create", sessile_sds_gpu_create(g, &a, &p, &s0));
    p.mass_scaling_dt = 1e-9;
    t_must("gpu create", sessile_sds_gpu_create(g, &a, &p, &s1));
    double st0 = h0, st1 = h0, t0 = 0, t1 = 0;
    t_must("advance", sessile_sds_gpu_advance(s0, 5, &st0, &t0));
    t_must("advance", sessile_sds_gpu_advance(s1, 5, &st1, &t1));
    t_must("download", sessile_sds_gpu_download(s0, &a));
    t_must("download", sessile_sds_gpu_download(s1, &b));
    size_t n3 = 3 * (size_t)a.ncells;
    t_true("H below every bound: five advance steps change no bit",
           t0 == t1 && !memcmp(a.x, b.x, n3 * sizeof *a.x) && !memcmp(a.v, b.v, n3 * sizeof *a.v));
    sessile_sds_gpu_destroy(s0), sessile_sds_gpu_destroy(s1);
    sessile_sds_free(&a), sessile_sds_free(&b);
  }
  /* 4. the same rest state: the ball, its small cells pulling on the rest,
   * relaxed from the same start */
  {
    const double up[3] = {0, 0, 0};
    sessile_sds r[2] = {{0}, {0}};
    double tend[2] = {0, 0};
    for (int sc = 0; sc < 2; sc++) {
      ball(up, &r[sc]);
      sessile_sds_params q;
      params_of(&q);
      q.damp_visc = 2, q.max_move = 0.05;
      q.mass_scaling_dt = sc ? H : 0;
      sessile_sds_gpu *s = NULL;
      t_must("gpu create", sessile_sds_gpu_create(g, &r[sc], &q, &s));
      double step = q.dt;
      while (tend[sc] < 30) t_must("advance", sessile_sds_gpu_advance(s, 200, &step, &tend[sc]));
      t_must("download", sessile_sds_gpu_download(s, &r[sc]));
      sessile_sds_gpu_destroy(s);
    }
    double rmin = INFINITY, vmax = 0;
    for (uint32_t c = 0; c < r[0].ncells; c++) rmin = fmin(rmin, r[0].r[c]);
    for (int sc = 0; sc < 2; sc++)
      for (size_t k = 0; k < 3 * (size_t)r[sc].ncells; k++) vmax = fmax(vmax, fabs(r[sc].v[k]));
    printf("settled: t = %.2f and %.2f s, largest speed %.3g u/s\n", tend[0], tend[1], vmax);
    t_check("settled: both at rest (largest speed, u/s)", vmax, 1e-7);
    /* the shape: every distance between two cells (the drag is -c m v while
     * the inertia is alpha m, so a scaled ball's rigid creep may differ) */
    double dd = 0;
    for (uint32_t a = 0; a < r[0].ncells; a++) {
      for (uint32_t b = a + 1; b < r[0].ncells; b++) {
        double l[2];
        for (int sc = 0; sc < 2; sc++) {
          const double *xa = r[sc].x + 3 * (size_t)a, *xb = r[sc].x + 3 * (size_t)b;
          l[sc] = sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                       (xa[2] - xb[2]) * (xa[2] - xb[2]));
        }
        dd = fmax(dd, fabs(l[0] - l[1]));
      }
    }
    t_check("the same rest shape scaled and not (largest change of a cell-cell distance / smallest radius)",
            dd / rmin, 1e-6);
    sessile_sds_free(&r[0]), sessile_sds_free(&r[1]);
  }
  free(al);
  sessile_sds_free(&o);
  return t_finish(g);
}
