/* `sessile bench fluid`: the stationary Navier-Stokes solve on the default
 * scene (the initial dome on the immersed box at the fluid resolution): a
 * full solve from rest, then a warm-started re-solve after the sponge grew
 * a little, with assembly, every Newton step, linear iterations and times. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/fem/fluid.h"
#include "sessile/growth/growth_ref.h"
#include "sessile/mesh/tetmesh.h"

static const char *help =
    "usage: sessile bench fluid [--resolution R] [--pc NAME] [--ksp gmres|bicgstab] [--block-scale]\n"
    "                           [--picard K] [--restart M] [--no-lsic]\n"
    "                           [--set KEY=VALUE]... [--device D]\n"
    "\n"
    "Solves the stationary Navier-Stokes equations (P1-P1 with PSPG/SUPG/LSIC,\n"
    "Newton; docs/fluid.md) on the default box at box level R (default: the\n"
    "fluid_resolution parameter, 1) around the initial sponge dome: first from\n"
    "rest, then warm-started after the sponge grew by 0.3 cm (a growth\n"
    "iteration's worth).  Prints each Newton step: residual, linear iterations,\n"
    "true linear residual, assembly and solve time.  Figures are for the record\n"
    "(docs/performance.md), never pass/fail.  The solver choices are the grow\n"
    "table's fluid_ksp_type, fluid_pc_type, fluid_ksp_rtol, fluid_ksp_max_it,\n"
    "fluid_ksp_restart, fluid_newton_rtol and fluid_newton_max_it (--set; docs/fluid.md); the\n"
    "flags are short for some: --pc NAME is --set fluid_pc_type=NAME (none, jacobi,\n"
    "ilu0, block_jacobi; docs/la.md), ILU(0) by default (Jacobi where the matrix\n"
    "exceeds maxStorageBufferRange and is stored in chunks; the pc column says which\n"
    "ran); --ksp K is --set fluid_ksp_type=K; --restart M is --set fluid_ksp_restart=M\n"
    "(GMRES(M)); --block-scale is --pc block_jacobi (the inverse of each node's 4x4\n"
    "diagonal block).  --picard K takes K Picard (Oseen) steps before Newton;\n"
    "--no-lsic drops the grad-div term.  --verbose prints each step to stderr as it goes.\n";

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
  printf("  %4s %-7s %12s %8s %12s %-14s %-12s %6s %10s %10s\n", "step", "kind", "residual", "lin its",
         "lin relres", "lin status", "pc", "chunks", "assembly s", "solve s");
  for (int k = 0; k < r->nsteps && k < SESSILE_FLUID_MAX_STEPS; k++) {
    const sessile_fluid_step *s = &r->step[k];
    printf("  %4d %-7s %12.4e %8d %12.3e %-14s %-12s %6u %10.3f %10.3f\n", k + 1, s->picard ? "picard" : "newton",
           s->residual, s->lin_iterations, s->lin_relres, sessile_solve_status_name(s->lin_status),
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

int cmd_bench_fluid(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  sessile_grow_params p;
  sessile_params_default(&p);
  unsigned res = 0;
  int picard = -1, lsic = -1, verbose = 0;
  sessile_status s = SESSILE_OK;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (cli_stray_value("bench fluid", argv, i)) return EXIT_USAGE;
    int r = cli_gpu_option("bench fluid", argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(a, "--block-scale") || !strcmp(a, "--no-block-scale")) {
      if (!strcmp(a, "--block-scale")) p.fluid_pc_type = SESSILE_PC_BLOCK_JACOBI;
      else if (p.fluid_pc_type == SESSILE_PC_BLOCK_JACOBI) /* back to the default */
        p.fluid_pc_type = (int)sessile_params_find(&sessile_grow_param_table, "fluid_pc_type")->def;
      continue;
    }
    if (!strcmp(a, "--no-lsic")) {
      lsic = 0;
      continue;
    }
    if (!strcmp(a, "--verbose")) {
      verbose = 1;
      continue;
    }
    static const char *const valued[] = {"--resolution", "--picard", "--restart", "--pc", "--ksp", "--set"};
    int k = 0;
    while (k < 6 && strcmp(a, valued[k])) k++;
    if (k == 6) return cli_usage_error("bench fluid", "unknown option '%.60s'", a);
    const char *v = cli_value("bench fluid", argc, argv, &i);
    if (!v || (k < 5 && cli_once("bench fluid", a, a))) return EXIT_USAGE; /* --set repeats */
    if (!strcmp(a, "--resolution")) {
      if (cli_parse_uint("bench fluid", a, v, 1, 4, &res)) return EXIT_USAGE;
    } else if (!strcmp(a, "--picard")) {
      unsigned u;
      if (cli_parse_uint("bench fluid", a, v, 0, SESSILE_FLUID_MAX_STEPS, &u)) return EXIT_USAGE;
      picard = (int)u;
    } else if (!strcmp(a, "--restart") || !strcmp(a, "--pc") || !strcmp(a, "--ksp")) {
      /* the table's parameters under a short flag: one parser, one list of names */
      const char *key = a[2] == 'r' ? "fluid_ksp_restart" : a[2] == 'p' ? "fluid_pc_type" : "fluid_ksp_type";
      s = sessile_params_set(&p, key, v);
      if (s != SESSILE_OK) return cli_usage_error("bench fluid", "%s: %s", a, sessile_error_message());
    } else if (!strcmp(a, "--set")) {
      s = cli_params_set_kv(&p, v);
      if (s != SESSILE_OK) return cli_fail(s);
    }
  }
  if (!res) res = (unsigned)p.fluid_resolution;
  sessile_box box;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p.box_cells_x, (uint32_t)p.box_cells_y, (uint32_t)p.box_cells_z};
  s = sessile_box_make(origin, p.box_base_cell, cells, (int)res, &box);
  if (s != SESSILE_OK) return cli_fail(s);
  double mx[3];
  sessile_box_max(&box, mx);

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
  sessile_params_fluid_solver(&p, &fp);
  if (picard >= 0) fp.picard_steps = picard;
  if (lsic >= 0) fp.lsic = lsic;
  if (verbose) fp.monitor = print_line;
  if (s == SESSILE_OK) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(g);
    printf("sessile bench fluid: device %s (%s), driver %s, fp%d\n", gi->name, gi->type, gi->driver,
           gi->precision);
    printf("box level %u: %u x %u x %u = %u nodes (%u unknowns), %u tets, spacing %.3g cm; "
           "%s + %s, Re = rho U L / eta = %.0f (L = 12 cm)\n",
           res, box.n[0], box.n[1], box.n[2], n, 4 * n, mesh.ntets, box.h,
           sessile_ksp_type_name(fp.ksp), sessile_pc_type_name(fp.pc),
           p.fluid_density * p.inlet_velocity * 0.12 / p.fluid_viscosity);
    printf("mesh and solver setup: %.2f s\n\n", t_setup);
    fflush(stdout);
    s = dome_mask(&box, p.sponge_radius, mx[0] / 2, mx[1] / 2, solid);
  }
  sessile_fluid_result r1, r2;
  if (s == SESSILE_OK) s = sessile_fluid_solve(fl, solid, &fp, up, &r1);
  if (s == SESSILE_OK) {
    print_result("full solve from rest", &r1);
    fflush(stdout);
    s = dome_mask(&box, p.sponge_radius + p.max_growth, mx[0] / 2, mx[1] / 2, solid);
  }
  if (s == SESSILE_OK) {
    for (uint32_t i = 0; i < n; i++)
      if (solid[i]) up[4 * i] = up[4 * i + 1] = up[4 * i + 2] = 0;
    s = sessile_fluid_solve(fl, solid, &fp, up, &r2);
  }
  if (s == SESSILE_OK) {
    printf("\n");
    print_result("warm-started re-solve (sponge radius +0.3 cm)", &r2);
  }
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&mesh);
  sessile_la_destroy(la);
  sessile_gpu_destroy(g);
  free(solid);
  free(up);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
