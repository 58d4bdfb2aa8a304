/* The fluid's solver choices in the grow table (fluid_ksp_type,
 * fluid_pc_type, fluid_ksp_rtol, fluid_ksp_max_it, fluid_ksp_restart,
 * fluid_newton_rtol, fluid_newton_max_it, fluid_nested, fluid_mg_precision,
 * fluid_mg_cycle, fluid_mg_sweeps, fluid_newton_forcing): the table's defaults map onto the
 * fluid library's own defaults (today's behaviour) but for the forcing (the
 * table's ew, the library's the paper's fixed), fluid_pc_type's names are the
 * pc registry's (every registered pc but mg, in sessile_pc_type's order),
 * every value set by name arrives in sessile_fluid_params (a precision
 * other than 64 or 32 is refused, and sweeps outside 1-8), the memory estimate counts the fp32
 * cycle's copies, and a small flow solve reports the Krylov method and
 * preconditioner it ran with. */
#include <stdlib.h>
#include <string.h>
#include "sessile/fem/fluid.h"
#include "sessile/growth/grow_params.h"
#include "sessile/la/pc.h"
#include "sessile/mesh/box.h"
#include "sessile/mesh/tetmesh.h"
#include "testutil.h"

static void defaults_are_the_fluids(void) {
  sessile_grow_params p;
  sessile_params_default(&p);
  sessile_fluid_params lib, got;
  sessile_fluid_params_default(&lib);
  sessile_fluid_params_default(&got);
  /* Poison the fields the mapping must write. */
  got.ksp = SESSILE_KSP_CG;
  got.pc = SESSILE_PC_BLOCK_JACOBI;
  got.linear_rtol = got.newton_rtol = -1;
  got.linear_max = got.restart = got.newton_max = got.nested = got.mg.precision = -1;
  got.mg.pre = got.mg.post = -1;
  sessile_params_fluid_solver(&p, &got);
  t_true("default fluid_ksp_type is the fluid's (gmres)", got.ksp == lib.ksp);
  t_true("default fluid_pc_type is the fluid's (mg)", got.pc == lib.pc);
  t_check("default fluid_ksp_rtol", got.linear_rtol - lib.linear_rtol, 0);
  t_check("default fluid_ksp_max_it", got.linear_max - lib.linear_max, 0);
  t_check("default fluid_ksp_restart", got.restart - lib.restart, 0);
  t_check("default fluid_newton_rtol", got.newton_rtol - lib.newton_rtol, 0);
  t_check("default fluid_newton_max_it", got.newton_max - lib.newton_max, 0);
  t_check("default fluid_nested", got.nested - lib.nested, 0);
  t_check("default fluid_mg_precision (32, the fluid's)", got.mg.precision - lib.mg.precision, 0);
  t_check("... which is 32", got.mg.precision - 32, 0);
  t_check("default fluid_mg_sweeps: the fluid's pre-smoothing", got.mg.pre - lib.mg.pre, 0);
  t_check("... and post-smoothing", got.mg.post - lib.mg.post, 0);
  t_check("... which are 3", got.mg.pre - 3, 0);
  t_true("the library's forcing is the paper's (fixed)", lib.forcing == SESSILE_FLUID_FORCING_FIXED);
  t_true("the table's fluid_newton_forcing is ew (docs/fluid.md)", got.forcing == SESSILE_FLUID_FORCING_EW);
  /* The mapping touches only the solver's fields. */
  got.ksp = lib.ksp, got.pc = lib.pc, got.linear_rtol = lib.linear_rtol, got.linear_max = lib.linear_max;
  got.restart = lib.restart, got.newton_rtol = lib.newton_rtol, got.newton_max = lib.newton_max;
  got.nested = lib.nested, got.mg.precision = lib.mg.precision, got.forcing = lib.forcing;
  got.mg.pre = lib.mg.pre, got.mg.post = lib.mg.post;
  t_true("no other field changed", memcmp(&got, &lib, sizeof got) == 0);
}

static void pc_names_are_the_registry(void) {
  const sessile_param_desc *d = sessile_params_find(&sessile_grow_param_table, "fluid_pc_type");
  t_true("fluid_pc_type is in the table", d && d->type == SESSILE_PT_ENUM);
  if (!d) return;
  int n = 0;
  for (; d->names[n]; n++) {
    sessile_pc_type t;
    t_ok(d->names[n], sessile_pc_type_from_name(d->names[n], &t));
    t_true("the name's index is its sessile_pc_type", (int)t == n);
  }
  int registered = 0;
  for (int i = 0; sessile_pc_registered(i); i++) {
    const char *name = sessile_pc_registered(i);
    int found = 0;
    for (int k = 0; k < n; k++) found |= !strcmp(d->names[k], name);
    t_true(name, found); /* every pc is offered (mg: the block multigrid) */
    registered++;
  }
  t_check("offered: every registered pc", n - registered, 0);
}

static void set_by_name(sessile_grow_params *p, sessile_fluid_params *fp) {
  sessile_params_default(p);
  t_ok("fluid_ksp_type", sessile_params_set(p, "fluid_ksp_type", "bicgstab"));
  t_ok("fluid_pc_type", sessile_params_set(p, "fluid_pc_type", "block_jacobi"));
  t_ok("fluid_ksp_rtol", sessile_params_set(p, "fluid_ksp_rtol", "1e-9"));
  t_ok("fluid_ksp_max_it", sessile_params_set(p, "fluid_ksp_max_it", "300"));
  t_ok("fluid_ksp_restart", sessile_params_set(p, "fluid_ksp_restart", "20"));
  t_ok("fluid_newton_rtol", sessile_params_set(p, "fluid_newton_rtol", "1e-5"));
  t_ok("fluid_newton_max_it", sessile_params_set(p, "fluid_newton_max_it", "7"));
  t_ok("fluid_nested", sessile_params_set(p, "fluid_nested", "false"));
  t_ok("fluid_mg_precision", sessile_params_set(p, "fluid_mg_precision", "64"));
  t_ok("fluid_mg_sweeps", sessile_params_set(p, "fluid_mg_sweeps", "2"));
  t_ok("fluid_newton_forcing", sessile_params_set(p, "fluid_newton_forcing", "fixed"));
  t_ok("valid", sessile_params_validate(p));
  sessile_fluid_params_default(fp);
  sessile_params_fluid_solver(p, fp);
  t_true("bicgstab arrives", fp->ksp == SESSILE_KSP_BICGSTAB);
  t_true("block_jacobi arrives", fp->pc == SESSILE_PC_BLOCK_JACOBI);
  t_check("rtol arrives", fp->linear_rtol - 1e-9, 0);
  t_check("max_it arrives", fp->linear_max - 300, 0);
  t_check("restart arrives", fp->restart - 20, 0);
  t_check("Newton rtol arrives", fp->newton_rtol - 1e-5, 0);
  t_check("Newton max arrives", fp->newton_max - 7, 0);
  t_check("nested off arrives", fp->nested, 0);
  t_check("fluid_mg_precision 64 arrives", fp->mg.precision - 64, 0);
  t_check("fluid_mg_sweeps 2 arrives (pre)", fp->mg.pre - 2, 0);
  t_check("fluid_mg_sweeps 2 arrives (post)", fp->mg.post - 2, 0);
  t_true("fluid_newton_forcing fixed arrives", fp->forcing == SESSILE_FLUID_FORCING_FIXED);
  /* Refused by name: an unknown pc, cg (nonsymmetric Jacobian), a restart
   * past la's GMRES basis. */
  sessile_grow_params q = *p;
  t_true("fluid_pc_type=amg refused", sessile_params_set(&q, "fluid_pc_type", "amg") == SESSILE_ERR_USAGE);
  t_true("fluid_ksp_type=cg refused", sessile_params_set(&q, "fluid_ksp_type", "cg") == SESSILE_ERR_USAGE);
  t_true("fluid_ksp_restart=65 refused", sessile_params_set(&q, "fluid_ksp_restart", "65") == SESSILE_ERR_USAGE);
  t_true("fluid_mg_precision=16 refused", sessile_params_set(&q, "fluid_mg_precision", "16") == SESSILE_ERR_USAGE);
  t_true("fluid_mg_sweeps=0 refused", sessile_params_set(&q, "fluid_mg_sweeps", "0") == SESSILE_ERR_USAGE);
  t_true("fluid_mg_sweeps=9 refused", sessile_params_set(&q, "fluid_mg_sweeps", "9") == SESSILE_ERR_USAGE);
  t_true("fluid_newton_forcing=exact refused", sessile_params_set(&q, "fluid_newton_forcing", "exact") == SESSILE_ERR_USAGE);
  t_true("refusals leave the values", memcmp(&q, p, sizeof q) == 0);
  t_ok("fluid_mg_precision=48 is in the table's range ...", sessile_params_set(&q, "fluid_mg_precision", "48"));
  t_true("... but refused by the validation", sessile_params_validate(&q) == SESSILE_ERR_USAGE);
  /* the memory estimate with the flow on: the fp32 cycle adds its copies */
  sessile_grow_params e64, e32;
  sessile_params_default(&e64);
  t_ok("diffusion_limited", sessile_params_set(&e64, "diffusion_limited", "false"));
  t_ok("fluid_mg_precision 64", sessile_params_set(&e64, "fluid_mg_precision", "64"));
  e32 = e64;
  t_ok("fluid_mg_precision", sessile_params_set(&e32, "fluid_mg_precision", "32"));
  double b64 = sessile_params_device_bytes(&e64), b32 = sessile_params_device_bytes(&e32);
  printf("  memory estimate with the flow: %.1f MiB (fp64 cycle), %.1f MiB (fp32 cycle)\n", b64 / 1048576,
         b32 / 1048576);
  t_true("the estimate counts the fp32 cycle's copies", b32 > b64);
  sessile_grow_params ej = e64;
  t_ok("fluid_pc_type jacobi", sessile_params_set(&ej, "fluid_pc_type", "jacobi"));
  t_true("... and GMRES's kept z_j for a pc that is not diagonal", sessile_params_device_bytes(&ej) < b64);
}

/* A Stokes-like flow in a small empty box (inflow at x-min, no solid): the
 * steps report the method and preconditioner the table chose. */
static void reaches_the_solver(sessile_gpu *g, const sessile_fluid_params *chosen) {
  sessile_la *la = NULL;
  sessile_fluid *fl = NULL;
  sessile_tetmesh mesh = {0};
  sessile_box box;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {4, 4, 3};
  t_must("box", sessile_box_make(origin, 1.0, cells, 1, &box));
  t_must("la", sessile_la_create(g, &la));
  t_must("mesh", sessile_tetmesh_from_box(&box, &mesh));
  t_must("fluid", sessile_fluid_create(la, &mesh, &fl));
  uint32_t n = sessile_box_nodes(&box);
  double *up = calloc((size_t)n * 4, sizeof *up);
  t_true("memory", up != NULL);
  sessile_fluid_params fp = *chosen;
  fp.newton_max = 3;
  sessile_fluid_result res;
  memset(&res, 0, sizeof res);
  t_ok("solve", sessile_fluid_solve(fl, NULL, &fp, up, &res));
  t_true("at least one step", res.nsteps >= 1);
  for (int k = 0; k < res.nsteps; k++) {
    t_true("step ran bicgstab", res.step[k].lin_ksp == SESSILE_KSP_BICGSTAB);
    t_true("step ran block_jacobi", res.step[k].lin_pc == SESSILE_PC_BLOCK_JACOBI);
  }
  free(up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&mesh);
  sessile_la_destroy(la);
}

int main(void) {
  defaults_are_the_fluids();
  pc_names_are_the_registry();
  sessile_grow_params p;
  sessile_fluid_params fp;
  set_by_name(&p, &fp);
  sessile_gpu *g = t_gpu(0);
  reaches_the_solver(g, &fp);
  return t_finish(g);
}
