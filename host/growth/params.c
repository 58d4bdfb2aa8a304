/* The parameter table of `sessile grow` (sessile/growth/grow_params.h): the one source
 * of every default; presets; the checks that need no device. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "sessile/growth/grow_params.h"

static const char *const skeleton_names[] = {"radiate", "halichondrid", NULL};
static const char *const domain_names[] = {"immersed", "conforming", NULL};
static const char *const probe_names[] = {"flux", "paper", NULL};
static const char *const far_names[] = {"height", "walls", "inlet", NULL};
static const char *const solver_names[] = {"mg", "jacobi", NULL};
static const char *const translocate_names[] = {"parallel", "sequential", NULL};
static const char *const adv_names[] = {"cut", "tet", NULL};
/* fluid_ksp_type: sessile_fluid_ksp's order (CG is not offered: the fluid's
 * Jacobian is nonsymmetric). */
static const char *const ksp_names[] = {"gmres", "bicgstab", NULL};
/* fluid_pc_type: the pc registry's names (sessile/la/pc.h) indexed by
 * sessile_pc_type (mg: the block multigrid on the immersed box, ILU(0) on
 * the conforming mesh); tests/growth/test_grow_solver_params.c checks them
 * against the registry. */
static const char *const pc_names[] = {"none", "jacobi", "ilu0", "block_jacobi", "mg", NULL};
/* fluid_mg_cycle: sessile_fluid_cycle's order (bmg's cycle 1, 2, 3). */
static const char *const cycle_names[] = {"v", "w", "vw", NULL};
/* nutrient_inflow: SESSILE_INFLOW_*'s order. */
static const char *const inflow_names[] = {"profile", "zero_flux", NULL};
/* fluid_newton_forcing: sessile_fluid_forcing's order. */
static const char *const forcing_names[] = {"fixed", "ew", NULL};

#define PT_REAL SESSILE_PT_REAL, NULL
#define PT_INT SESSILE_PT_INT, NULL
#define PT_BOOL SESSILE_PT_BOOL, NULL
#define PT_ENUM_SKELETON SESSILE_PT_ENUM, skeleton_names
#define PT_ENUM_DOMAIN SESSILE_PT_ENUM, domain_names
#define PT_ENUM_PROBE SESSILE_PT_ENUM, probe_names
#define PT_ENUM_FAR SESSILE_PT_ENUM, far_names
#define PT_ENUM_SOLVER SESSILE_PT_ENUM, solver_names
#define PT_ENUM_TRANSLOCATE SESSILE_PT_ENUM, translocate_names
#define PT_ENUM_ADV SESSILE_PT_ENUM, adv_names
#define PT_ENUM_KSP SESSILE_PT_ENUM, ksp_names
#define PT_ENUM_PC SESSILE_PT_ENUM, pc_names
#define PT_ENUM_CYCLE SESSILE_PT_ENUM, cycle_names
#define PT_ENUM_FORCING SESSILE_PT_ENUM, forcing_names
#define PT_ENUM_INFLOW SESSILE_PT_ENUM, inflow_names
#define BOUNDS_0 0
#define BOUNDS_LO_OPEN SESSILE_PARAM_LO_OPEN
#define DESC(type_, names_, name, def, lo, hi, bounds, unit, src, desc) \
  {#name, type_, offsetof(sessile_grow_params, name), def, lo, hi, bounds, unit, src, desc, names_},
#define DESC_(...) DESC(__VA_ARGS__)

static const sessile_param_desc descs[] = {
#define X(name, type, def, lo, hi, bounds, unit, src, desc) \
  DESC_(PT_##type, name, def, lo, hi, BOUNDS_##bounds, unit, src, desc)
    SESSILE_PARAMS(X)
#undef X
};

static sessile_status validate(const void *values);

/* The solver parameters' earlier names (before the fluid_/nutrient_ prefixes,
 * docs/fluid.md): configs and stored runs that use them still read. */
static const sessile_param_alias aliases[] = {{"linear_rtol", "nutrient_ksp_rtol"},
                                              {"linear_max_iterations", "nutrient_ksp_max_it"},
                                              {"nutrient_solver", "nutrient_pc_type"},
                                              {"nvs_rtol", "fluid_newton_rtol"},
                                              {"max_nvs_iterations", "fluid_newton_max_it"},
                                              {NULL, NULL}};

/* Runs made before these parameters existed ran otherwise than their
 * defaults: every Newton step to the fixed tolerance, and no nested start;
 * they resume as they began (docs/run.md, docs/fluid.md). */
static const sessile_param_before before[] = {
    {"fluid_newton_forcing", "fixed"}, {"fluid_nested", "false"}, {"nutrient_inflow", "zero_flux"}, {NULL, NULL}};

const sessile_param_table sessile_grow_param_table = {
    "grow", sizeof(sessile_grow_params), (int)(sizeof descs / sizeof descs[0]), descs, validate, aliases, before};

void sessile_params_default(sessile_grow_params *p) { sessile_params_defaults(&sessile_grow_param_table, p); }

sessile_status sessile_params_set(sessile_grow_params *p, const char *key, const char *value) {
  return sessile_params_set_text(&sessile_grow_param_table, p, key, value);
}

sessile_status sessile_params_validate(const sessile_grow_params *p) {
  return sessile_params_check(&sessile_grow_param_table, p);
}

sessile_status sessile_params_preset(sessile_grow_params *p, const char *name) {
  sessile_params_default(p);
  if (strcmp(name, "radiate") == 0) return SESSILE_OK;
  if (strcmp(name, "crella") == 0) {
    /* Halichondrid skeleton (eqs 1-2) + randomised x/y position (§4.7); the
     * normal offset radius and the jitter are ours (docs/model.md says why). */
    p->skeletal_growth = SESSILE_SKELETON_HALICHONDRID;
    p->normal_offset_radius = 0.5;
    p->position_jitter = 4.0;
    return SESSILE_OK;
  }
  return sessile_error_set(SESSILE_ERR_USAGE, "unknown preset '%s' (presets: radiate, crella)", name);
}

/* The default far-field height scales with the sponge, not the box: 4.8
 * initial radii, 28.8 cm for the paper's 6 cm sponge (docs/nutrient.md).
 * Only where that cannot be met does the default bend: at most the box top
 * (a sponge too large for its box keeps the old default) and at least two
 * node spacings above the sponge's top (a sponge too small for the grid). */
#define FAR_FIELD_RADII 4.8

double sessile_params_far_field_height(const sessile_grow_params *p) {
  if (p->far_field_height >= 0) return p->far_field_height;
  double top = p->box_base_cell * p->box_cells_z, h = p->box_base_cell * ldexp(1.0, 1 - p->box_resolution);
  double H = FAR_FIELD_RADII * p->sponge_radius, low = p->sponge_z + p->sponge_radius + 2 * h;
  if (H < low) H = low;
  return H < top ? H : top;
}

/* Box nodes at the nutrient's resolution (each level halves the cell). */
static double box_nodes(const sessile_grow_params *p, int level) {
  double k = ldexp(1.0, level - 1);
  return (p->box_cells_x * k + 1) * (p->box_cells_y * k + 1) * (p->box_cells_z * k + 1);
}

/* Flow nodes: the immersed fluid box, or TetGen's mesh of the water
 * estimated from the far-field size (a regular tetrahedron of edge a has
 * volume a^3 / (6 sqrt 2); about 6 tetrahedra per node).  The sponge's
 * surface refines the conforming mesh further: this is a lower bound. */
static double flow_nodes(const sessile_grow_params *p, double *tets) {
  double h = p->box_base_cell;
  double vol = h * p->box_cells_x * h * p->box_cells_y * h * p->box_cells_z;
  double a = p->conforming_size_far;
  *tets = vol / (a * a * a / (6 * sqrt(2.0)));
  if (p->domain == SESSILE_DOMAIN_CONFORMING) return *tets / 6;
  return box_nodes(p, p->fluid_resolution);
}

double sessile_params_device_bytes(const sessile_grow_params *p) {
  double tets;
  /* nutrient: ~12 reals per node (solution, CG vectors, operator diagonal)
   * plus the solid mask; flow: block-CSR (4x4 reals, ~15 neighbours) for the
   * Jacobian and its ILU(0) (or the multigrid's levels), and GMRES(50)'s basis
   * of 4 reals per node, with its first 16 preconditioned vectors kept for
   * a pc that is not diagonal (host/la/gmres.c). */
  double nutrient = box_nodes(p, p->box_resolution) * (12 * 8 + 4);
  /* advected on the cut cells: 6 weights and 3 velocities per node, and
   * BiCGSTAB's vectors */
  if (!p->diffusion_limited && p->advection_scheme == SESSILE_ADVECTION_CUT)
    nutrient += box_nodes(p, p->box_resolution) * (17 * 8);
  double fn = flow_nodes(p, &tets);
  if (p->fluid_nested) fn *= 8.0 / 7.0; /* the nested start's coarser boxes: 1/8 + 1/64 + ... more */
  int flow = !p->diffusion_limited || p->fluid_every_iteration || p->fluid_at_snapshots;
  double per = 2 * 15 * 16 * 8 + 52 * 4 * 8;
  if (p->fluid_pc_type != SESSILE_PC_JACOBI && p->fluid_pc_type != SESSILE_PC_NONE) per += 16 * 4 * 8;
  /* fluid_mg_precision 32: the cycle's fp32 copy of the fine block values and
   * its three fp32 vectors on the finest level (its coarse levels, an eighth
   * and less, shrink against the fp64 ones counted in the ILU(0) share) */
  if (p->fluid_pc_type == SESSILE_PC_MG && p->fluid_mg_precision == 32) per += 15 * 16 * 4 + 3 * 4 * 4;
  return nutrient + (flow ? fn * per : 0);
}

static sessile_status validate(const void *values) {
  const sessile_grow_params *p = values;
  double h = p->box_base_cell * ldexp(1.0, 1 - p->box_resolution); /* node spacing */
  double top = p->box_base_cell * p->box_cells_z;
  double sx = p->box_base_cell * p->box_cells_x, sy = p->box_base_cell * p->box_cells_y;
  double R = p->sponge_radius;
  SESSILE_CHECK(p->sponge_z < R, SESSILE_ERR_USAGE,
                "sponge_z (%g cm) must be below sponge_radius (%g cm): the sponge grows on the "
                "substratum", p->sponge_z, R);
  /* The sponge keeps one node spacing from every wall (the growth loop
   * clamps its jittered position there too). */
  SESSILE_CHECK(p->sponge_z + R + h < top && 2 * (R + h) < sx && 2 * (R + h) < sy, SESSILE_ERR_USAGE,
                "the sponge (radius %g cm, centre height %g cm, plus a wall margin of one node "
                "spacing, %g cm) does not fit the box (%g x %g x %g cm); enlarge the box "
                "(box_cells_*, box_base_cell) or shrink sponge_radius",
                R, p->sponge_z, h, sx, sy, top);
  double cx = p->sponge_x < 0 ? sx / 2 : p->sponge_x, cy = p->sponge_y < 0 ? sy / 2 : p->sponge_y;
  SESSILE_CHECK(cx - R - h >= 0 && cx + R + h <= sx && cy - R - h >= 0 && cy + R + h <= sy,
                SESSILE_ERR_USAGE,
                "the sponge centre (%g, %g) cm puts the sponge (radius %g cm) within one node "
                "spacing (%g cm) of a side wall or outside the box (%g x %g cm)", cx, cy, R, h, sx, sy);
  if (p->far_field != SESSILE_FAR_WALLS) { /* height, inlet */
    double H = sessile_params_far_field_height(p);
    SESSILE_CHECK(p->far_field_height == -1 || p->far_field_height > 0, SESSILE_ERR_USAGE,
                  "far_field_height must be positive, or -1 for 4.8 sponge radii (got %g)", p->far_field_height);
    SESSILE_CHECK(H <= top * (1 + 1e-12), SESSILE_ERR_USAGE,
                  "far_field_height (%g cm) must not exceed the box top (%g cm = box_base_cell x "
                  "box_cells_z); raise box_cells_z or lower far_field_height", H, top);
    SESSILE_CHECK(p->sponge_z + R + h < H, SESSILE_ERR_USAGE,
                  "the sponge (top at %g cm) plus one node spacing (%g cm) must stay below "
                  "far_field_height (%g cm)", p->sponge_z + R, h, H);
  }
  SESSILE_CHECK(p->vertex_insertion_threshold > p->vertex_fusion_threshold, SESSILE_ERR_USAGE,
                "vertex_insertion_threshold (%g) must exceed vertex_fusion_threshold (%g)",
                p->vertex_insertion_threshold, p->vertex_fusion_threshold);
  SESSILE_CHECK(p->fluid_mg_precision == 64 || p->fluid_mg_precision == 32, SESSILE_ERR_USAGE,
                "fluid_mg_precision must be 64 or 32 (the bits of the multigrid cycle), got %d",
                p->fluid_mg_precision);
  SESSILE_CHECK(p->fluid_resolution <= p->box_resolution, SESSILE_ERR_USAGE,
                "fluid_resolution (%d) must not exceed box_resolution (%d)", p->fluid_resolution,
                p->box_resolution);
  /* Sizes: 32-bit node and element indices, and the host's memory. */
  double nodes = box_nodes(p, p->box_resolution), tets;
  double fnodes = flow_nodes(p, &tets);
  SESSILE_CHECK(nodes * 6 < 2147483647.0, SESSILE_ERR_USAGE,
                "the box would have %.3g nodes and %.3g tetrahedra, past 32-bit indices; lower "
                "box_resolution or box_cells_*", nodes, nodes * 6);
  if (p->domain == SESSILE_DOMAIN_CONFORMING)
    SESSILE_CHECK(tets < 2e7, SESSILE_ERR_USAGE,
                  "the conforming mesh would have at least %.3g tetrahedra (%.3g nodes) at "
                  "conforming_size_far = %g cm; TetGen and the flow cannot hold more than 2e7: "
                  "raise conforming_size_far", tets, fnodes, p->conforming_size_far);
  double need = sessile_params_device_bytes(p);
  long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
  double host = pages > 0 && psize > 0 ? (double)pages * (double)psize : 0;
  SESSILE_CHECK(host == 0 || need < host, SESSILE_ERR_USAGE,
                "the run needs about %.1f GiB (box %.3g nodes, flow %.3g nodes) but this machine "
                "has %.1f GiB; lower box_resolution, fluid_resolution or the box size",
                need / 1073741824.0, nodes, fnodes, host / 1073741824.0);
  return SESSILE_OK;
}
