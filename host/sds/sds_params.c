/* The SDS model's scalar parameters as a table (sessile/sds/sds_run.h,
 * docs/sds.md "Parameters"): the model text's `NAME = value` lines over the
 * table's defaults, then --config and --set over both (the CLI).  Units:
 * lengths in model units u, time in model seconds s (docs/sds.md "Units").
 * "Paper" is Porter & McCormack, "prototype" the authors' code (read for
 * facts), "ours" our choice.  The defaults are those the loop used before
 * the table (sessile_sds_params_default, and 0 gravity for a model that
 * sets none), so a model gives the same bytes as before. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "sessile/sds/sds_process.h"
#include "sessile/sds/sds_run.h"

#define OFF(f) offsetof(sessile_sds_run_params, f)
#define OPEN_BOTH (SESSILE_PARAM_LO_OPEN | SESSILE_PARAM_HI_OPEN)

/* device_rules: sessile_sds_rules_kernel's order. */
static const char *const rules_kernel_names[] = {"generated", "bytecode", NULL};
/* device_fuse: sessile_sds_fuse's order. */
static const char *const fuse_names[] = {"auto", "always", "never", NULL};

static const sessile_param_desc descs[] = {
    {"sphere_radius", SESSILE_PT_REAL, OFF(sphere_radius), 1, 0, INFINITY, OPEN_BOTH, "u", "ours",
     "radius of the starting icosphere (a model with `surface` has none)", NULL},
    {"sphere_subdivisions", SESSILE_PT_INT, OFF(sphere_subdivisions), 2, 0, 5, 0, "", "ours",
     "subdivisions of the starting icosphere (2: 162 surface cells)", NULL},
    {"start_jitter", SESSILE_PT_REAL, OFF(start_jitter), 0, 0, 0.2, 0, "edges", "ours",
     "each starting sphere's vertex moved along its radius by this x the mean edge x a normal deviate (--seed)", NULL},
    {"start_symmetry", SESSILE_PT_INT, OFF(start_symmetry), 0, 0, 12, 0, "", "paper 3.7",
     "0: the icosphere; n >= 2: a ball with the mirror symmetry of n tips round the equator (tips at 360/n degrees)",
     NULL},
    {"tips_below", SESSILE_PT_BOOL, OFF(tips_below), 0, 0, 1, 0, "", "paper 3.6",
     "make sure an interior cell lies below each growing tip at the start", NULL},
    {"density", SESSILE_PT_REAL, OFF(density), 1, 0, INFINITY, OPEN_BOTH, "m/u^3", "paper 3.1.1",
     "uniform density: a cell's mass is density 4/3 pi r^3", NULL},
    {"edge_stiffness", SESSILE_PT_REAL, OFF(edge_stiffness), 1, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "u/s^2",
     "prototype", "edge spring stiffness k_edge (paper 3.2), scaled per edge by R'(m_a + m_b)", NULL},
    {"volume_stiffness", SESSILE_PT_REAL, OFF(volume_stiffness), 2, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "u/s^2",
     "prototype", "tet (volume) spring stiffness k_vol (paper 3.2)", NULL},
    {"uniform_stiffness", SESSILE_PT_BOOL, OFF(uniform_stiffness), 0, 0, 1, 0, "", "paper 3.2",
     "true: every spring's stiffness is k_edge, k_vol itself (energies, m u^2/s^2), the paper's; false: the prototype's scaling", NULL},
    {"surface_multiplier", SESSILE_PT_REAL, OFF(surface_multiplier), 1, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "",
     "prototype", "stiffness of surface springs over internal ones (paper 3.2)", NULL},
    {"axial_stiffness", SESSILE_PT_REAL, OFF(axial_stiffness), 1, 0, INFINITY, OPEN_BOTH, "", "ours",
     "a surface spring born at angle a to the gradient of the morphogen declared axis=1 takes 1 + (this - 1) cos^2 a "
     "x its stiffness (1: isotropic; docs/sds.md, \"Axial stiffness\")", NULL},
    {"axial_growth", SESSILE_PT_REAL, OFF(axial_growth), 0, -0.5, 1, 0, "", "ours",
     "a growing cell's edge at angle a to the gradient of the morphogen declared axis=1 lengthens its rest length "
     "by 1 + this (3 cos^2 a - 1) x the growth (0: isotropic; 1: along the axis only; "
     "docs/sds.md, \"Oriented growth\")", NULL},
    {"convergent_extension", SESSILE_PT_REAL, OFF(convergent_extension), 0, 0, 1, 0, "1/s", "ours",
     "each step an edge between two cells whose state `extending` is set, at angle a to the gradient of the "
     "morphogen declared axis=1, multiplies its rest length by 1 + this dt (3 cos^2 a - 1): the tissue narrows "
     "across the axis and lengthens along it (0: none; docs/sds.md, \"Convergent extension\")", NULL},
    {"damping", SESSILE_PT_REAL, OFF(damping), 0.001, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "1/s", "prototype",
     "the tets' damping on dV/dt (paper 3.2; the prototype's kDamp)", NULL},
    {"viscosity", SESSILE_PT_REAL, OFF(viscosity), 1, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "1/s", "prototype",
     "viscous damping -c m v (paper 3.2; the prototype's 1 % per step at dt 0.01 as a rate)", NULL},
    {"gravity", SESSILE_PT_REAL, OFF(gravity), 0, -INFINITY, INFINITY, OPEN_BOTH, "u/s^2", "ours",
     "gravity along -z (paper 3.2 names it; the prototype's 10 crushes a body here)", NULL},
    {"self_collide", SESSILE_PT_BOOL, OFF(self_collide), 1, 0, 1, 0, "", "paper 3.2",
     "surface self-collision by spatial hashing (Teschner et al.)", NULL},
    {"obstacle_adhesion", SESSILE_PT_REAL, OFF(obstacle_adhesion), 0, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "u/s^2",
     "ours", "the rock's pull on a cell one to two contact distances from it: a tent peaking at this 1.5 contact "
     "distances out (paper 3.4: a form made to stick to an object; docs/sds.md)", NULL},
    {"obstacle_friction", SESSILE_PT_REAL, OFF(obstacle_friction), 0, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "1/s", "ours",
     "a cell within the rock's reach has its velocity along the rock relaxed at this rate (implicit; 0: frictionless)",
     NULL},
    {"dt", SESSILE_PT_REAL, OFF(dt), 1e-3, 0, INFINITY, OPEN_BOTH, "s", "ours",
     "the first physics step; the step control adapts it (paper 3.2: adaptive Verlet)", NULL},
    {"max_move", SESSILE_PT_REAL, OFF(max_move), 0.05, 0, 1, SESSILE_PARAM_LO_OPEN, "radii", "ours",
     "a step moving a cell further than this x its radius is undone and halved", NULL},
    {"stable_safety", SESSILE_PT_REAL, OFF(stable_safety), 0.8, 0, 1, SESSILE_PARAM_LO_OPEN, "", "ours",
     "steps stay below this fraction of the stable-step bound", NULL},
    {"mass_scaling_dt", SESSILE_PT_REAL, OFF(mass_scaling_dt), 0, 0, INFINITY, SESSILE_PARAM_HI_OPEN, "s", "ours",
     "selective mass scaling: a cell whose stable bound is below this step moves with the inertia that lifts its "
     "bound to it, its forces unchanged (0: none; docs/sds.md, \"Mass scaling\")", NULL},
    {"device_loop", SESSILE_PT_BOOL, OFF(device_loop), 0, 0, 1, 0, "", "ours",
     "true: between topology events the steps run in batches on the device, the rules and morphogens included "
     "(needs fp64 and rules the device can run); the same bytes as the host-driven loop (docs/sds.md)", NULL},
    {"device_rules", SESSILE_PT_ENUM, OFF(device_rules), 0, 0, 1, 0, "", "ours",
     "the device's rules kernel: generated (the rules written out as GLSL, compiled at model load) or bytecode (one "
     "interpreter for every model); the same bytes either way (docs/sds_rules.md, \"Generated kernel\")",
     rules_kernel_names},
    {"device_fuse", SESSILE_PT_ENUM, OFF(device_fuse), 0, 0, 2, 0, "", "ours",
     "where the fused kernels run (one dispatch for several): auto (small complexes, where the dispatches they "
     "save cost more than the code every invocation then runs: llvmpipe runs both sides of a branch; the kernels "
     "with a tail at any size on a CPU device, where they run on a few workgroups), always or never; the same "
     "bytes every way (docs/sds.md, \"Fewer dispatches a step\")",
     fuse_names},
};

const sessile_param_table sessile_sds_run_param_table = {
    "sds run MODEL", sizeof(sessile_sds_run_params), (int)(sizeof descs / sizeof descs[0]), descs, NULL, NULL, NULL};

/* A model line that sets a table parameter: one number, checked as --set
 * would check it ("%.17g" gives the parsed double back bit for bit). */
static sessile_status take_line(const sessile_param_desc *d, const sessile_sds_param *q, const char *where,
                                sessile_sds_run_params *p) {
  SESSILE_CHECK(q->nvalues == 1, SESSILE_ERR_USAGE, "%s:%d: %s takes one number", where, q->line, d->name);
  char text[40];
  snprintf(text, sizeof text, "%.17g", q->values[0]);
  /* the model's 0 and 1 are a flag's false and true */
  sessile_status st = sessile_params_set_text(&sessile_sds_run_param_table, p, d->name, text);
  if (st != SESSILE_OK) return sessile_error_set(st, "%s:%d: %s", where, q->line, sessile_error_message());
  return SESSILE_OK;
}

sessile_status sessile_sds_run_params_of_model(const char *text, const char *name, sessile_sds_run_params *p) {
  const char *where = name ? name : "model";
  sessile_sds_model *m = NULL;
  SESSILE_CALL(sessile_sds_model_parse(text, where, &m));
  const sessile_param_table *t = &sessile_sds_run_param_table;
  sessile_params_defaults(t, p);
  sessile_status st = SESSILE_OK;
  for (int i = 0; st == SESSILE_OK && i < t->count; i++) {
    const sessile_sds_param *q = sessile_sds_model_param_find(m, t->params[i].name);
    if (q) st = take_line(&t->params[i], q, where, p);
  }
  sessile_sds_model_destroy(m);
  return st;
}
