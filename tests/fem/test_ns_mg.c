/* The block multigrid preconditioner (sessile/la/bmg.h, pc "mg") on the
 * Navier-Stokes systems of the immersed flow (docs/fluid.md, "Multigrid").
 *
 * The default scene's box (38.4 x 38.4 x 28.8 cm) at three resolutions,
 * 9x9x7, 17x17x13 and 33x33x25 nodes, with a solid dome (radius 6 cm) at the
 * floor's centre, inlet 0.05 m/s, the paper's boundary conditions:
 *  - Stokes (rho = 0) and Oseen (the Picard linearisation at the inlet flow,
 *    Re = rho U L / eta = 120, L = 12 cm), coarse operators rediscretised
 *    on the coarse boxes, W(2,2) cycles: the multigrid iteration
 *    x += V(b - A x) converges with an asymptotic factor (the mean over
 *    iterations 4..12) <= 0.5 on every grid, and the factors of the grids
 *    differ by at most 0.1.  On 9x9x7 the hierarchy has two levels (a
 *    two-grid cycle with an exact coarse solve); finer grids add levels;
 *  - the device V-cycle equals the plain-C reference (1e-10 relative; fp64),
 *    and its smoother and residual give the same bits reading the matrix
 *    and x through storage buffers as through texel buffers, and the small
 *    levels' smoothing the same in one workgroup as in 8 dispatches a sweep;
 *  - the same V-cycle with the matrices stored in row chunks (the test-only
 *    chunk limit) equals the unchunked one (1e-12);
 *  - the fluid's solve with pc mg (rediscretised coarse levels): the first
 *    two Newton steps from rest on 33x33x25 reach the linear 1e-6 in at
 *    most 30 GMRES(50) iterations each, and its default 3 sweeps take fewer
 *    on the first step than 2; on a mesh that is not a box it falls back to
 *    ILU(0);
 *  - Galerkin coarse operators are measured and printed on the two coarser
 *    grids (they diverge beyond two levels: docs/fluid.md); block-Jacobi smoothing converges
 *    (factor < 1), the VW(2,2) cycle (V on the finest level, W below) to
 *    factor <= 0.5 on 17x17x13; a second setup with the same fixed unknowns does not
 *    rebuild the masks.
 * With --mg32 (ctest test_ns_mg32), the cycle in fp32 inside the fp64 context
 * (sessile_bmg_options.precision 32; docs/la.md, "The cycle in fp32"):
 *  - the Stokes and Oseen factors stay <= 0.5 and h-independent within 0.1,
 *    and within 1e-5 of the fp64 cycle's factors (fp32 rounding is ~6e-8
 *    relative per operation and scale-invariant, so it perturbs each cycle's
 *    output by ~1e-6 relative whatever the residual's size; measured ~1e-7);
 *  - the device's fp32 cycle against the fp64 plain-C reference: 1e-4 relative
 *    (max norm; fp32's 6e-8 unit roundoff amplified by the cycle's thousands
 *    of operations per unknown and the coarse inverse; measured ~1e-6);
 *    storage reads = texel reads and one-workgroup = per-colour smoothing bit
 *    for bit, chunked (fp32 values) = unchunked to 1e-12; block Jacobi
 *    smoothing converges; a set stop slot (S_STOP 1 or 3, the solver's
 *    fp64 scalars) skips the whole fp32 cycle and a clear one runs it;
 *  - the fluid's Newton solve from rest on 17x17x13 (no nested start; three
 *    levels, so the fp32 cycle's coarse correction and its coarsest inverse
 *    both act; 33x33x25 took 26 of the test's 38 s for the same checks): the
 *    same Newton steps as with the fp64 cycle, every linear solve at true
 *    relres <= 1e-6 in at most 2 more GMRES iterations than fp64's (each
 *    iteration's residual reduction differs by ~1e-6 relative, so the counts
 *    differ only where a solve ends within a hair of the tolerance), and
 *    the velocities within 1e-4 of the fp64 solve's (max norm, relative to
 *    the inlet speed; both take the same Newton steps, each solved to the
 *    linear tolerance 1e-6, so they differ by about 1e-6 of the steps'
 *    sizes, amplified by the steps after; 1e-4 stays well inside the
 *    Newton tolerance 1e-3 that bounds either's distance to the discrete
 *    solution; measured ~1e-8).
 * In an fp32 context (SESSILE_PRECISION=32) precision 32 is the context's own
 * cycle: --mg32 then checks that it gives the bits of precision 64. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/fem/fluid.h"
#include "sessile/la/la_ref.h"
#include "sessile/la/pc.h"
#include "sessile/mesh/box.h"
#include "sessile/mesh/tetmesh.h"
#include "testutil.h"
#include "la/bmg_internal.h" /* bmg_rec_cycle: the fp32 cycle's stop-slot guard */

static sessile_gpu *gpu;
static double dome_radius = 6.0; /* cm; --explore may change it */
static sessile_la *la;
static int fp64;
static int explore; /* --explore: print where the slow mode sits */

typedef struct {
  sessile_box box;
  sessile_tetmesh mesh;
  sessile_fluid *fl;
  uint8_t *solid;
  uint32_t n;
} scene;

static void scene_make(int level, double radius, scene *sc) {
  const double o[3] = {0, 0, 0};
  const uint32_t cells[3] = {4, 4, 3};
  t_must("box", sessile_box_make(o, 9.6, cells, level, &sc->box));
  t_must("mesh", sessile_tetmesh_from_box(&sc->box, &sc->mesh));
  t_must("fluid", sessile_fluid_create(la, &sc->mesh, &sc->fl));
  sc->n = sessile_box_nodes(&sc->box);
  sc->solid = t_xalloc(sc->n);
  for (uint32_t i = 0; i < sc->n; i++) {
    double x[3];
    sessile_box_node_pos(&sc->box, i, x);
    double dx = x[0] - 19.2, dy = x[1] - 19.2;
    sc->solid[i] = dx * dx + dy * dy + x[2] * x[2] <= radius * radius;
  }
}

static void scene_free(scene *sc) {
  sessile_fluid_destroy(sc->fl);
  sessile_tetmesh_free(&sc->mesh);
  free(sc->solid);
}

/* The system (Stokes: rho = 0, else the Picard step at the inlet flow). */
static void system_of(scene *sc, int stokes, sessile_bcsr4 *a, double *b) {
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  if (stokes) p.rho = 0;
  double *up = t_dalloc((size_t)sc->n * 4);
  for (uint32_t i = 0; i < sc->n; i++) up[4 * i] = sc->solid[i] ? 0 : p.inlet[0];
  t_must("jacobian", sessile_fluid_jacobian(sc->fl, sc->solid, &p, up, 1, a, b));
  free(up);
}

static double norm(const double *v, size_t n) {
  double s = 0;
  for (size_t i = 0; i < n; i++) s += v[i] * v[i];
  return sqrt(s);
}

/* The rediscretised coarse operators of grid lev's hierarchy into ca[0..],
 * set on mg; how many (the caller frees them). */
static int coarse_operators(sessile_bmg *mg, int lev, int stokes, sessile_bcsr4 *ca) {
  int nc = sessile_bmg_levels(mg) - 1;
  for (int l = 1; l <= nc; l++) {
    scene c;
    scene_make(lev - l, dome_radius, &c);
    system_of(&c, stokes, &ca[l - 1], NULL);
    t_must("coarse operator", sessile_bmg_set_operator(mg, l, &ca[l - 1]));
    scene_free(&c);
  }
  return nc;
}

/* Mean convergence factor of x += V(b - A x) over iterations 4..12, with
 * the hierarchy for grid g and options o (levels: how many it made). */
static double mg_factor(int lev, int stokes, int galerkin, const sessile_bcsr4 *a, const double *b,
                        const sessile_bmg_options *o, int *levels) {
  size_t n4 = (size_t)a->nbrows * 4;
  sessile_bmg *mg = NULL;
  sessile_mat *m = NULL;
  sessile_vec *rv = NULL, *zv = NULL;
  scene fine;
  scene_make(lev, dome_radius, &fine);
  t_must("bmg", sessile_bmg_create(la, fine.box.n, o, &mg));
  sessile_bcsr4 ca[8];
  int nc = galerkin ? 0 : coarse_operators(mg, lev, stokes, ca);
  t_must("mat", sessile_mat_create_bcsr4(la, a, &m));
  t_must("bmg setup", sessile_bmg_setup(mg, m));
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &rv));
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &zv));
  *levels = sessile_bmg_levels(mg);
  double *x = t_dalloc(n4), *r = t_dalloc(n4), *z = t_dalloc(n4), nr[13];
  memcpy(r, b, n4 * sizeof *r);
  nr[0] = norm(r, n4);
  for (int k = 0; k < 12; k++) {
    t_must("upload", sessile_vec_upload(rv, r));
    t_must("vcycle", sessile_bmg_vcycle(mg, rv, zv));
    t_must("download", sessile_vec_download(zv, z));
    for (size_t i = 0; i < n4; i++) x[i] += z[i];
    sessile_ref_spmv_bcsr4(a, x, r);
    for (size_t i = 0; i < n4; i++) r[i] = b[i] - r[i];
    nr[k + 1] = norm(r, n4);
  }
  if (explore) { /* where the slowest mode's residual sits: its three largest entries */
    static const char comp[4] = {'u', 'v', 'w', 'p'};
    for (int t = 0; t < 3; t++) {
      size_t im = 0;
      for (size_t i = 0; i < n4; i++)
        if (fabs(r[i]) > fabs(r[im])) im = i;
      double xp[3];
      sessile_box_node_pos(&fine.box, (uint32_t)(im / 4), xp);
      printf("    largest residual %d: %c at (%.1f, %.1f, %.1f) cm, %.2e of the first\n", t + 1, comp[im % 4], xp[0],
             xp[1], xp[2], fabs(r[im]) / nr[0]);
      r[im] = 0;
    }
  }
  printf("    residuals:");
  for (int k = 0; k <= 12; k++) printf(" %.2e", nr[k] / nr[0]);
  printf("\n");
  free(x), free(r), free(z);
  sessile_vec_destroy(rv), sessile_vec_destroy(zv);
  sessile_mat_destroy(m);
  sessile_bmg_destroy(mg);
  for (int l = 0; l < nc; l++) sessile_bcsr4_free(&ca[l]);
  scene_free(&fine);
  return pow(nr[12] / nr[4], 1.0 / 8);
}

/* Device V-cycle against the reference, and chunked against unchunked. */
static void vcycle_checks(scene *sc, const sessile_bcsr4 *a, const double *b) {
  size_t n4 = (size_t)a->nbrows * 4;
  sessile_bmg *mg = NULL;
  sessile_mat *m = NULL, *mc = NULL;
  sessile_vec *rv = NULL, *zv = NULL;
  t_must("bmg", sessile_bmg_create(la, sc->box.n, NULL, &mg));
  t_must("mat", sessile_mat_create_bcsr4(la, a, &m));
  t_must("bmg setup", sessile_bmg_setup(mg, m));
  t_true("first setup builds the masks once", sessile_bmg_rebuilds(mg) == 1);
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &rv));
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &zv));
  double *z = t_dalloc(n4), *zr = t_dalloc(n4), *zc = t_dalloc(n4);
  t_must("upload", sessile_vec_upload(rv, b));
  t_must("vcycle", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, z));
  t_must("ref vcycle", sessile_ref_bmg_vcycle(mg, b, zr));
  if (fp64) t_check("device V-cycle = reference (max rel)", t_relerr(z, zr, n4), 1e-10);
  /* the smoother and residual reading storage buffers (la option
   * spmv_storage) instead of texel buffers: the same values, the same bits */
  {
    sessile_la_options so;
    sessile_la_options_default(&so);
    so.spmv_storage = 1;
    sessile_la_set_options(la, &so);
    double *zs = t_dalloc(n4);
    t_must("vcycle (storage reads)", sessile_bmg_vcycle(mg, rv, zv));
    t_must("download", sessile_vec_download(zv, zs));
    sessile_la_options_default(&so);
    sessile_la_set_options(la, &so);
    t_true("V-cycle with storage reads = with texel reads, bit for bit", memcmp(zs, z, n4 * sizeof *z) == 0);
    /* every level's smoothing in 8 dispatches a sweep (wg_max_nodes 0)
     * against the small levels' in one workgroup */
    sessile_bmg_options wo;
    sessile_bmg_options_default(&wo);
    wo.wg_max_nodes = 0;
    sessile_bmg *mw = NULL;
    t_must("bmg (no one-workgroup smoothing)", sessile_bmg_create(la, sc->box.n, &wo, &mw));
    t_must("bmg setup", sessile_bmg_setup(mw, m));
    t_must("vcycle", sessile_bmg_vcycle(mw, rv, zv));
    t_must("download", sessile_vec_download(zv, zs));
    printf("    levels of at most %u nodes smoothed in one workgroup:", wo.wg_max_nodes = 1024);
    for (int l = 0; l < sessile_bmg_levels(mg); l++)
      if (sessile_bmg_level_nodes(mg, l) <= 1024) printf(" %u", sessile_bmg_level_nodes(mg, l));
    printf("\n");
    t_true("V-cycle with one-workgroup smoothing = per-colour dispatches, bit for bit",
           memcmp(zs, z, n4 * sizeof *z) == 0);
    sessile_bmg_destroy(mw);
    free(zs);
  }
  /* the same matrix in row chunks of at most 256 KiB */
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  lo.max_matrix_chunk_bytes = 256 << 10;
  sessile_la_set_options(la, &lo);
  t_must("mat (chunked)", sessile_mat_create_bcsr4(la, a, &mc));
  sessile_la_options_default(&lo);
  sessile_la_set_options(la, &lo);
  printf("    chunks: %u\n", sessile_mat_chunks(mc));
  t_true("the matrix is stored in several chunks", sessile_mat_chunks(mc) > 2);
  t_must("bmg setup (chunked)", sessile_bmg_setup(mg, mc));
  t_true("same fixed unknowns: no rebuild", sessile_bmg_rebuilds(mg) == 1);
  t_must("vcycle (chunked)", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, zc));
  t_check("chunked V-cycle = unchunked (max rel)", t_relerr(zc, z, n4), 1e-12);
  free(z), free(zr), free(zc);
  sessile_vec_destroy(rv), sessile_vec_destroy(zv);
  sessile_mat_destroy(m), sessile_mat_destroy(mc);
  sessile_bmg_destroy(mg);
}

/* The fluid's own path: one Newton step from rest with pc mg (GMRES(50),
 * rediscretised coarse operators kept in the fluid), then a second solve
 * reusing the hierarchy; a mesh that is not a box falls back to ILU(0). */
static void fluid_newton(scene *sc) {
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  p.pc = SESSILE_PC_MG;
  p.newton_max = 2;
  double *up = t_dalloc((size_t)sc->n * 4);
  sessile_fluid_result res;
  t_must("fluid solve (mg)", sessile_fluid_solve(sc->fl, sc->solid, &p, up, &res));
  for (int k = 0; k < res.nsteps; k++) {
    const sessile_fluid_step *st = &res.step[k];
    printf("    Newton step %d on %u nodes: pc %s, %d GMRES iterations, true relres %.2e\n", k + 1, sc->n,
           sessile_pc_type_name(st->lin_pc), st->lin_iterations, st->lin_relres);
    t_true("the step ran pc mg", st->lin_pc == SESSILE_PC_MG);
    t_check("GMRES+mg Newton step: true relres", st->lin_relres, 1e-6);
    t_check("GMRES+mg Newton step: iterations (<= 30)", st->lin_iterations, 30);
  }
  /* the fluid's three sweeps (fluid_mg_sweeps) against two on the first
   * step: fewer iterations, the reason for the default (docs/fluid.md,
   * "Three sweeps": 8 against 11 on the bench's scene) */
  int it3 = res.step[0].lin_iterations;
  t_check("the fluid's default: 3 sweeps", p.mg.pre - 3, 0);
  p.mg.pre = p.mg.post = 2;
  p.newton_max = 1;
  memset(up, 0, (size_t)sc->n * 4 * sizeof *up);
  t_must("fluid solve (mg, 2 sweeps)", sessile_fluid_solve(sc->fl, sc->solid, &p, up, &res));
  printf("    first Newton step: %d GMRES iterations with 3 sweeps, %d with 2\n", it3, res.step[0].lin_iterations);
  t_true("3 sweeps take fewer GMRES iterations than 2", it3 < res.step[0].lin_iterations);
  free(up);
}

static void fallback(void) {
  scene sc;
  scene_make(2, 6.0, &sc);
  sessile_fluid_destroy(sc.fl);
  sc.mesh.xyz[3 * 40] += 0.05; /* one node off the lattice: not a box */
  t_must("fluid", sessile_fluid_create(la, &sc.mesh, &sc.fl));
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  p.pc = SESSILE_PC_MG;
  p.newton_max = 1;
  double *up = t_dalloc((size_t)sc.n * 4);
  sessile_fluid_result res;
  t_must("fluid solve (not a box)", sessile_fluid_solve(sc.fl, sc.solid, &p, up, &res));
  t_true("not a box: pc mg falls back to ILU(0)", res.nsteps == 1 && res.step[0].lin_pc == SESSILE_PC_ILU0);
  free(up);
  scene_free(&sc);
}

/* --- --mg32: the cycle in fp32 inside the fp64 context ------------------- */

static sessile_bmg_options opts32(void) {
  sessile_bmg_options o;
  sessile_bmg_options_default(&o);
  o.precision = 32;
  return o;
}

/* The cycle recorded as GMRES records it, guarded by la's fp64 stop slot
 * (set to `stop` for the run). */
static void guarded_cycle(sessile_bmg *mg, sessile_vec *rv, sessile_vec *zv, double stop) {
  la_scalar_set(la, S_STOP, stop);
  t_must("begin", sessile_cmd_begin(la->cmd));
  t_must("record", bmg_rec_cycle(mg, la->cmd, vref_of(rv), vref_of(zv), S_STOP));
  t_must("end", sessile_cmd_end(la->cmd));
  t_must("run", sessile_cmd_submit_wait(la->cmd));
  la_scalar_set(la, S_STOP, 0);
}

/* A set stop slot skips every f32 dispatch (the finest x32 and z keep their
 * values); a clear one runs the cycle. */
static void guard32_checks(sessile_bmg *mg, sessile_vec *rv, sessile_vec *zv, const double *b, const double *z) {
  size_t n4 = (size_t)mg->lv[0].nodes * 4;
  float *x0 = t_xalloc(n4 * sizeof *x0), *x1 = t_xalloc(n4 * sizeof *x1);
  double *r2 = t_dalloc(n4), *zg = t_dalloc(n4);
  t_must("download x32", sessile_buffer_download(mg->lv[0].x32, 0, x0, n4 * sizeof *x0));
  for (size_t i = 0; i < n4; i++) r2[i] = 2 * b[i];
  t_must("upload", sessile_vec_upload(rv, r2));
  static const double stops[2] = {1.0, 3.0}; /* STOP_CONVERGED, STOP_BREAKDOWN */
  for (int k = 0; k < 2; k++) {
    t_must("fill", sessile_vec_fill(la, 7.0, zv));
    guarded_cycle(mg, rv, zv, stops[k]);
    t_must("download", sessile_vec_download(zv, zg));
    t_must("download x32", sessile_buffer_download(mg->lv[0].x32, 0, x1, n4 * sizeof *x1));
    int kept = 1;
    for (size_t i = 0; i < n4; i++) kept &= zg[i] == 7.0;
    t_true(k ? "S_STOP 3: z untouched" : "S_STOP 1: z untouched", kept);
    t_true(k ? "S_STOP 3: the fp32 cycle skipped (x32 kept)" : "S_STOP 1: the fp32 cycle skipped (x32 kept)",
           memcmp(x0, x1, n4 * sizeof *x0) == 0);
  }
  guarded_cycle(mg, rv, zv, 0.0);
  t_must("download", sessile_vec_download(zv, zg));
  for (size_t i = 0; i < n4; i++) r2[i] = 2 * z[i]; /* the cycle of 2b: 2 z exactly (scaling by 2 is exact) */
  t_true("S_STOP 0: the guarded cycle runs (z of 2b = 2 z, bit for bit)", memcmp(zg, r2, n4 * sizeof *zg) == 0);
  t_must("upload", sessile_vec_upload(rv, b));
  free(x0), free(x1), free(r2), free(zg);
}

/* The fp32 device cycle against the fp64 reference, its read paths, its
 * chunking, its guard (the fp64 vcycle_checks' counterparts). */
/* GMRES with the fp32 cycle in fp64 (mg32): a cycle of at most 16
 * iterations updates x from the kept z_j = M^-1 v_j (gmres.c), for which
 * the Arnoldi relation holds, so the true residual is the recursive
 * estimate to fp64 rounding, though M^-1 is linear only to fp32 rounding;
 * the textbook update x += M^-1 (V y) (a cycle of more than 16, restart 30)
 * is off by the cycle's fp32 rounding. */
static void gmres_kept_z(int lev, const sessile_bcsr4 *a, const double *b) {
  size_t n4 = (size_t)a->nbrows * 4;
  sessile_bmg_options o32 = opts32();
  sessile_bmg *mg = NULL;
  sessile_mat *m = NULL;
  sessile_vec *bv = NULL, *x = NULL;
  sessile_pc *pc = NULL;
  scene fine;
  scene_make(lev, dome_radius, &fine);
  t_must("bmg (fp32 cycle)", sessile_bmg_create(la, fine.box.n, &o32, &mg));
  sessile_bcsr4 ca[8];
  int nc = coarse_operators(mg, lev, 1, ca);
  t_must("mat", sessile_mat_create_bcsr4(la, a, &m));
  t_must("pc mg", sessile_pc_create_type(la, SESSILE_PC_MG, &pc));
  t_must("pc mg block", sessile_pc_mg_set_block(pc, mg));
  t_must("pc mg setup", sessile_pc_setup(pc, m));
  t_must("b", sessile_vec_create(la, (uint32_t)n4, &bv));
  t_must("x", sessile_vec_create(la, (uint32_t)n4, &x));
  t_must("upload", sessile_vec_upload(bv, b));
  double gap[2] = {0, 0}, *xs[2] = {t_dalloc(n4), t_dalloc(n4)};
  int its[2] = {0, 0};
  static const char *const upd[2] = {"kept z_j", "textbook"};
  for (int k = 0; k < 2; k++) {
    sessile_la_options lo;
    sessile_la_options_default(&lo);
    lo.gmres_textbook_update = k;
    sessile_la_set_options(la, &lo);
    sessile_ksp_options o;
    sessile_ksp_options_default(&o);
    o.type = SESSILE_KSP_GMRES;
    o.pc = SESSILE_PC_MG;
    o.restart = 30;
    o.rtol = 1e-6;
    o.max_it = 30;
    sessile_solve_result r;
    t_must("x = 0", sessile_vec_fill(la, 0.0, x));
    t_must("gmres + mg (fp32 cycle)", sessile_ksp_solve_pc(la, &o, m, pc, bv, x, &r));
    t_must("download", sessile_vec_download(x, xs[k]));
    its[k] = r.iterations;
    gap[k] = fabs(r.true_relres - r.est_relres) / r.true_relres;
    printf("    gmres + fp32 cycle, %s update: %d iterations, true relres %.3e, estimate %.3e (%.1e apart)\n",
           upd[k], r.iterations, r.true_relres, r.est_relres, gap[k]);
    char what[96];
    snprintf(what, sizeof what, "gmres + fp32 cycle, %s update: true relres", upd[k]);
    t_check(what, r.true_relres, k ? 1e-5 : 1e-6); /* the textbook's: the rtol plus the cycle's rounding */
  }
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  sessile_la_set_options(la, &lo);
  t_true("the same iterations either way (at most 16: the kept z_j's)", its[0] == its[1] && its[0] <= 16);
  t_check("kept z_j: true relres = estimate within 1e-9 relative", gap[0], 1e-9);
  t_true("... closer than the textbook update's (off by the cycle's fp32 rounding)", gap[0] < gap[1]);
  double dx = t_relerr(xs[0], xs[1], n4);
  printf("    x: kept z_j against textbook: %.2e (max rel)\n", dx);
  t_check("x: kept z_j = textbook within the fp32 cycle's rounding (max rel)", dx, 1e-4);
  free(xs[0]), free(xs[1]);
  sessile_vec_destroy(x), sessile_vec_destroy(bv);
  sessile_pc_destroy(pc);
  sessile_mat_destroy(m);
  sessile_bmg_destroy(mg);
  for (int l = 0; l < nc; l++) sessile_bcsr4_free(&ca[l]);
  scene_free(&fine);
}

/* A second setup of mg on mc in chunks of at most 256 KiB (the fp32 copy
 * cast on the device from the fp64 chunks; storage: reading them through
 * storage buffers, la option spmv_storage), then one cycle of rv into z. */
static void recast_cycle(sessile_bmg *mg, const sessile_mat *mc, int storage, sessile_vec *rv,
                         sessile_vec *zv, double *z) {
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  lo.max_matrix_chunk_bytes = 256 << 10;
  lo.spmv_storage = storage;
  sessile_la_set_options(la, &lo);
  t_must(storage ? "bmg setup again (the device's cast, storage reads)" : "bmg setup again (the device's cast)",
         sessile_bmg_setup(mg, mc));
  sessile_la_options_default(&lo);
  sessile_la_set_options(la, &lo);
  t_must("vcycle (cast on the device)", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, z));
}

static void vcycle32_checks(scene *sc, const sessile_bcsr4 *a, const double *b) {
  size_t n4 = (size_t)a->nbrows * 4;
  sessile_bmg_options o = opts32();
  sessile_bmg *mg = NULL, *mw = NULL;
  sessile_mat *m = NULL, *mc = NULL;
  sessile_vec *rv = NULL, *zv = NULL;
  t_must("bmg (fp32 cycle)", sessile_bmg_create(la, sc->box.n, &o, &mg));
  t_must("mat", sessile_mat_create_bcsr4(la, a, &m));
  t_must("bmg setup", sessile_bmg_setup(mg, m));
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &rv));
  t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &zv));
  double *z = t_dalloc(n4), *zr = t_dalloc(n4), *zs = t_dalloc(n4);
  t_must("upload", sessile_vec_upload(rv, b));
  t_must("vcycle", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, z));
  t_must("ref vcycle", sessile_ref_bmg_vcycle(mg, b, zr));
  double e = t_relerr(z, zr, n4);
  printf("    fp32 cycle - fp64 reference: %.2e (max, relative)\n", e);
  t_check("fp32 device V-cycle = fp64 reference within fp32 rounding (max rel)", e, 1e-4);
  t_true("... and is not the fp64 cycle (it runs in fp32)", e > 0);
  sessile_la_options so;
  sessile_la_options_default(&so);
  so.spmv_storage = 1;
  sessile_la_set_options(la, &so);
  t_must("vcycle (storage reads)", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, zs));
  sessile_la_options_default(&so);
  sessile_la_set_options(la, &so);
  t_true("fp32: storage reads = texel reads, bit for bit", memcmp(zs, z, n4 * sizeof *z) == 0);
  o.wg_max_nodes = 0;
  t_must("bmg (fp32, no one-workgroup smoothing)", sessile_bmg_create(la, sc->box.n, &o, &mw));
  t_must("bmg setup", sessile_bmg_setup(mw, m));
  t_must("vcycle", sessile_bmg_vcycle(mw, rv, zv));
  t_must("download", sessile_vec_download(zv, zs));
  t_true("fp32: one-workgroup smoothing = per-colour dispatches, bit for bit", memcmp(zs, z, n4 * sizeof *z) == 0);
  sessile_bmg_destroy(mw);
  guard32_checks(mg, rv, zv, b, z);
  /* the fine matrix and the cycle's fp32 copies in chunks of at most 256 KiB:
   * the fp32 copy is chunked for 4-byte values, so in about half the chunks */
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  lo.max_matrix_chunk_bytes = 256 << 10;
  sessile_la_set_options(la, &lo);
  t_must("mat (chunked)", sessile_mat_create_bcsr4(la, a, &mc));
  t_must("bmg setup (chunked)", sessile_bmg_setup(mg, mc));
  sessile_la_options_default(&lo);
  sessile_la_set_options(la, &lo);
  uint32_t c64 = sessile_mat_chunks(mc), c32 = mg->lv[0].m->nchunks;
  printf("    chunks of the fine matrix: %u in fp64, %u in the cycle's fp32 copy\n", c64, c32);
  t_true("the fp32 copy is in several chunks, fewer than the fp64 matrix's", c32 > 1 && c32 < c64);
  t_must("vcycle (chunked)", sessile_bmg_vcycle(mg, rv, zv));
  t_must("download", sessile_vec_download(zv, zs));
  t_check("fp32: chunked V-cycle = unchunked (max rel)", t_relerr(zs, z, n4), 1e-12);
  /* a second setup of the same pattern refreshes the fp32 copy on the device
   * from the fp64 chunks (bmg_vals32: 25 fp64 chunks over 13 fp32 ones) */
  double *zd = t_dalloc(n4);
  recast_cycle(mg, mc, 0, rv, zv, zd);
  double dc = t_relerr(zd, zs, n4);
  printf("    the device's cast against the host's: %s (max rel %.3g)\n",
         memcmp(zd, zs, n4 * sizeof *zd) ? "differs" : "the same bits", dc);
  t_check("fp32: the copy cast on the device = the host's, the cycle within an fp32 rounding (max rel)", dc, 1e-6);
  /* the device's cast reading storage (la option spmv_storage) instead of
   * texel views (bmg_vals32_tex): the same casts, the same bits */
  recast_cycle(mg, mc, 1, rv, zv, zs);
  t_true("fp32: the device's cast through storage reads = through texels, bit for bit",
         memcmp(zd, zs, n4 * sizeof *zd) == 0);
  free(zd);
  free(z), free(zr), free(zs);
  sessile_vec_destroy(rv), sessile_vec_destroy(zv);
  sessile_mat_destroy(m), sessile_mat_destroy(mc);
  sessile_bmg_destroy(mg);
}

/* The fluid's Newton solve from rest with the fp64 and the fp32 cycle. */
static void fluid_newton32(scene *sc) {
  sessile_fluid_result res[2];
  double *up[2];
  for (int k = 0; k < 2; k++) {
    sessile_fluid_params p;
    sessile_fluid_params_default(&p);
    p.pc = SESSILE_PC_MG;
    p.nested = 0; /* the same Newton steps from rest, step by step */
    p.mg.precision = k ? 32 : 64;
    up[k] = t_dalloc((size_t)sc->n * 4);
    t_must(k ? "fluid solve (fp32 cycle)" : "fluid solve (fp64 cycle)",
           sessile_fluid_solve(sc->fl, sc->solid, &p, up[k], &res[k]));
    for (int s = 0; s < res[k].nsteps; s++)
      printf("    %s cycle, Newton step %d: %d GMRES iterations, true relres %.2e\n", k ? "fp32" : "fp64", s + 1,
             res[k].step[s].lin_iterations, res[k].step[s].lin_relres);
  }
  t_check("fp32 cycle: the fp64 cycle's number of Newton steps (difference)", abs(res[1].nsteps - res[0].nsteps), 0);
  for (int s = 0; s < res[1].nsteps && s < res[0].nsteps; s++) {
    const sessile_fluid_step *a = &res[0].step[s], *b = &res[1].step[s];
    t_true("the step ran pc mg", b->lin_pc == SESSILE_PC_MG);
    t_check("fp32 cycle: true relres", b->lin_relres, 1e-6);
    t_check("fp32 cycle: GMRES iterations - fp64 cycle's (<= 2)", b->lin_iterations - a->lin_iterations, 2);
  }
  double d = 0;
  for (uint32_t i = 0; i < sc->n; i++)
    for (int c = 0; c < 3; c++) d = fmax(d, fabs(up[1][4 * i + c] - up[0][4 * i + c]));
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  printf("    velocities, fp32 - fp64 cycle: %.2e m/s (inlet %.2g m/s)\n", d, p.inlet[0]);
  t_check("fp32 cycle: velocities - fp64 cycle's (max, relative to the inlet)", d / p.inlet[0], 1e-4);
  free(up[0]), free(up[1]);
}

static int mg32_main(void) {
  gpu = t_gpu(0);
  t_must("la", sessile_la_create(gpu, &la));
  fp64 = sessile_la_real_bytes(la) == 8;
  if (!fp64) { /* precision 32 is then the fp32 context's own cycle: the same bits as 64 */
    scene sc;
    scene_make(3, 6.0, &sc);
    sessile_bcsr4 a;
    size_t n4 = (size_t)sc.n * 4;
    double *b = t_dalloc(n4), *z[2] = {t_dalloc(n4), t_dalloc(n4)};
    system_of(&sc, 1, &a, b);
    sessile_mat *m = NULL;
    sessile_vec *rv = NULL, *zv = NULL;
    t_must("mat", sessile_mat_create_bcsr4(la, &a, &m));
    t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &rv));
    t_must("vecs", sessile_vec_create(la, (uint32_t)n4, &zv));
    t_must("upload", sessile_vec_upload(rv, b));
    for (int k = 0; k < 2; k++) {
      sessile_bmg_options o = opts32();
      if (!k) sessile_bmg_options_default(&o);
      sessile_bmg *mg = NULL;
      t_must("bmg", sessile_bmg_create(la, sc.box.n, &o, &mg));
      t_must("bmg setup", sessile_bmg_setup(mg, m));
      t_must("vcycle", sessile_bmg_vcycle(mg, rv, zv));
      t_must("download", sessile_vec_download(zv, z[k]));
      sessile_bmg_destroy(mg);
    }
    t_true("fp32 context: precision 32 = 64, bit for bit", memcmp(z[0], z[1], n4 * sizeof *b) == 0);
    free(b), free(z[0]), free(z[1]);
    sessile_vec_destroy(rv), sessile_vec_destroy(zv);
    sessile_mat_destroy(m);
    sessile_bcsr4_free(&a);
    scene_free(&sc);
    sessile_la_destroy(la);
    return t_finish(gpu);
  }
  static const char *const kind[2] = {"Stokes", "Oseen Re 120"};
  for (int stokes = 1; stokes >= 0; stokes--) {
    double f[3];
    for (int lev = 2; lev <= 4; lev++) {
      scene sc;
      scene_make(lev, 6.0, &sc);
      sessile_bcsr4 a;
      double *b = t_dalloc((size_t)sc.n * 4);
      system_of(&sc, stokes, &a, b);
      sessile_bmg_options o64, o32 = opts32();
      sessile_bmg_options_default(&o64);
      int nl;
      double f64 = mg_factor(lev, stokes, 0, &a, b, &o64, &nl);
      f[lev - 2] = mg_factor(lev, stokes, 0, &a, b, &o32, &nl);
      printf("  %s %ux%ux%u: %d levels, factor fp32 cycle %.4f, fp64 cycle %.4f\n", kind[!stokes], sc.box.n[0],
             sc.box.n[1], sc.box.n[2], nl, f[lev - 2], f64);
      char what[128];
      snprintf(what, sizeof what, "%s %ux%ux%u: fp32-cycle factor", kind[!stokes], sc.box.n[0], sc.box.n[1],
               sc.box.n[2]);
      t_check(what, f[lev - 2], 0.5);
      snprintf(what, sizeof what, "%s %ux%ux%u: |fp32 - fp64 cycle factor|", kind[!stokes], sc.box.n[0],
               sc.box.n[1], sc.box.n[2]);
      t_check(what, fabs(f[lev - 2] - f64), 1e-5);
      if (lev == 3 && stokes) {
        vcycle32_checks(&sc, &a, b);
        gmres_kept_z(lev, &a, b);
        o32.smoother = SESSILE_BMG_JACOBI;
        o32.omega = 0.6;
        double fj = mg_factor(lev, stokes, 0, &a, b, &o32, &nl);
        printf("  fp32 cycle, block Jacobi (omega 0.6): factor %.3f\n", fj);
        t_check("fp32 cycle, block-Jacobi smoothing converges: factor", fj, 0.99);
      }
      sessile_bcsr4_free(&a);
      free(b);
      scene_free(&sc);
    }
    double lo = fmin(f[0], fmin(f[1], f[2])), hi = fmax(f[0], fmax(f[1], f[2]));
    char what[96];
    snprintf(what, sizeof what, "%s: fp32-cycle factors h-independent (max - min)", kind[!stokes]);
    t_check(what, hi - lo, 0.1);
  }
  scene sc;
  scene_make(3, 6.0, &sc);
  fluid_newton32(&sc);
  scene_free(&sc);
  sessile_la_destroy(la);
  return t_finish(gpu);
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  int fp32 = 0;
  if (argc == 2 && !strcmp(argv[1], "--mg32")) return mg32_main();
  /* --explore LEVEL PRE POST OMEGA CYCLE [RADIUS [MAX_LEVELS [COARSE_DENSE_MAX]]]: factors only
   * (LEVEL 2-5: 9x9x7 to 65x65x49; RADIUS the dome's in cm, 0 for none but
   * the floor's centre node; docs/fluid.md, "Multigrid") */
  if (argc >= 7 && argc <= 10 && !strcmp(argv[1], "--explore")) {
    gpu = t_gpu(0);
    fp64 = 1;
    explore = 1;
    if (argc >= 8) dome_radius = atof(argv[7]);
    t_must("la", sessile_la_create(gpu, &la));
    for (int stokes = 1; stokes >= 0; stokes--) {
      scene sc;
      scene_make(atoi(argv[2]), dome_radius, &sc);
      sessile_bcsr4 a;
      double *b = t_dalloc((size_t)sc.n * 4);
      system_of(&sc, stokes, &a, b);
      sessile_bmg_options o;
      sessile_bmg_options_default(&o);
      o.pre = atoi(argv[3]), o.post = atoi(argv[4]), o.omega = atof(argv[5]), o.cycle = atoi(argv[6]);
      if (argc >= 9) o.max_levels = atoi(argv[8]);
      if (argc >= 10) o.coarse_dense_max = (uint32_t)atoi(argv[9]);
      int nl;
      double f = mg_factor(atoi(argv[2]), stokes, 0, &a, b, &o, &nl);
      printf("%s: %u nodes, %d levels, factor %.3f\n", stokes ? "Stokes" : "Oseen", sc.n, nl, f);
      sessile_bcsr4_free(&a);
      free(b);
      scene_free(&sc);
    }
    sessile_la_destroy(la);
    return t_finish(gpu);
  }
  gpu = t_gpu_args(argc, argv, &fp32);
  fp64 = !fp32;
  t_must("la", sessile_la_create(gpu, &la));
  static const char *const kind[2] = {"Stokes", "Oseen Re 120"};
  for (int stokes = 1; stokes >= 0; stokes--) {
    double f[3];
    for (int lev = 2; lev <= 4; lev++) {
      scene sc;
      scene_make(lev, 6.0, &sc);
      sessile_bcsr4 a;
      double *b = t_dalloc((size_t)sc.n * 4);
      system_of(&sc, stokes, &a, b);
      sessile_bmg_options o;
      sessile_bmg_options_default(&o);
      int nl;
      if (lev < 4) { /* already divergent at 17x17x13: the finest grid's 4.6 s would show it again */
        double fg = mg_factor(lev, stokes, 1, &a, b, &o, &nl);
        printf("  %s %ux%ux%u: Galerkin coarse operators: factor %.3f\n", kind[!stokes], sc.box.n[0],
               sc.box.n[1], sc.box.n[2], fg);
      }
      f[lev - 2] = mg_factor(lev, stokes, 0, &a, b, &o, &nl);
      printf("  %s %ux%ux%u: %d levels, factor %.3f\n", kind[!stokes], sc.box.n[0], sc.box.n[1], sc.box.n[2],
             nl, f[lev - 2]);
      char what[96];
      snprintf(what, sizeof what, "%s %ux%ux%u: multigrid factor", kind[!stokes], sc.box.n[0], sc.box.n[1],
               sc.box.n[2]);
      t_check(what, f[lev - 2], 0.5);
      if (lev == 3 && stokes) {
        vcycle_checks(&sc, &a, b);
        o.smoother = SESSILE_BMG_JACOBI;
        o.omega = 0.6;
        double fj = mg_factor(lev, stokes, 0, &a, b, &o, &nl);
        printf("  block Jacobi (omega 0.6): factor %.3f\n", fj);
        t_check("block-Jacobi smoothing converges: factor", fj, 0.99);
        sessile_bmg_options_default(&o);
        o.cycle = 3; /* VW: V on the finest level, W below (bench fluid --mg-cycle vw) */
        double fvw = mg_factor(lev, stokes, 0, &a, b, &o, &nl);
        printf("  VW(2,2): factor %.3f\n", fvw);
        t_check("VW(2,2) cycle: factor", fvw, 0.5);
      }
      sessile_bcsr4_free(&a);
      free(b);
      scene_free(&sc);
    }
    double lo = fmin(f[0], fmin(f[1], f[2])), hi = fmax(f[0], fmax(f[1], f[2]));
    char what[96];
    snprintf(what, sizeof what, "%s: factors h-independent (max - min)", kind[!stokes]);
    t_check(what, hi - lo, 0.1);
  }
  {
    scene sc;
    scene_make(4, 6.0, &sc);
    fluid_newton(&sc);
    scene_free(&sc);
  }
  fallback();
  sessile_la_destroy(la);
  return t_finish(gpu);
}
