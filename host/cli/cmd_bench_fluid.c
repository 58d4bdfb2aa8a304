/* `sessile bench fluid`: the stationary Navier-Stokes solve on the default
 * scene (the initial dome on the immersed box at the fluid resolution): a
 * full solve from rest, then a warm-started re-solve after the sponge grew
 * a little, with assembly, every Newton step, linear iterations and times. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/fem/fluid.h"
#include "sessile/load.h"
#include "sessile/growth/growth_ref.h"
#include "sessile/mesh/tetmesh.h"

static const char *help =
    "usage: sessile bench fluid [--resolution R] [--pc NAME] [--ksp gmres|bicgstab] [--block-scale]\n"
    "                           [--picard K] [--restart M] [--no-lsic] [--no-compare]\n"
    "                           [--mg-smoother gs|jacobi] [--mg-sweeps N] [--mg-cycle v|w|vw] [--mg-galerkin]\n"
    "                           [--mg-wg-max N] [--mg-precision 64|32] [--baseline ilu0|storage] [--kernels]\n"
    "                           [--forcing fixed|ew] [--repeat N]\n"
    "                           [--set KEY=VALUE]...\n"
    "                           [--device D]\n"
    "\n"
    "Solves the stationary Navier-Stokes equations (P1-P1 with PSPG/SUPG/LSIC,\n"
    "Newton; docs/fluid.md) on the default box at box level R (default: the\n"
    "fluid_resolution parameter, 1) around the initial sponge dome: first from\n"
    "rest, then warm-started after the sponge grew by 0.3 cm (a growth\n"
    "iteration's worth).  Prints each Newton step: residual, linear iterations,\n"
    "true linear residual, assembly and solve time.  Figures are for the record\n"
    "(docs/performance.md), never pass/fail.  The solver choices are the grow\n"
    "table's fluid_ksp_type, fluid_pc_type, fluid_ksp_rtol, fluid_ksp_max_it,\n"
    "fluid_ksp_restart, fluid_newton_rtol, fluid_newton_max_it, fluid_nested,\n"
    "fluid_mg_precision, fluid_mg_cycle, fluid_mg_sweeps and fluid_newton_forcing (--set;\n"
    "docs/fluid.md: a start far from the solution, here from rest, begins from the\n"
    "solution on the box of twice the spacing; --set fluid_nested=false for plain\n"
    "Newton from rest); the\n"
    "flags are short for some: --pc NAME is --set fluid_pc_type=NAME (none, jacobi,\n"
    "ilu0, block_jacobi, mg; docs/la.md), mg (block multigrid) by default (ilu0 runs\n"
    "Jacobi where the matrix exceeds maxStorageBufferRange and is stored in chunks;\n"
    "the pc column says which ran); --ksp K is --set fluid_ksp_type=K; --restart M is\n"
    "--set fluid_ksp_restart=M (GMRES(M)); --mg-precision B is --set\n"
    "fluid_mg_precision=B (pc mg's cycle in 32 bits inside the fp64 GMRES, the\n"
    "default, or in 64; on an fp32 device it is fp32 either way); --mg-cycle C is\n"
    "--set fluid_mg_cycle=C; --block-scale is --pc block_jacobi (the inverse of each\n"
    "node's 4x4 diagonal block); --forcing F is --set fluid_newton_forcing=F: the\n"
    "bench solves every Newton step's linear system to fluid_ksp_rtol (fixed, the\n"
    "paper's 1e-6, where the preconditioners are compared) unless told ew (grow's\n"
    "default, Eisenstat-Walker: docs/fluid.md).  --picard K takes K Picard (Oseen) steps before\n"
    "Newton; --no-lsic drops the grad-div term.  --verbose prints each step to stderr\n"
    "as it goes.\n";
/* the rest of --help (one literal would pass the 4095 characters C17 promises) */
static const char *help2 =
    "\n"
    "Unless --no-compare (or the pc is ilu0), the same two solves run first with\n"
    "ilu0 (--baseline storage: the chosen pc reading its matrices through storage\n"
    "buffers instead of texel buffers, the la option spmv_storage: the same bits),\n"
    "then with the chosen pc, and a last table compares them: Newton steps,\n"
    "GMRES iterations per step, wall and CPU seconds (the process's, lavapipe's\n"
    "threads included: on a loaded machine the fairer figure) and the ratios.\n"
    "pc mg's hierarchy (docs/fluid.md, \"Multigrid\"): --mg-smoother (8-colour block\n"
    "Gauss-Seidel, default, or block Jacobi with omega 0.6), --mg-sweeps N (--set\n"
    "fluid_mg_sweeps=N: sweeps before and after each coarse correction, default 3),\n"
    "--mg-cycle (v, w, the default, or vw: V on the finest level, W below),\n"
    "--mg-galerkin (Galerkin coarse operators instead of the rediscretised ones),\n"
    "--mg-wg-max N (levels of at most N nodes smoothed in one workgroup, one dispatch\n"
    "for all their sweeps; default 1024, 0: never).\n"
    "--kernels: after the chosen pc's two solves, the device time of each kernel in\n"
    "them (timestamps around every dispatch; the baseline's are not timed; the first\n"
    "round only).\n"
    "--repeat N: N rounds (1-20; default 3 at level 1, 1 above), each the baseline's\n"
    "two solves then the chosen pc's, alternated so that the machine's drift falls\n"
    "on both; the first round prints every Newton step, later ones a line a pc, and\n"
    "the table gives the median wall and CPU seconds over the rounds (their range\n"
    "beside) and the ratios of the medians, each round's ratio listed.  The solves\n"
    "are deterministic: every round takes the same steps and iterations (a round that\n"
    "does not is reported).\n";

/* The grow table's parameter a short flag sets, or NULL. */
static const char *table_key(const char *flag) {
  static const char *const map[][2] = {{"--restart", "fluid_ksp_restart"}, {"--pc", "fluid_pc_type"},
                                       {"--ksp", "fluid_ksp_type"}, {"--mg-precision", "fluid_mg_precision"},
                                       {"--mg-cycle", "fluid_mg_cycle"}, {"--mg-sweeps", "fluid_mg_sweeps"},
                                       {"--forcing", "fluid_newton_forcing"}};
  for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
    if (!strcmp(flag, map[i][0])) return map[i][1];
  return NULL;
}

/* --verbose: the fluid solver's monitor lines to stderr. */
static void print_line(void *user, const char *line) {
  (void)user;
  fprintf(stderr, "%s\n", line);
}

static void print_result(const char *what, const sessile_fluid_result *r) {
  printf("%s: %s after %d steps, residual %.3e -> %.3e (rest state %.3e), %d linear iterations, %.2f s "
         "(assembly %.2f s, linear solves %.2f s)\n",
         what, r->converged ? "converged" : "NOT converged", r->nsteps, r->residual0, r->residual,
         r->residual_rest,
         r->lin_iterations, r->seconds, r->assembly_s, r->solve_s);
  if (r->coarse_tried)
    printf("  nested start (fluid_nested): the solution on the box of twice the spacing, %d Newton steps and %d "
           "linear iterations there (coarser boxes included), %.2f s of the total: %s\n", r->coarse_steps,
           r->coarse_lin_iterations, r->coarse_seconds, r->started_coarse ? "taken" : "not taken (the given start was nearer)");
  printf("  %4s %-7s %12s %8s %9s %12s %-14s %-12s %6s %10s %10s\n", "step", "kind", "residual", "lin its",
         "lin aim", "lin relres", "lin status", "pc", "chunks", "assembly s", "solve s");
  for (int k = 0; k < r->nsteps && k < SESSILE_FLUID_MAX_STEPS; k++) {
    const sessile_fluid_step *s = &r->step[k];
    printf("  %4d %-7s %12.4e %8d %9.1e %12.3e %-14s %-12s %6u %10.3f %10.3f\n", k + 1,
           s->picard ? "picard" : "newton", s->residual, s->lin_iterations, s->lin_rtol, s->lin_relres, sessile_solve_status_name(s->lin_status),
           sessile_pc_type_name(s->lin_pc), s->lin_chunks,
           s->assembly_s, s->solve_s);
  }
}

static sessile_status dome_mask(const sessile_box *b, double radius, double cx, double cy, uint8_t *solid) {
  sessile_surface s = {0};
  const double c[3] = {cx, cy, 0};
  SESSILE_CALL(sessile_surface_icosphere(4, radius, c, &s));
  for (uint32_t v = 0; v < s.nv; v++)
    if (s.pos[3 * v + 2] < 0) s.pos[3 * v + 2] = 0;
  uint32_t n = sessile_box_nodes(b);
  uint32_t *m = malloc((size_t)n * 4);
  sessile_status st = m ? sessile_growth_ref_classify(b, &s, m)
                        : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t i = 0; st == SESSILE_OK && i < n; i++) solid[i] = m[i] != 0;
  free(m);
  sessile_surface_free(&s);
  return st;
}

/* One preconditioner's pair of solves: from rest around the dome, then warm
 * after it grew by max_growth; CPU seconds of each into cpu[2]. */
static sessile_status run_pair(sessile_fluid *fl, const sessile_box *box, const sessile_grow_params *p,
                               const sessile_fluid_params *fp, uint8_t *solid, double *up,
                               sessile_fluid_result r[2], double cpu[2], int round) {
  double mx[3];
  sessile_box_max(box, mx);
  uint32_t n = sessile_box_nodes(box);
  memset(up, 0, (size_t)n * 4 * sizeof *up);
  if (!round) printf("--- preconditioner %s ---\n", sessile_pc_type_name(fp->pc));
  SESSILE_CALL(dome_mask(box, p->sponge_radius, mx[0] / 2, mx[1] / 2, solid));
  double c0 = cli_cpu_seconds();
  SESSILE_CALL(sessile_fluid_solve(fl, solid, fp, up, &r[0]));
  cpu[0] = cli_cpu_seconds() - c0;
  if (!round) print_result("full solve from rest", &r[0]);
  fflush(stdout);
  SESSILE_CALL(dome_mask(box, p->sponge_radius + p->max_growth, mx[0] / 2, mx[1] / 2, solid));
  for (uint32_t i = 0; i < n; i++)
    if (solid[i]) up[4 * i] = up[4 * i + 1] = up[4 * i + 2] = 0;
  c0 = cli_cpu_seconds();
  SESSILE_CALL(sessile_fluid_solve(fl, solid, fp, up, &r[1]));
  cpu[1] = cli_cpu_seconds() - c0;
  if (!round) {
    printf("\n");
    print_result("warm-started re-solve (sponge radius +0.3 cm)", &r[1]);
    printf("\n");
  } else {
    printf("round %d, %s: from rest %.2f s (%d steps, %d linear iterations), warm %.2f s (%d, %d)\n", round + 1,
           sessile_pc_type_name(fp->pc), r[0].seconds, r[0].nsteps, r[0].lin_iterations, r[1].seconds, r[1].nsteps,
           r[1].lin_iterations);
  }
  fflush(stdout);
  return SESSILE_OK;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The median of v[0..n-1] (n <= 20; v is left as it was). */
static double median_of(const double *v, int n) {
  double w[20];
  memcpy(w, v, (size_t)n * sizeof *w);
  qsort(w, (size_t)n, sizeof *w, cmp_double);
  return n % 2 ? w[n / 2] : 0.5 * (w[n / 2 - 1] + w[n / 2]);
}

/* The table of the pairs that ran over `rounds` rounds (r[round][pc][rest,
 * warm]; k0: 0 with the baseline, else 1): steps and iterations of the first
 * round, median seconds (and their range), and the ratios of the medians. */
static void print_compare(const sessile_fluid_result (*r)[2][2], const double (*cpu)[2][2], int rounds,
                          const char *name[2], int k0) {
  char cpuname[256];
  double load[3];
  sessile_load_average(load);
  printf("machine: %s\n", sessile_cpu_describe(cpuname, sizeof cpuname));
  printf("%s (load %.1f %.1f %.1f)%s:\n", k0 ? "summary" : "comparison in this run", load[0], load[1], load[2],
         rounds > 1 ? ", seconds the median over the rounds" : "");
  printf("  %-12s %-5s %5s %8s %9s %8s %9s %8s %8s %10s%s\n", "pc", "solve", "steps", "lin its", "its/step",
         "max its", "solve s", "pc set s", "total s", "cpu s", rounds > 1 ? "   total s over the rounds" : "");
  double med[2][2] = {{0, 0}, {0, 0}}, medc[2][2] = {{0, 0}, {0, 0}};
  for (int k = k0; k < 2; k++)
    for (int w = 0; w < 2; w++) {
      const sessile_fluid_result *x = &r[0][k][w];
      double tot[20], sol[20], set[20], cp[20];
      int same = 1;
      for (int q = 0; q < rounds; q++) {
        const sessile_fluid_result *y = &r[q][k][w];
        tot[q] = y->seconds, sol[q] = y->solve_s, cp[q] = cpu[q][k][w], set[q] = 0;
        for (int i = 0; i < y->nsteps; i++) set[q] += y->step[i].pc_setup_s;
        same &= y->nsteps == x->nsteps && y->lin_iterations == x->lin_iterations;
      }
      med[k][w] = median_of(tot, rounds), medc[k][w] = median_of(cp, rounds);
      int mx = 0;
      for (int i = 0; i < x->nsteps; i++)
        if (x->step[i].lin_iterations > mx) mx = x->step[i].lin_iterations;
      printf("  %-12s %-5s %5d %8d %9.1f %8d %9.2f %8.2f %8.2f %10.2f", name[k], w ? "warm" : "rest", x->nsteps,
             x->lin_iterations, x->nsteps ? (double)x->lin_iterations / x->nsteps : 0.0, mx, median_of(sol, rounds),
             median_of(set, rounds), med[k][w], medc[k][w]);
      if (rounds > 1) {
        qsort(tot, (size_t)rounds, sizeof *tot, cmp_double);
        printf("   %.2f-%.2f", tot[0], tot[rounds - 1]);
      }
      printf("%s%s\n", x->converged ? "" : "  NOT converged",
             same ? "" : "  (the rounds took different steps or iterations)");
    }
  for (int w = 0; w < 2 && !k0; w++) {
    printf("  %s: %s / %s = %.2fx in wall time, %.2fx in CPU time", w ? "warm" : "from rest", name[0], name[1],
           med[1][w] > 0 ? med[0][w] / med[1][w] : 0.0, medc[1][w] > 0 ? medc[0][w] / medc[1][w] : 0.0);
    if (rounds > 1) {
      printf(" (medians of %d rounds; each round's wall ratio:", rounds);
      for (int q = 0; q < rounds; q++)
        printf(" %.2f", r[q][1][w].seconds > 0 ? r[q][0][w].seconds / r[q][1][w].seconds : 0.0);
      printf(")");
    }
    printf("\n");
  }
}

int cmd_bench_fluid(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  sessile_grow_params p;
  sessile_params_default(&p);
  /* the preconditioners are compared at the paper's linear tolerance each
   * step (grow's default is ew; --forcing, --set) */
  p.fluid_newton_forcing = SESSILE_FLUID_FORCING_FIXED;
  unsigned res = 0;
  int picard = -1, lsic = -1, verbose = 0, compare = 1;
  sessile_bmg_options mgo;
  sessile_bmg_options_default(&mgo);
  int galerkin = 0, storage_base = 0, kernels = 0;
  unsigned repeat = 0; /* 0: the default, 3 at level 1 and 1 above */
  sessile_status s = SESSILE_OK;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (cli_stray_value("bench fluid", argv, i)) return EXIT_USAGE;
    int r = cli_gpu_option("bench fluid", argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(help, stdout);
      fputs(help2, stdout);
      return EXIT_OK;
    }
    if (!strcmp(a, "--block-scale") || !strcmp(a, "--no-block-scale")) {
      if (!strcmp(a, "--block-scale")) p.fluid_pc_type = SESSILE_PC_BLOCK_JACOBI;
      else if (p.fluid_pc_type == SESSILE_PC_BLOCK_JACOBI) /* back to the default */
        p.fluid_pc_type = (int)sessile_params_find(&sessile_grow_param_table, "fluid_pc_type")->def;
      continue;
    }
    if (!strcmp(a, "--kernels")) {
      kernels = 1;
      continue;
    }
    if (!strcmp(a, "--no-lsic")) {
      lsic = 0;
      continue;
    }
    if (!strcmp(a, "--verbose") || !strcmp(a, "--no-compare") || !strcmp(a, "--mg-galerkin")) {
      if (a[2] == 'v') verbose = 1;
      else if (a[2] == 'n') compare = 0;
      else galerkin = 1;
      continue;
    }
    static const char *const valued[] = {"--resolution", "--picard", "--restart", "--pc", "--ksp",
                                         "--mg-smoother", "--mg-sweeps", "--mg-cycle", "--mg-wg-max", "--mg-precision",
                                         "--baseline", "--forcing", "--repeat", "--set"};
    int k = 0;
    while (k < 14 && strcmp(a, valued[k])) k++;
    if (k == 14) return cli_usage_error("bench fluid", "unknown option '%.60s'", a);
    const char *v = cli_value("bench fluid", argc, argv, &i);
    if (!v || (k < 13 && cli_once("bench fluid", a, a))) return EXIT_USAGE; /* --set repeats */
    if (!strcmp(a, "--repeat")) {
      if (cli_parse_uint("bench fluid", a, v, 1, 20, &repeat)) return EXIT_USAGE;
      continue;
    }
    if (!strcmp(a, "--mg-wg-max")) {
      unsigned u;
      if (cli_parse_uint("bench fluid", a, v, 0, 1u << 30, &u)) return EXIT_USAGE;
      mgo.wg_max_nodes = u;
      continue;
    }
    if (!strcmp(a, "--baseline")) {
      if (strcmp(v, "ilu0") && strcmp(v, "storage"))
        return cli_usage_error("bench fluid", "--baseline: ilu0 or storage (got '%.40s')", v);
      storage_base = v[0] == 's';
      continue;
    }
    if (!strcmp(a, "--mg-smoother")) {
      if (strcmp(v, "gs") && strcmp(v, "jacobi"))
        return cli_usage_error("bench fluid", "--mg-smoother: gs or jacobi (got '%.40s')", v);
      mgo.smoother = v[0] == 'j' ? SESSILE_BMG_JACOBI : SESSILE_BMG_GAUSS_SEIDEL;
      if (v[0] == 'j') mgo.omega = 0.6;
      continue;
    }
    if (!strcmp(a, "--resolution")) {
      if (cli_parse_uint("bench fluid", a, v, 1, 4, &res)) return EXIT_USAGE;
    } else if (!strcmp(a, "--picard")) {
      unsigned u;
      if (cli_parse_uint("bench fluid", a, v, 0, SESSILE_FLUID_MAX_STEPS, &u)) return EXIT_USAGE;
      picard = (int)u;
    } else if (table_key(a)) { /* the table's parameters under a short flag: one parser, one list of names */
      s = sessile_params_set(&p, table_key(a), v);
      if (s != SESSILE_OK) return cli_usage_error("bench fluid", "%s: %s", a, sessile_error_message());
    } else if (!strcmp(a, "--set")) {
      s = cli_params_set_kv(&p, v);
      if (s != SESSILE_OK) return cli_fail(s);
    }
  }
  /* fluid_mg_precision (--mg-precision, --set): the table's range holds 33..63
   * too; the validation refuses them with its message */
  if (p.fluid_mg_precision != 64 && p.fluid_mg_precision != 32 && sessile_params_validate(&p) != SESSILE_OK)
    return cli_usage_error("bench fluid", "%s", sessile_error_message());
  if (!res) res = (unsigned)p.fluid_resolution;
  if (!repeat) repeat = res == 1 ? 3 : 1;
  sessile_box box;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p.box_cells_x, (uint32_t)p.box_cells_y, (uint32_t)p.box_cells_z};
  s = sessile_box_make(origin, p.box_base_cell, cells, (int)res, &box);
  if (s != SESSILE_OK) return cli_fail(s);

  sessile_gpu *g = NULL;
  sessile_la *la = NULL;
  sessile_fluid *fl = NULL;
  sessile_tetmesh mesh = {0};
  uint32_t n = sessile_box_nodes(&box);
  uint8_t *solid = malloc(n);
  double *up = calloc((size_t)n * 4, sizeof *up);
  if (!solid || !up) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) s = cli_gpu_create(&go, &g);
  if (s == SESSILE_OK) s = sessile_la_create(g, &la);
  double t0 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_tetmesh_from_box(&box, &mesh);
  if (s == SESSILE_OK) s = sessile_fluid_create(la, &mesh, &fl);
  double t_setup = sessile_wall_seconds() - t0;
  sessile_fluid_params fp;
  sessile_fluid_params_default(&fp);
  fp.rho = p.fluid_density;
  fp.eta = p.fluid_viscosity;
  fp.inlet[0] = p.inlet_velocity;
  fp.mg = mgo; /* the bench's own mg options; the table's (precision, cycle, sweeps) over them */
  sessile_params_fluid_solver(&p, &fp);
  if (picard >= 0) fp.picard_steps = picard;
  if (lsic >= 0) fp.lsic = lsic;
  if (verbose) fp.monitor = print_line;
  fp.mg_galerkin = galerkin;
  if (s == SESSILE_OK) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(g);
    printf("sessile bench fluid: device %s (%s), driver %s, fp%d\n", gi->name, gi->type, gi->driver,
           gi->precision);
    printf("box level %u: %u x %u x %u = %u nodes (%u unknowns), %u tets, spacing %.3g cm; "
           "%s + %s, Re = rho U L / eta = %.0f (L = 12 cm)\n",
           res, box.n[0], box.n[1], box.n[2], n, 4 * n, mesh.ntets, box.h,
           sessile_ksp_type_name(fp.ksp), sessile_pc_type_name(fp.pc),
           p.fluid_density * p.inlet_velocity * 0.12 / p.fluid_viscosity);
    if (fp.pc == SESSILE_PC_MG)
      printf("pc mg: %s smoother, %d+%d sweeps, %s-cycle in fp%d, %s coarse operators, levels of at most %u nodes "
             "smoothed in one workgroup\n",
             mgo.smoother == SESSILE_BMG_JACOBI ? "block Jacobi" : "8-colour block Gauss-Seidel", fp.mg.pre, fp.mg.post,
             fp.mg.cycle == 3 ? "VW" : fp.mg.cycle == 2 ? "W" : "V", gi->precision == 32 ? 32 : fp.mg.precision,
             galerkin ? "Galerkin" : "rediscretised", mgo.wg_max_nodes);
    if (fp.forcing == SESSILE_FLUID_FORCING_EW)
      printf("Newton to %g of the rest state's residual; each linear solve to the Eisenstat-Walker "
             "tolerance, at least %g (--forcing ew)\n", fp.newton_rtol, fp.linear_rtol);
    else
      printf("Newton to %g of the rest state's residual; each linear solve to %g (--forcing fixed)\n",
             fp.newton_rtol, fp.linear_rtol);
    printf("mesh and solver setup: %.2f s\n\n", t_setup);
    fflush(stdout);
  }
  /* ilu0 first (the reference), then the chosen pc */
  sessile_fluid_result (*r)[2][2] = calloc(repeat, sizeof *r);
  double (*cpu)[2][2] = calloc(repeat, sizeof *cpu);
  char base_name[48];
  snprintf(base_name, sizeof base_name, "%s-storage", sessile_pc_type_name(fp.pc));
  const char *name[2] = {storage_base ? base_name : "ilu0", sessile_pc_type_name(fp.pc)};
  if ((!r || !cpu) && s == SESSILE_OK) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  int both = compare && (fp.pc != SESSILE_PC_ILU0 || storage_base);
  if (s == SESSILE_OK && repeat > 1) printf("%u rounds, alternated; the first in full\n\n", repeat);
  for (unsigned q = 0; q < repeat && s == SESSILE_OK; q++)
  for (int k = both ? 0 : 1; k < 2 && s == SESSILE_OK; k++) {
    sessile_fluid_params qp = fp;
    /* the baseline: ilu0, or the same pc with storage reads (the option is
     * read when a pass is recorded) */
    sessile_la_options lo;
    sessile_la_options_default(&lo);
    lo.spmv_storage = k == 0 && storage_base;
    sessile_la_set_options(la, &lo);
    if (k == 0 && !storage_base) qp.pc = SESSILE_PC_ILU0;
    int prof = k == 1 && kernels && q == 0;
    if (prof) s = sessile_gpu_profile(g, 1);
    double w0 = sessile_wall_seconds();
    if (s == SESSILE_OK) s = run_pair(fl, &box, &p, &qp, solid, up, r[q][k], cpu[q][k], (int)q);
    if (s == SESSILE_OK && prof) {
      char what[64];
      snprintf(what, sizeof what, "the %s solves (from rest and warm)", name[1]);
      cli_print_kernels(g, what, sessile_wall_seconds() - w0);
      s = sessile_gpu_profile(g, 0);
    }
  }
  if (s == SESSILE_OK)
    print_compare((const sessile_fluid_result(*)[2][2])r, (const double(*)[2][2])cpu, (int)repeat, name, !both);
  free(r);
  free(cpu);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&mesh);
  sessile_la_destroy(la);
  sessile_gpu_destroy(g);
  free(solid);
  free(up);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
