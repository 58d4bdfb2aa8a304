/* SDS forces: the host reference is -grad E (central finite differences)
 * with every term on (springs, gravity, box, obstacle, attraction); the GPU
 * gather equals the host (damping on); an imported complex has zero force on
 * the GPU too; the inverted-tet kernel finds a constructed inversion; the
 * same input gives the same bytes after N steps, and follows the host's
 * integrator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "sessile/sds/sds.h"
#include "testutil.h"

static double potential(const sessile_sds *o, const sessile_sds_params *p) {
  sessile_sds_energy e;
  sessile_sds_energy_of(o, p, &e);
  return e.edge + e.vol + e.potential;
}

/* -grad E by central differences of step h in every coordinate. */
static void minus_grad_fd(sessile_sds *o, const sessile_sds_params *p, double h, size_t n3, double *out) {
  for (size_t k = 0; k < n3; k++) {
    double x0 = o->x[k];
    o->x[k] = x0 + h;
    double ep = potential(o, p);
    o->x[k] = x0 - h;
    double em = potential(o, p);
    o->x[k] = x0;
    out[k] = -(ep - em) / (2 * h);
  }
}


static double maxabs(const double *a, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
  return m;
}

/* A variant of the stiffness (the device holding o and p): the host's
 * forces = -grad E by central differences and other than the prototype's
 * f; the device's forces (damping on; texel and storage reads) and stable
 * bound = the host's; the bound other than the prototype's `bound0` unless
 * that is the same bound. */
static void variant(const char *what, sessile_sds *o, const sessile_sds_params *p, sessile_sds_gpu *sg,
                    const double *f, double bound0, int fp64) {
  size_t n3 = 3 * (size_t)o->ncells;
  double *fv = t_dalloc(n3), *fd = t_dalloc(n3), *fg = t_dalloc(n3), bg = 0;
  char m[160];
  sessile_sds_forces_ref(o, p, 0, fv);
  minus_grad_fd(o, p, 1e-6, n3, fd);
  snprintf(m, sizeof m, "%s: host forces = -grad E (central differences, rel to max)", what);
  t_check(m, t_relerr(fv, fd, n3), 1e-6);
  snprintf(m, sizeof m, "%s: other forces than the prototype's", what);
  t_true(m, t_relerr(fv, f, n3) > 1e-3);
  sessile_sds_forces_ref(o, p, 1, fv);
  for (int storage = 0; storage < 2; storage++) {
    sessile_sds_gpu_set_reads(sg, storage);
    t_must("gpu forces", sessile_sds_gpu_forces(sg, 1, fg));
    snprintf(m, sizeof m, "%s: GPU forces = host forces, damping on, %s reads (rel to max)", what,
             storage ? "storage" : "texel");
    t_check(m, t_relerr(fg, fv, n3), fp64 ? 1e-12 : 1e-5);
  }
  sessile_sds_gpu_set_reads(sg, 0);
  double bh = sessile_sds_stable_dt(o, p);
  t_must("gpu stable bound", sessile_sds_gpu_stable_dt(sg, &bg));
  printf("%s: stable bound host %.17g, device %.17g (prototype's %.17g)\n", what, bh, bg, bound0);
  snprintf(m, sizeof m, "%s: GPU stable bound = host's (rel)", what);
  t_check(m, fabs(bg - bh) / bh, fp64 ? 1e-12 : 1e-5);
  snprintf(m, sizeof m, "%s: another stable bound than the prototype's", what);
  t_true(m, fabs(bh - bound0) > 1e-6 * bh);
  free(fv), free(fd), free(fg);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  int fp64 = sessile_gpu_info_of(g)->precision == 64;
  const double ctr[3] = {0, 0, 0}, octr[3] = {0.9, 0, 0};
  sessile_sds o = {0};
  t_must("icosphere level 2 through TetGen", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
  size_t n = o.ncells, n3 = 3 * n;
  printf("organism: %u cells, %u tets, %u edges\n", o.ncells, o.ntets, o.nedges);

  /* zero force at import, on the GPU */
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.gravity = 0;
  sessile_sds_gpu *sg = NULL;
  t_must("gpu create", sessile_sds_gpu_create(g, &o, &p, &sg));
  double *f = t_dalloc(n3), *fg = t_dalloc(n3), *ffd = t_dalloc(n3);
  t_must("gpu forces", sessile_sds_gpu_forces(sg, 1, fg));
  double unit = 0;
  for (size_t c = 0; c < n; c++) unit = fmax(unit, o.m[c]);
  t_check("GPU: imported complex, largest force / force of a unit strain", maxabs(fg, n3) / unit,
          fp64 ? 1e-13 : 1e-5);
  uint32_t *inv = NULL, ninv = 0;
  t_must("gpu inverted", sessile_sds_gpu_inverted(sg, &inv, &ninv));
  t_true("GPU: no inverted tet at import", ninv == 0);
  free(inv);

  /* a perturbed state with every force term on */
  uint64_t rng = sessile_rng_stream(13, 1);
  for (size_t c = 0; c < n; c++)
    for (int i = 0; i < 3; i++) {
      o.x[3 * c + i] += 0.08 * o.r[c] * sessile_rng_normal(&rng);
      o.v[3 * c + i] = 0.3 * sessile_rng_normal(&rng);
    }
  for (size_t c = 0; c < 20 && c < n; c++) o.attract[c] = (int32_t)(c % 2);
  const double apos[6] = {3, 0, 0, 0, -2, 1};
  sessile_surface rock = {0};
  t_must("rock", sessile_surface_icosphere(2, 0.5, octr, &rock));
  p.gravity = 10;
  p.k_edge = 3, p.k_vol = 5, p.surface_mult = 1.7, p.damp_visc = 0.2, p.damp_vol = 0.3;
  p.box = 1;
  for (int i = 0; i < 3; i++) p.box_lo[i] = -0.85, p.box_hi[i] = 2;
  p.k_wall = 100;
  p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
  p.nattract = 2, p.attract_pos = apos, p.k_attract = 2;
  int nbox = 0, nrock = 0;
  for (size_t c = 0; c < n; c++) {
    for (int i = 0; i < 3; i++) nbox += o.x[3 * c + i] < -0.85;
    double d = hypot(hypot(o.x[3 * c] - 0.9, o.x[3 * c + 1]), o.x[3 * c + 2]);
    nrock += d < 0.45;
  }
  printf("cells against the box: %d, inside the rock: %d, attracted: 20\n", nbox, nrock);
  t_true("the box and the rock act on some cells", nbox > 0 && nrock > 0);

  /* host: f = -grad E by central differences */
  sessile_sds_forces_ref(&o, &p, 0, f);
  double h = 1e-6;
  minus_grad_fd(&o, &p, h, n3, ffd);
  t_check("host forces = -grad E (central differences, h 1e-6, rel to max)", t_relerr(f, ffd, n3), 1e-6);

  /* GPU = host, damping on */
  t_must("gpu set params", sessile_sds_gpu_set_params(sg, &p));
  t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
  sessile_sds_forces_ref(&o, &p, 1, f);
  t_must("gpu forces", sessile_sds_gpu_forces(sg, 1, fg));
  t_check("GPU forces = host forces, damping on (rel to max)", t_relerr(fg, f, n3), fp64 ? 1e-12 : 1e-5);
  sessile_sds_forces_ref(&o, &p, 0, f);
  t_must("gpu forces", sessile_sds_gpu_forces(sg, 0, fg));
  t_check("GPU forces = -grad E by differences (rel to max)", t_relerr(fg, ffd, n3), 1e-6);

  /* the stable bound: the device's kernels (stable.glsl, stable_min) against
   * the host's sessile_sds_stable_dt, which sums the same terms in element
   * order (rounding only); with the box and the rock (the wall term), then
   * with self-collision alone (the contact term on surface cells), through
   * texel and storage reads */
  {
    double bh = sessile_sds_stable_dt(&o, &p), bg = 0;
    t_must("gpu stable bound", sessile_sds_gpu_stable_dt(sg, &bg));
    printf("stable bound: host %.17g, device %.17g\n", bh, bg);
    t_true("the bound is below dt_max (the springs set it)", bh < p.dt_max);
    t_check("GPU stable bound = host's, box and rock (rel)", fabs(bg - bh) / bh, fp64 ? 1e-12 : 1e-5);
    sessile_sds_gpu_set_reads(sg, 1);
    t_must("gpu stable bound, storage reads", sessile_sds_gpu_stable_dt(sg, &bg));
    t_check("GPU stable bound = host's, storage reads (rel)", fabs(bg - bh) / bh, fp64 ? 1e-12 : 1e-5);
    sessile_sds_gpu_set_reads(sg, 0);
    sessile_sds_params q = p;
    q.box = 0, q.obstacle.nf = q.obstacle.nv = 0, q.self_collide = 1, q.k_contact = 3000;
    double bq = sessile_sds_stable_dt(&o, &q);
    t_must("gpu set params", sessile_sds_gpu_set_params(sg, &q));
    t_must("gpu stable bound, self-collision", sessile_sds_gpu_stable_dt(sg, &bg));
    t_true("the contact term changes the bound", fabs(bq - bh) > 1e-3 * bh);
    t_check("GPU stable bound = host's, self-collision (rel)", fabs(bg - bq) / bq, fp64 ? 1e-12 : 1e-5);
    /* an advance step asked for more than the cap takes the cap,
     * stable_safety x the bound */
    double ask = 1.0, el = 0;
    q.max_move = 1e9, q.dt_max = 10;
    t_must("gpu set params", sessile_sds_gpu_set_params(sg, &q));
    t_must("gpu stable bound, dt_max 10", sessile_sds_gpu_stable_dt(sg, &bg));
    t_must("advance one step", sessile_sds_gpu_advance(sg, 1, &ask, &el));
    printf("advance asked 1 s: took %.17g s, the cap %.17g s\n", el, q.stable_safety * bg);
    /* fp64: the same product on both sides; fp32: the device multiplies in
     * float, the host in double: one float rounding (2^-23) */
    t_check("the step taken is stable_safety x the device's bound (rel)", fabs(el - q.stable_safety * bg) / el,
            fp64 ? 0 : 0x1p-23);
    t_check("and the host's (rel)", fabs(el - q.stable_safety * sessile_sds_stable_dt(&o, &q)) / el, fp64 ? 1e-12 : 1e-5);
    /* the advance's gather takes the element sums from the stable kernel:
     * the same bytes as a plain step of the same dt (its own sums) */
    sessile_sds wa = {0}, wb = {0};
    t_must("copies", sessile_sds_copy(&o, &wa));
    t_must("copies", sessile_sds_copy(&o, &wb));
    t_must("download", sessile_sds_gpu_download(sg, &wa));
    t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
    t_must("one plain step", sessile_sds_gpu_step(sg, el, NULL));
    t_must("download", sessile_sds_gpu_download(sg, &wb));
    t_true("an advance step = a plain step of its dt, bit for bit",
           !memcmp(wa.x, wb.x, n3 * sizeof *wa.x) && !memcmp(wa.v, wb.v, n3 * sizeof *wa.v));
    double moved = 0;
    for (size_t k = 0; k < n3; k++) moved = fmax(moved, fabs(wa.x[k] - o.x[k]));
    t_true("and the step moved the cells", moved > 0);
    sessile_sds_free(&wa), sessile_sds_free(&wb);
    t_must("gpu set params", sessile_sds_gpu_set_params(sg, &p));
    t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
  }

  /* the paper's uniform stiffness (uniform_stiffness: s_k = k_edge, k_vol
   * for every spring) */
  {
    sessile_sds_params u = p;
    u.uniform_stiffness = 1, u.k_edge = 0.02, u.k_vol = 0.03; /* energies: about the prototype's at this size */
    t_must("gpu set params", sessile_sds_gpu_set_params(sg, &u));
    variant("uniform stiffness", &o, &u, sg, f, sessile_sds_stable_dt(&o, &p), fp64);
    t_must("gpu set params", sessile_sds_gpu_set_params(sg, &p));
  }

  /* per-spring stiffness on the surface (edge_k, the axial stiffness's; up to
   * 3000 x, so that the surface cells set the stable bound);
   * an interior spring's edge_k does nothing */
  {
    double *k0 = o.edge_k, *fk = t_dalloc(n3), *fi = t_dalloc(n3), bound0 = sessile_sds_stable_dt(&o, &p);
    o.edge_k = t_dalloc(o.nedges);
    uint64_t rk = sessile_rng_stream(17, 1);
    for (uint32_t e = 0; e < o.nedges; e++) o.edge_k[e] = o.edge_surface[e] ? sessile_rng_range(&rk, 0.2, 3000) : 1;
    t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
    variant("per-spring stiffness", &o, &p, sg, f, bound0, fp64);
    sessile_sds_forces_ref(&o, &p, 1, fk);
    for (uint32_t e = 0; e < o.nedges; e++)
      if (!o.edge_surface[e]) o.edge_k[e] = 5;
    sessile_sds_forces_ref(&o, &p, 1, fi);
    t_true("per-spring stiffness: an interior spring's edge_k is not used", !memcmp(fi, fk, n3 * sizeof *fi));
    free(o.edge_k), o.edge_k = k0;
    t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
    free(fk), free(fi);
  }

  /* inversion: reflect a vertex of tet 0 through its opposite face */
  sessile_sds w = {0};
  t_must("copy", sessile_sds_copy(&o, &w));
  const uint32_t *q = w.tet;
  double *x0 = w.x + 3 * (size_t)q[0], *x1 = w.x + 3 * (size_t)q[1], *x2 = w.x + 3 * (size_t)q[2],
         *x3 = w.x + 3 * (size_t)q[3];
  double a[3], b[3], nn[3], d[3];
  for (int i = 0; i < 3; i++) a[i] = x2[i] - x1[i], b[i] = x3[i] - x1[i], d[i] = x0[i] - x1[i];
  nn[0] = a[1] * b[2] - a[2] * b[1], nn[1] = a[2] * b[0] - a[0] * b[2], nn[2] = a[0] * b[1] - a[1] * b[0];
  double s = (d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2]) / (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
  for (int i = 0; i < 3; i++) x0[i] -= 2 * s * nn[i];
  uint32_t *ih = NULL, nh = 0;
  t_must("host inverted", sessile_sds_inverted_ref(&w, &ih, &nh));
  t_must("gpu upload", sessile_sds_gpu_upload(sg, &w));
  t_must("gpu inverted", sessile_sds_gpu_inverted(sg, &inv, &ninv));
  printf("inverted tets: host %u, GPU %u (first %u)\n", nh, ninv, ninv ? inv[0] : 0);
  t_true("GPU finds the constructed inverted tet 0", ninv > 0 && inv[0] == 0);
  t_true("GPU inverted list = host list", ninv == nh && !memcmp(inv, ih, nh * sizeof *ih));
  free(inv), inv = NULL, ninv = 0;
  sessile_sds_gpu_set_reads(sg, 1);
  t_must("gpu inverted, storage reads", sessile_sds_gpu_inverted(sg, &inv, &ninv));
  sessile_sds_gpu_set_reads(sg, 0);
  t_true("GPU inverted list through storage reads = host list", ninv == nh && !memcmp(inv, ih, nh * sizeof *ih));
  free(inv), free(ih);
  sessile_sds_free(&w);

  /* same input, same bytes; and the host integrator's trajectory */
  p.box = 0, p.obstacle.nf = 0, p.nattract = 0;
  sessile_sds r1 = {0}, r2 = {0}, rh = {0};
  t_must("copies", sessile_sds_copy(&o, &r1));
  t_must("copies", sessile_sds_copy(&o, &r2));
  t_must("copies", sessile_sds_copy(&o, &rh));
  sessile_sds_gpu *s2 = NULL;
  t_must("gpu set params", sessile_sds_gpu_set_params(sg, &p));
  t_must("gpu upload", sessile_sds_gpu_upload(sg, &o));
  t_must("second gpu", sessile_sds_gpu_create(g, &o, &p, &s2));
  const int N = 40;
  double dt = 2e-3;
  for (int k = 0; k < N; k++) {
    t_must("step", sessile_sds_gpu_step(sg, dt, NULL));
    t_must("step", sessile_sds_gpu_step(s2, dt, NULL));
    sessile_sds_step_ref(&rh, &p, dt);
  }
  t_must("download", sessile_sds_gpu_download(sg, &r1));
  t_must("download", sessile_sds_gpu_download(s2, &r2));
  t_true("two GPU runs of 40 steps: identical bytes (x, v)",
         !memcmp(r1.x, r2.x, n3 * 8) && !memcmp(r1.v, r2.v, n3 * 8));
  t_must("upload", sessile_sds_gpu_upload(s2, &o));
  t_must("batched steps", sessile_sds_gpu_steps(s2, N - 1, dt)); /* odd: ends in the other buffer pair */
  t_must("one more", sessile_sds_gpu_steps(s2, 1, dt));
  t_must("download", sessile_sds_gpu_download(s2, &r2));
  t_true("40 steps in two submissions (39 + 1): the same bytes as one at a time",
         !memcmp(r1.x, r2.x, n3 * 8) && !memcmp(r1.v, r2.v, n3 * 8));
  /* the storage-read kernels give the bytes of the texel-read ones (the
   * default where the views fit: shaders/sds/sds_load.glsl) */
  t_must("upload", sessile_sds_gpu_upload(s2, &o));
  sessile_sds_gpu_set_reads(s2, 1);
  for (int k = 0; k < N; k++) t_must("step, storage reads", sessile_sds_gpu_step(s2, dt, NULL));
  t_must("download", sessile_sds_gpu_download(s2, &r2));
  t_true("40 steps through storage reads: the same bytes as through texel reads",
         !memcmp(r1.x, r2.x, n3 * 8) && !memcmp(r1.v, r2.v, n3 * 8));
  sessile_sds_gpu_set_reads(s2, 0);
  /* growth alone: sessile_sds_gpu_update_radii gives the device state of a
   * full upload (sg holds r1's x and v: it was downloaded from it) */
  {
    sessile_sds gr = {0};
    t_must("copy", sessile_sds_copy(&r1, &gr));
    for (uint32_t c = 0; c < gr.ncells; c++) gr.r[c] *= 1 + 0.02 * (c % 3), gr.m[c] *= 1.5;
    double *fa = t_dalloc(n3), *fb = t_dalloc(n3);
    t_must("update radii", sessile_sds_gpu_update_radii(sg, &gr));
    t_must("forces", sessile_sds_gpu_forces(sg, 1, fa));
    t_must("full upload", sessile_sds_gpu_upload(s2, &gr));
    t_must("forces", sessile_sds_gpu_forces(s2, 1, fb));
    t_true("grown radii: update_radii gives the forces of a full upload, bit for bit", !memcmp(fa, fb, n3 * 8));
    t_must("step", sessile_sds_gpu_step(sg, dt, NULL));
    t_must("step", sessile_sds_gpu_step(s2, dt, NULL));
    t_must("download", sessile_sds_gpu_download(sg, &r2));
    t_must("download", sessile_sds_gpu_download(s2, &gr));
    t_true("and the same next step", !memcmp(r2.x, gr.x, n3 * 8) && !memcmp(r2.v, gr.v, n3 * 8));
    gr.ncells--;
    t_true("update_radii refuses another complex", sessile_sds_gpu_update_radii(sg, &gr) == SESSILE_ERR_USAGE);
    gr.ncells++;
    free(fa), free(fb);
    sessile_sds_free(&gr);
  }
  /* the loop's transfers ride in the step's submission (gpu.h,
   * sessile_cmd_upload): a step, its download and a growth of the radii cost
   * one submission, staged or not; the bytes are those of full uploads */
  {
    sessile_sds wa = {0}, wb = {0};
    t_must("copy", sessile_sds_copy(&r1, &wa));
    t_must("copy", sessile_sds_copy(&r1, &wb));
    t_must("upload", sessile_sds_gpu_upload(s2, &wa));
    t_must("upload", sessile_sds_gpu_upload(sg, &wb));
    uint64_t q0 = sessile_gpu_submissions(g);
    for (int k = 0; k < 10; k++) {
      t_must("step", sessile_sds_gpu_step(s2, dt, NULL));
      t_must("download", sessile_sds_gpu_download(s2, &wa));
      for (uint32_t c = 0; c < wa.ncells; c++) wa.r[c] *= 1 + 0.001 * (c % 4), wa.m[c] *= 1.002;
      t_must("update radii", sessile_sds_gpu_update_radii(s2, &wa));
    }
    uint64_t nq = sessile_gpu_submissions(g) - q0;
    printf("10 steps, each downloaded and its radii grown: %llu submissions\n", (unsigned long long)nq);
    t_true("10 steps, each downloaded and its radii grown: 10 submissions", nq == 10);
    for (int k = 0; k < 10; k++) {
      t_must("step", sessile_sds_gpu_step(sg, dt, NULL));
      t_must("download", sessile_sds_gpu_download(sg, &wb));
      for (uint32_t c = 0; c < wb.ncells; c++) wb.r[c] *= 1 + 0.001 * (c % 4), wb.m[c] *= 1.002;
      t_must("full upload", sessile_sds_gpu_upload(sg, &wb));
    }
    t_true("... and the bytes of full uploads after each growth (x, v, r, m)",
           !memcmp(wa.x, wb.x, n3 * 8) && !memcmp(wa.v, wb.v, n3 * 8) && !memcmp(wa.r, wb.r, n * 8) &&
               !memcmp(wa.m, wb.m, n * 8));
    sessile_sds_free(&wa), sessile_sds_free(&wb);
  }
  t_check("GPU positions after 40 steps = host integrator's (rel to max)", t_relerr(r1.x, rh.x, n3),
          fp64 ? 1e-10 : 1e-4);
  double disp = 0;
  for (size_t k = 0; k < n3; k++) disp = fmax(disp, fabs(r1.x[k] - o.x[k]));
  printf("largest displacement over the 40 steps: %.3g u\n", disp);
  t_true("the run moved the cells", disp > 1e-3);
  sessile_sds_gpu_destroy(s2);
  sessile_sds_free(&r1), sessile_sds_free(&r2), sessile_sds_free(&rh);

  sessile_sds_gpu_destroy(sg);
  sessile_surface_free(&rock);
  free(f), free(fg), free(ffd);
  sessile_sds_free(&o);
  return t_finish(g);
}
