/* The per-vertex growth kernels (normals, probe, translocate, grow, and the
 * chained step) against their C references, closed forms and invariants.
 *
 * Tolerances (fp64 contexts; --fp32 multiplies them as stated in `tol`):
 *  - normals: 1e-14 absolute on unit vectors (same sums in the same order;
 *    only sqrt/division rounding may differ by an ulp).
 *  - probe vs reference: 1e-13 relative; vs the closed form on a linear field
 *    (P1 interpolation is exact for linear fields): 1e-12 relative.
 *  - translocation GPU vs parallel reference: 1e-12 after 5 passes; sum
 *    conservation with no clamp active: 1e-13 relative per pass.
 *  - growth: Chindapol values vs the formula 1e-15 relative; GPU lengths and
 *    positions vs reference 1e-13 (double pow in the kernel is an
 *    atanh/Taylor evaluation, ~1e-16 relative, against libm's pow);
 *    Halichondrid directions vs reference 1e-14 (this can only hold when the
 *    GPU's random vectors equal the reference's: a different r moves a
 *    direction by ~R = 0.02).
 *  - radiate sphere in a uniform field: every vertex moves by the same g
 *    along its normal (1e-13 relative); the new radii's spread / mean below
 *    g emax^2 / (2 R) (area-weighted normals of an icosphere deviate from
 *    radial by a small angle e, which changes the radius only by ~g e^2 / 2;
 *    emax is measured). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/growth_ref.h"
#include "shapes.h"
#include "testutil.h"

static sessile_la *la;
static sessile_growth_gpu *gg;
static double tolx = 1; /* tolerance multiplier: 1 for fp64, large for fp32 */

static double maxabs(const double *a, const double *b, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) {
    double d = fabs(a[i] - b[i]);
    if (!(d <= m)) m = d;
  }
  return m;
}
static double tol(double fp64_tol, double fp32_tol) { return tolx == 1 ? fp64_tol : fp32_tol; }

/* The test box: 0.25 cm cells over [0,8] x [0,8] x [0,7]. */
static const sessile_box box = {.origin = {0, 0, 0}, .h = 0.25, .n = {33, 33, 29}};

static sessile_vec *field_vec(const double *f) {
  sessile_vec *v = NULL;
  t_must("vec_create", sessile_vec_create(la, sessile_box_nodes(&box), &v));
  t_must("vec_upload", sessile_vec_upload(v, f));
  return v;
}

/* A smooth, non-trivial nutrient field in [0, 1]. */
static void smooth_field(double *f) {
  for (uint32_t i = 0; i < sessile_box_nodes(&box); i++) {
    double p[3];
    sessile_box_node_pos(&box, i, p);
    f[i] = 0.5 + 0.25 * sin(0.7 * p[0] + 0.3) * cos(0.5 * p[1]) + 0.2 * tanh(0.4 * (p[2] - 3));
  }
}

static void test_normals(const sessile_surface *s) {
  double *ref = t_dalloc(3 * s->nv), *gpu = t_dalloc(3 * s->nv);
  sessile_surface_normals(s, ref);
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, s));
  t_must("normals", sessile_growth_gpu_normals(gg, gpu));
  t_check("normals: GPU vs sessile_surface_normals (abs)", maxabs(gpu, ref, 3 * s->nv),
          tol(1e-14, 1e-6));
  free(ref), free(gpu);
}

static void test_probe_and_step(const sessile_surface *s) {
  uint32_t nv = s->nv, nodes = sessile_box_nodes(&box);
  double *f = t_dalloc(nodes), *nrm = t_dalloc(3 * nv);
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.translocate_passes = 0;
  double *pos = t_dalloc(3 * nv), *probed = t_dalloc(nv), *ref = t_dalloc(nv);
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, s));

  /* Linear field: the closed form (1/S) sum_k w_k (a + b.x + d_k o b.N). */
  const double a0 = 0.2, bb[3] = {0.03, -0.02, 0.05};
  for (uint32_t i = 0; i < nodes; i++) {
    double q[3];
    sessile_box_node_pos(&box, i, q);
    f[i] = a0 + bb[0] * q[0] + bb[1] * q[1] + bb[2] * q[2];
  }
  sessile_vec *v = field_vec(f);
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, probed, NULL, NULL));
  sessile_surface_normals(s, nrm);
  for (uint32_t i = 0; i < nv; i++) {
    double bx = 0, bn = 0, sum = 0;
    for (int q = 0; q < 3; q++) bx += bb[q] * s->pos[3 * i + q], bn += bb[q] * nrm[3 * i + q];
    for (uint32_t k = 0; k < p.probe_samples; k++) {
      double d = (double)k / (p.probe_samples - 1);
      sum += (a0 + bx + d * p.probe_offset * bn) / (20 * d + 1);
    }
    ref[i] = sum / p.probe_samples;
  }
  t_check("probe on a linear field vs closed form (rel)", t_relerr(probed, ref, nv), tol(1e-12, 1e-5));
  /* The flux probe is exact on linear fields: (4 c(d) - c(2d)) / (2d) with
   * c(s) = a + s b.N is (3a + 2 d b.N) / (2d), over flux_ref, floored at 0. */
  p.probe_flux = 1;
  p.probe_distance = 0.3;
  p.flux_ref = 0.04;
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, probed, NULL, NULL));
  for (uint32_t i = 0; i < nv; i++) {
    double a = a0, bn = 0;
    for (int q = 0; q < 3; q++) a += bb[q] * s->pos[3 * i + q], bn += bb[q] * nrm[3 * i + q];
    ref[i] = fmax((3 * a + 2 * p.probe_distance * bn) / (2 * p.probe_distance) / p.flux_ref, 0);
  }
  t_check("flux probe on a linear field vs closed form (rel)", t_relerr(probed, ref, nv), tol(1e-12, 1e-5));
  sessile_growth_ref_probe_flux(&box, s->pos, nrm, nv, f, p.probe_distance, p.flux_ref, ref);
  t_check("flux probe GPU vs reference (rel)", t_relerr(probed, ref, nv), tol(1e-13, 1e-5));
  p.probe_flux = 0;
  sessile_vec_destroy(v);

  /* Smooth field: GPU vs reference for every output of the chained step,
   * with 3 translocation passes and Halichondrid directions. */
  smooth_field(f);
  v = field_vec(f);
  p.translocate_passes = 3;
  p.t_give = 0.04;
  p.halichondrid = 1;
  p.l_max = 0.05;
  double *tr = t_dalloc(nv), *len = t_dalloc(nv), *rpos = t_dalloc(3 * nv), *rprobed = t_dalloc(nv),
         *rtr = t_dalloc(nv), *rlen = t_dalloc(nv), *dir = t_dalloc(3 * nv), *rdir = t_dalloc(3 * nv);
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 42, 7, pos, probed, tr, len));
  t_must("ref step", sessile_growth_ref_step(&box, s, f, &p, 42, 7, rpos, rprobed, rtr, rlen));
  t_check("step: probed GPU vs reference (rel)", t_relerr(probed, rprobed, nv), tol(1e-13, 1e-5));
  t_check("step: translocated GPU vs reference (rel)", t_relerr(tr, rtr, nv), tol(1e-12, 1e-5));
  t_check("step: growth length GPU vs reference (rel)", t_relerr(len, rlen, nv), tol(1e-13, 1e-5));
  t_check("step: new positions GPU vs reference (abs, cm)", maxabs(pos, rpos, 3 * nv), tol(1e-13, 1e-5));
  {
    /* the same chain with the flux probe (no upper clamp in translocation) */
    sessile_growth_params q = p;
    q.probe_flux = 1;
    q.probe_distance = 0.25;
    q.flux_ref = 0.05;
    q.ceiling = 5.0;
    double *fp = t_dalloc(3 * nv), *rfp = t_dalloc(3 * nv), *ft = t_dalloc(nv), *rft = t_dalloc(nv);
    t_must("step", sessile_growth_gpu_step(gg, &box, v, &q, 42, 7, fp, NULL, ft, NULL));
    t_must("ref step", sessile_growth_ref_step(&box, s, f, &q, 42, 7, rfp, NULL, rft, NULL));
    t_check("flux step: translocated GPU vs reference (rel)", t_relerr(ft, rft, nv), tol(1e-12, 1e-5));
    t_check("flux step: new positions GPU vs reference (abs, cm)", maxabs(fp, rfp, 3 * nv), tol(1e-13, 1e-5));
    double top = 0;
    for (uint32_t i = 0; i < nv; i++) top = fmax(top, fp[3 * i + 2]);
    t_check("flux step: no vertex above the ceiling (cm)", fmax(top - q.ceiling, 0), 0);
    free(fp), free(rfp), free(ft), free(rft);
  }
  /* Directions: the random vectors themselves. */
  t_must("directions", sessile_growth_gpu_directions(gg, dir));
  sessile_growth_ref_grow(&box, s->pos, nrm, nv, rtr, &p, 42, 7, rpos, rlen, rdir);
  t_check("Halichondrid directions GPU vs reference (abs)", maxabs(dir, rdir, 3 * nv), tol(1e-14, 1e-6));
  /* Chindapol lengths from the GPU's own translocated values. */
  double e = 0;
  for (uint32_t i = 0; i < nv; i++) {
    double g = sessile_growth_chindapol(&p, tr[i]);
    if (!(tr[i] > p.nutrient_threshold && g > p.growth_threshold)) g = 0;
    double d = fabs(len[i] - g) / (fabs(g) + 1e-300);
    if (len[i] != g && !(d <= e)) e = d;
  }
  t_check("GPU growth length vs g(C_translocated) (rel)", e, tol(1e-13, 1e-5));
  uint32_t grew = 0;
  for (uint32_t i = 0; i < nv; i++) grew += len[i] > 0;
  t_true("some vertices grew", grew > 0);

  /* Determinism and seeds. */
  double *pos2 = t_dalloc(3 * nv);
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 42, 7, pos2, NULL, NULL, NULL));
  t_true("Halichondrid: same seed and iteration -> bitwise identical positions",
         memcmp(pos, pos2, 3 * nv * sizeof *pos) == 0);
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 43, 7, pos2, NULL, NULL, NULL));
  t_true("Halichondrid: different seeds -> different positions", maxabs(pos, pos2, 3 * nv) > 1e-6);
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 42, 8, pos2, NULL, NULL, NULL));
  t_true("Halichondrid: different iterations -> different positions", maxabs(pos, pos2, 3 * nv) > 1e-6);

  sessile_vec_destroy(v);
  free(f), free(nrm), free(pos), free(pos2), free(probed), free(ref), free(tr), free(len),
      free(rpos), free(rprobed), free(rtr), free(rlen), free(dir), free(rdir);
}

/* How the probe average depends on S (printed for docs/growth.md): the
 * average of S samples tends to the integral of w(d) c(d) over [0, 1] as S
 * grows; report each S's max relative distance from S = 1025. */
static void measure_samples(const sessile_surface *s) {
  uint32_t nv = s->nv;
  double *f = t_dalloc(sessile_box_nodes(&box)), *nrm = t_dalloc(3 * nv), *ref = t_dalloc(nv), *a = t_dalloc(nv);
  smooth_field(f);
  sessile_surface_normals(s, nrm);
  /* W_S = (1/S) sum_k w(d_k): the probe of a uniform field c = 1. */
#define WSUM(S, out) do { out = 0; for (uint32_t k = 0; k < (S); k++) out += 1.0 / (20.0 * k / ((S) - 1) + 1); out /= (S); } while (0)
  double wref, ws;
  WSUM(1025u, wref);
  sessile_growth_ref_probe(&box, s->pos, nrm, nv, f, 0.1, 1025, ref);
  for (uint32_t i = 0; i < nv; i++) ref[i] /= wref;
  const uint32_t ss[] = {2, 4, 8, 16, 32};
  for (size_t q = 0; q < sizeof ss / sizeof ss[0]; q++) {
    sessile_growth_ref_probe(&box, s->pos, nrm, nv, f, 0.1, ss[q], a);
    WSUM(ss[q], ws);
    for (uint32_t i = 0; i < nv; i++) a[i] /= ws;
    printf("MEASURE probe S=%u: weight sum W_S = %.4f (S=1025: %.4f); max relative difference of "
           "probe/W_S from S=1025: %.3e\n", ss[q], ws, wref, t_relerr(a, ref, nv));
  }
#undef WSUM
  free(f), free(nrm), free(ref), free(a);
}

static void test_random(void) {
  /* Uniforms in [0, 1): range, mean and per-component independence of the
   * hash (a 30000-sample mean has sd 0.29/sqrt(30000) = 0.0017). */
  double mn = 1, mx = 0, mean[3] = {0}, R = 0.02, rmax = 0;
  uint32_t n = 10000, same = 0;
  for (uint32_t v = 0; v < n; v++)
    for (uint32_t a = 0; a < 3; a++) {
      double u = sessile_growth_uniform(7, 3, v, a);
      mn = u < mn ? u : mn, mx = u > mx ? u : mx;
      mean[a] += u / n;
      double r = fabs(R * (2 * u - 1));
      rmax = r > rmax ? r : rmax;
      if (a && u == sessile_growth_uniform(7, 3, v, a - 1)) same++;
    }
  t_true("uniforms in [0, 1)", mn >= 0 && mx < 1);
  t_check("r components within [-R, R]: max|r| - R (<= 0)", rmax - R > 0 ? rmax - R : 0, 0);
  for (int a = 0; a < 3; a++) t_check("uniform mean - 0.5 (10000 samples, 6 sd)", fabs(mean[a] - 0.5), 0.0104);
  t_check("equal uniforms across components (of 20000)", same, 2);
  t_true("different seeds give different hashes",
         sessile_growth_hash(1, 0, 0, 0) != sessile_growth_hash(2, 0, 0, 0) &&
             sessile_growth_hash((uint64_t)1 << 32, 0, 0, 0) != sessile_growth_hash(0, 0, 0, 0));
}

static void test_chindapol(void) {
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.max_growth = 1e9; /* no clamp here: the formula alone (clampMG has its own check) */
  const double cs[] = {0.0, 0.1, 0.5, 1.0, 2.0};
  double e = 0;
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
    double c = cs[i], cn = c > 0 ? exp(p.kinetic_order * log(c)) : 0;
    double want = p.growth_rate * p.l_max * cn / (p.growth_constant + cn);
    double got = sessile_growth_chindapol(&p, c);
    double d = fabs(got - want) / (want > 0 ? want : 1);
    e = d > e ? d : e;
  }
  t_check("Chindapol g(C) vs Gr Lmax C^n / (K + C^n) (rel)", e, 1e-15);
  p.max_growth = 0.03;
  t_check("Chindapol clamps at maxgrowth", fabs(sessile_growth_chindapol(&p, 5.0) - 0.03), 0);
  t_check("Chindapol g(-1) = 0", fabs(sessile_growth_chindapol(&p, -1.0)), 0);
}

static void test_translocate(const sessile_surface *s) {
  uint32_t nv = s->nv, *off, *nbr;
  t_must("neighbours", sessile_surface_vertex_neighbours(s, &off, &nbr));
  double *c = t_dalloc(nv), *a = t_dalloc(nv), *b = t_dalloc(nv), *seq = t_dalloc(nv);
  /* Conservation with no clamp active: c in [0.1, 0.3], T = 0.02, N <= 6. */
  for (uint32_t i = 0; i < nv; i++) c[i] = 0.1 + 0.2 * sessile_growth_uniform(5, 0, i, 0);
  double s0 = 0, s1 = 0;
  for (uint32_t i = 0; i < nv; i++) s0 += c[i];
  t_must("sweep", sessile_growth_ref_translocate_sweep(off, nbr, nv, 0.02, 1.0, c, a));
  for (uint32_t i = 0; i < nv; i++) s1 += a[i];
  t_check("order-independent sweep conserves the sum (rel, no clamp)", fabs(s1 - s0) / s0, 1e-13);
  /* A sweep is 7 passes: a lone spike at a degree-N vertex loses 7 N T to
   * first order (T = 1e-6, second-order terms ~1e-12). */
  {
    double *spike = t_dalloc(nv), *out = t_dalloc(nv), T = 1e-6;
    uint32_t x = 17, N = off[x + 1] - off[x];
    spike[x] = 1;
    t_must("sweep", sessile_growth_ref_translocate_sweep(off, nbr, nv, T, 1.0, spike, out));
    double lose = SESSILE_TRANSLOCATE_SWEEP * N * T;
    t_check("sweep: a vertex of degree N loses 7 N T to first order (rel)",
            fabs((1 - out[x]) - lose) / lose, 1e-4);
    free(spike), free(out);
  }
  memcpy(seq, c, nv * sizeof *c);
  sessile_growth_ref_translocate_sequential(off, nbr, nv, 0.02, 1.0, seq);
  s1 = 0;
  for (uint32_t i = 0; i < nv; i++) s1 += seq[i];
  t_check("sequential translocation conserves the sum (rel, no clamp)", fabs(s1 - s0) / s0, 1e-13);

  /* GPU vs parallel reference through the step with a uniform field of
   * value chosen so probed = C0; compare 5 passes of a realistic field. */
  double *f = t_dalloc(sessile_box_nodes(&box)), *tr = t_dalloc(nv), *pr = t_dalloc(nv), *pos = t_dalloc(3 * nv);
  smooth_field(f);
  sessile_vec *v = field_vec(f);
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.translocate_passes = 5;
  p.t_give = 0.05;
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, s));
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, pr, tr, NULL));
  memcpy(a, pr, nv * sizeof *a);
  double cmax = sessile_growth_translocate_cmax(&p);
  for (int q = 0; q < 5; q++) {
    t_must("sweep", sessile_growth_ref_translocate_sweep(off, nbr, nv, p.t_give, cmax, a, b));
    memcpy(a, b, nv * sizeof *a);
  }
  t_check("translocation (5 sweeps) GPU vs order-independent reference (rel)", t_relerr(tr, a, nv), tol(1e-12, 1e-5));
  double gs = 0, ps = 0;
  for (uint32_t i = 0; i < nv; i++) gs += tr[i], ps += pr[i];
  t_check("GPU translocation conserves the probed sum (rel, no clamp on this field)", fabs(gs - ps) / ps,
          tol(1e-12, 1e-5));
  /* Parallel vs the paper's sequential form on this realistic field. */
  for (int passes = 1; passes <= 5; passes += 4) {
    memcpy(a, pr, nv * sizeof *a), memcpy(seq, pr, nv * sizeof *a);
    for (int q = 0; q < passes; q++) {
      t_must("sweep", sessile_growth_ref_translocate_sweep(off, nbr, nv, p.t_give, cmax, a, b));
      memcpy(a, b, nv * sizeof *a);
      sessile_growth_ref_translocate_sequential(off, nbr, nv, p.t_give, cmax, seq);
    }
    double mxd = 0, mean = 0, range_lo = 1, range_hi = 0, chg = 0;
    for (uint32_t i = 0; i < nv; i++) {
      double d = fabs(a[i] - seq[i]);
      mxd = d > mxd ? d : mxd;
      mean += d / nv;
      chg = fmax(chg, fabs(a[i] - pr[i]));
      range_lo = fmin(range_lo, pr[i]), range_hi = fmax(range_hi, pr[i]);
    }
    printf("MEASURE translocation T=%.2f, %d pass(es), %u vertices, probed in [%.3f, %.3f]: "
           "parallel vs sequential max|diff| %.3e, mean %.3e; max change by the parallel form %.3e\n",
           p.t_give, passes, nv, range_lo, range_hi, mxd, mean, chg);
  }
  /* translocate_mode = sequential: the step runs the paper's sweeps (seq
   * holds 5 of them from the same probed values) between probe and grow,
   * and its positions are the reference step's. */
  {
    double *rpos = t_dalloc(3 * nv), *rtr = t_dalloc(nv), *pos1 = t_dalloc(3 * nv);
    sessile_growth_params q = p;
    q.translocate_sequential = 1;
    t_must("step (sequential)", sessile_growth_gpu_step(gg, &box, v, &q, 1, 0, pos1, NULL, tr, NULL));
    t_check("sequential step: translocated = 5 sequential sweeps of the probed (rel)", t_relerr(tr, seq, nv),
            tol(1e-15, 1e-5));
    t_true("sequential step: differs from the parallel form", t_relerr(tr, a, nv) > 1e-3);
    t_must("ref step (sequential)", sessile_growth_ref_step(&box, s, f, &q, 1, 0, rpos, NULL, rtr, NULL));
    t_check("sequential step: reference translocated (rel)", t_relerr(rtr, seq, nv), tol(1e-15, 1e-5));
    t_check("sequential step: positions GPU vs reference (rel)", t_relerr(pos1, rpos, 3 * nv), tol(1e-14, 1e-5));
    t_true("sequential step: positions differ from the parallel step's", t_relerr(pos1, pos, 3 * nv) > 0);
    free(rpos), free(rtr), free(pos1);
  }
  sessile_vec_destroy(v);
  free(off), free(nbr), free(c), free(a), free(b), free(seq), free(f), free(tr), free(pr), free(pos);
}

/* Radiate growth of a sphere in a uniform field: all vertices move by the
 * same length along their normals. */
static void test_radiate_sphere(void) {
  sessile_surface s = {0};
  const double c[3] = {4.0, 4.0, 3.5};
  t_must("icosphere", sessile_surface_icosphere(4, 2.0, c, &s));
  uint32_t nv = s.nv, nodes = sessile_box_nodes(&box);
  double *f = t_dalloc(nodes), *pos = t_dalloc(3 * nv), *len = t_dalloc(nv), *nrm = t_dalloc(3 * nv);
  for (uint32_t i = 0; i < nodes; i++) f[i] = 0.8;
  sessile_vec *v = field_vec(f);
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.translocate_passes = 2;
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, &s));
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, NULL, NULL, len));
  sessile_surface_normals(&s, nrm);
  double g0 = len[0], dev_len = 0, dev_par = 0, rmin = 1e9, rmax = 0, rmean = 0, emax = 0;
  for (uint32_t i = 0; i < nv; i++) {
    /* angle between the area-weighted normal and the radial direction */
    double ru[3], rl = 0, cosang = 0;
    for (int q = 0; q < 3; q++) ru[q] = s.pos[3 * i + q] - c[q], rl += ru[q] * ru[q];
    for (int q = 0; q < 3; q++) cosang += ru[q] / sqrt(rl) * nrm[3 * i + q];
    emax = fmax(emax, acos(fmin(1.0, cosang)));
    dev_len = fmax(dev_len, fabs(len[i] - g0) / g0);
    double d[3], r2 = 0;
    for (int q = 0; q < 3; q++) {
      d[q] = pos[3 * i + q] - s.pos[3 * i + q];
      double x = pos[3 * i + q] - c[q];
      r2 += x * x;
    }
    for (int q = 0; q < 3; q++) dev_par = fmax(dev_par, fabs(d[q] - g0 * nrm[3 * i + q]) / g0);
    double r = sqrt(r2);
    rmin = fmin(rmin, r), rmax = fmax(rmax, r), rmean += r / nv;
  }
  /* |R u + g n| = sqrt(R^2 + 2 R g cos e + g^2) >= R + g - g e^2/2 (to
   * first order in g/R): the spread is bounded by g emax^2 / 2. */
  double spread_tol = (0.5 * g0 * emax * emax * 1.05 + 1e-12) / rmean;
  printf("   radiate: g = %.6e cm, new radius mean %.9f, spread %.3e, max normal angle %.3e rad\n",
         g0, rmean, rmax - rmin, emax);
  t_true("radiate: vertices grew (g > 0)", g0 > 0);
  t_check("radiate, uniform field: growth lengths equal (rel)", dev_len, tol(1e-13, 1e-5));
  t_check("radiate: displacement = g N (rel to g)", dev_par, tol(1e-12, 1e-4));
  t_check("radiate: new radius spread / mean (tol g emax^2/2 / R)", (rmax - rmin) / rmean,
          tolx == 1 ? spread_tol : 1e-5);

  /* Clamping: a sphere touching the box's x-max wall grows by maxgrowth. */
  const double c2[3] = {6.0, 4.0, 3.5};
  t_must("icosphere", sessile_surface_icosphere(3, 2.0, c2, &s));
  nv = s.nv;
  double *rpos = t_dalloc(3 * nv), *fl = t_dalloc(nodes);
  p.growth_rate = 100;
  p.max_growth = 0.3;
  p.translocate_passes = 0;
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, &s));
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, NULL, NULL, NULL));
  for (uint32_t i = 0; i < nodes; i++) fl[i] = 0.8;
  t_must("ref step", sessile_growth_ref_step(&box, &s, fl, &p, 1, 0, rpos, NULL, NULL, NULL));
  double mx[3], out = 0;
  uint32_t on_wall = 0;
  sessile_box_max(&box, mx);
  for (uint32_t i = 0; i < nv; i++)
    for (int q = 0; q < 3; q++) {
      double x = pos[3 * i + q];
      out = fmax(out, fmax(box.origin[q] - x, x - mx[q]));
      on_wall += x == mx[q];
    }
  t_check("clamping: distance outside the box after growth (<= 0)", out > 0 ? out : 0, 0);
  t_true("clamping: some vertices were clamped onto the x-max wall", on_wall > 0);
  t_check("clamping: GPU vs reference positions (abs, cm)", maxabs(pos, rpos, 3 * nv), tol(1e-13, 1e-5));

  /* Thresholds: a nutrient threshold above the field stops all growth. */
  p.nutrient_threshold = 0.9;
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, NULL, NULL, len));
  double moved = maxabs(pos, s.pos, 3 * nv), lsum = 0;
  for (uint32_t i = 0; i < nv; i++) lsum += len[i];
  t_check("Iroquois threshold above C: no vertex moves (abs, fp64 exact)", moved, tol(0, 1e-6));
  t_check("Iroquois threshold above C: all lengths 0", lsum, 0);
  p.nutrient_threshold = 0;
  p.growth_threshold = 1.0; /* above maxgrowth */
  t_must("step", sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, NULL, NULL, len));
  t_check("growth threshold above g: no vertex moves", maxabs(pos, s.pos, 3 * nv), tol(0, 1e-6));

  sessile_vec_destroy(v);
  sessile_surface_free(&s);
  free(f), free(pos), free(len), free(nrm), free(rpos), free(fl);
}

/* Timing (printed, never asserted): one step on 10242 vertices with a
 * 65x65x49 field. */
static void timing(void) {
  sessile_box b = {.origin = {0, 0, 0}, .h = 0.25, .n = {65, 65, 49}};
  sessile_surface s = {0};
  const double c[3] = {8.03, 7.98, 6.01};
  shape_radial(6, 5.0, c, bumps, &s);
  uint32_t nodes = sessile_box_nodes(&b), nv = s.nv;
  double *f = t_dalloc(nodes), *pos = t_dalloc(3 * nv), *rpos = t_dalloc(3 * nv);
  for (uint32_t i = 0; i < nodes; i++) {
    double q[3];
    sessile_box_node_pos(&b, i, q);
    f[i] = 0.5 + 0.4 * sin(0.3 * q[0]) * cos(0.2 * q[1]);
  }
  sessile_vec *v = NULL;
  t_must("vec", sessile_vec_create(la, nodes, &v));
  t_must("upload", sessile_vec_upload(v, f));
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.halichondrid = 1;
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, &s));
  double best = 1e30;
  for (int r = 0; r < 3; r++) {
    double t0 = sessile_wall_seconds();
    t_must("step", sessile_growth_gpu_step(gg, &b, v, &p, 3, 1, pos, NULL, NULL, NULL));
    best = fmin(best, sessile_wall_seconds() - t0);
  }
  double t0 = sessile_wall_seconds();
  t_must("ref step", sessile_growth_ref_step(&b, &s, f, &p, 3, 1, rpos, NULL, NULL, NULL));
  double tref = sessile_wall_seconds() - t0;
  t_check("10242-vertex step: GPU vs reference positions (abs, cm)", maxabs(pos, rpos, 3 * nv),
          tol(1e-13, 1e-5));
  printf("TIME growth step (normals, probe S=%u, %d translocation pass, Halichondrid grow), %u "
         "vertices, 65x65x49 field: GPU call %.4f s (best of 3, downloads included), host "
         "reference %.4f s\n", p.probe_samples, p.translocate_passes, nv, best, tref);
  sessile_vec_destroy(v);
  sessile_surface_free(&s);
  free(f), free(pos), free(rpos);
}

static void test_errors(void) {
  sessile_growth_params p;
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.t_give = 1.5;
  t_true("t_give 1.5 is a usage error", sessile_growth_params_check(&p) == SESSILE_ERR_USAGE);
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  p.probe_samples = 1;
  t_true("1 probe sample is a usage error", sessile_growth_params_check(&p) == SESSILE_ERR_USAGE);
  sessile_vec *v = NULL;
  t_must("vec", sessile_vec_create(la, 10, &v));
  double pos[3 * 642];
  sessile_growth_params_default(&p);
  p.probe_flux = 0; /* eq 6 unless a test says otherwise */
  t_true("field of the wrong size is a usage error",
         sessile_growth_gpu_step(gg, &box, v, &p, 1, 0, pos, NULL, NULL, NULL) == SESSILE_ERR_USAGE);
  sessile_vec_destroy(v);
}

int main(int argc, char **argv) {
  int prec = argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0;
  sessile_gpu *g = t_gpu(prec);
  if (sessile_gpu_info_of(g)->precision == 32) tolx = 1e6;
  t_must("la", sessile_la_create(g, &la));
  t_must("growth gpu", sessile_growth_gpu_create(la, &gg));
  sessile_surface s = {0};
  const double c[3] = {4.05, 3.95, 3.4};
  shape_radial(4, 2.2, c, bumps, &s);
  test_normals(&s);
  test_probe_and_step(&s);
  test_random();
  measure_samples(&s);
  test_chindapol();
  test_translocate(&s);
  test_radiate_sphere();
  test_errors();
  timing();
  sessile_surface_free(&s);
  sessile_growth_gpu_destroy(gg);
  sessile_la_destroy(la);
  return t_finish(g);
}
