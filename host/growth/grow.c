/* The growth run's state (O'Hagan et al., Figure 2): the box, the starting
 * sponge on the substratum, the nutrient's solver and the growth kernels,
 * made once and freed once; one iteration is grow_iterate.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"
#include "sessile/growth/growth_ref.h"
#include "sessile/rng.h"

const char *sessile_grow_stage_name(int stage) {
  static const char *names[] = {
#define X(n) #n,
      SESSILE_GROW_STAGES(X)
#undef X
  };
  return stage >= 0 && stage < SESSILE_STAGE_COUNT ? names[stage] : "?";
}

void sessile_grow_options_default(sessile_grow_options *o) {
  memset(o, 0, sizeof *o);
  o->preset = "radiate";
  o->iterations = 50;
  o->seed = 1;
  o->every = 10;
  o->slices = "x,y,z";
  o->fields = 1;
  o->check_every_iteration = 1;
  o->monitor = NULL;
}

/* Uniform in [-1, 1] from the top 53 bits. */
static double uniform_pm1(uint64_t *state) {
  return (double)(sessile_rng_next(state) >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

sessile_status grow_setup(grow_run *r) {
  const sessile_grow_params *p = r->p;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p->box_cells_x, (uint32_t)p->box_cells_y,
                             (uint32_t)p->box_cells_z};
  SESSILE_CALL(sessile_box_make(origin, p->box_base_cell, cells, p->box_resolution, &r->box));
  double mx[3];
  sessile_box_max(&r->box, mx);
  /* The sponge sits on the substratum (its lowest point touches z = 0) at the
   * chosen x/y, shifted by the seeded jitter (§4.7); the shift is clamped so
   * the sponge stays one cell inside the side walls. */
  uint64_t st = r->o->seed ^ 0x5EED5EED5EED5EEDull;
  double jx = p->position_jitter * uniform_pm1(&st), jy = p->position_jitter * uniform_pm1(&st);
  r->center[0] = (p->sponge_x < 0 ? mx[0] / 2 : p->sponge_x) + jx;
  r->center[1] = (p->sponge_y < 0 ? mx[1] / 2 : p->sponge_y) + jy;
  r->center[2] = p->sponge_z;
  for (int a = 0; a < 2; a++) {
    double lo = p->sponge_radius + r->box.h, hi = mx[a] - p->sponge_radius - r->box.h;
    if (r->center[a] < lo) r->center[a] = lo;
    if (r->center[a] > hi) r->center[a] = hi;
  }
  if (r->o->initial) SESSILE_CALL(sessile_surface_copy(r->o->initial, &r->surf));
  else SESSILE_CALL(sessile_surface_icosphere(p->sponge_resolution, p->sponge_radius, r->center, &r->surf));
  /* A sponge grows attached to the rock: the part of the sphere below the
   * substratum is projected onto it (a flat base; its triangles keep their
   * downward orientation, so the surface stays closed and consistent). */
  for (uint32_t v = 0; v < r->surf.nv; v++)
    if (r->surf.pos[3 * v + 2] < r->box.origin[2]) r->surf.pos[3 * v + 2] = r->box.origin[2];
  SESSILE_CALL(sessile_la_create(r->gpu, &r->la));
  sessile_cut_bc bc;
  sessile_cut_bc_default(&bc);
  /* With the current, far_field = height's inflow wall carries the bare
   * profile (nutrient_inflow = profile; docs/nutrient.md "The inflow"). */
  int profile = !p->diffusion_limited && p->nutrient_inflow == SESSILE_INFLOW_PROFILE;
  bc.far_field = p->far_field == SESSILE_FAR_WALLS   ? SESSILE_FAR_FIELD_WALLS
                 : p->far_field == SESSILE_FAR_INLET ? SESSILE_FAR_FIELD_INLET
                 : profile                           ? SESSILE_FAR_FIELD_PROFILE
                                                     : SESSILE_FAR_FIELD_HEIGHT;
  bc.height = sessile_params_far_field_height(p);
  SESSILE_CALL(sessile_cut_nutrient_create(r->la, &r->box, &bc,
                                           p->nutrient_pc_type == SESSILE_SOLVER_MG ? 12 : 1,
                                           &r->nutrient));
  SESSILE_CALL(sessile_growth_gpu_create(r->la, &r->growth));
  uint32_t nodes = sessile_box_nodes(&r->box);
  sessile_cut_nutrient_level(r->nutrient, 0, NULL, &r->solid, NULL);
  SESSILE_CALL(sessile_vec_create(r->la, nodes, &r->c));
  /* Start from c = 1 (the far field); the first solve fixes the rest. */
  SESSILE_CALL(sessile_vec_fill(r->la, 1.0, r->c));
  r->sum.box_nodes = nodes;
  return SESSILE_OK;
}

void grow_teardown(grow_run *r) {
  grow_flow_teardown(r);
  sessile_vec_destroy(r->c);
  sessile_growth_gpu_destroy(r->growth);
  sessile_cut_nutrient_destroy(r->nutrient);
  sessile_la_destroy(r->la);
  sessile_surface_free(&r->surf);
  for (int i = 0; i < r->nvtu; i++) free(r->vtu_files[i]);
  free(r->vtu_files);
  free(r->vtu_steps);
  free(r->normals);
  free(r->newpos);
  grow_flow_saved_free(&r->saved);
  for (int i = 0; i < 3; i++) free(r->ck_bytes[i]);
}

/* Refuses a box the device cannot hold, with the estimate. */
sessile_status sessile_grow_check_device(const sessile_gpu *g, const sessile_grow_params *p) {
  const sessile_gpu_info *gi = sessile_gpu_info_of(g);
  double need = sessile_params_device_bytes(p);
  if (gi->precision == 32) need *= 0.5;
  SESSILE_CHECK(gi->device_local_bytes == 0 || need < (double)gi->device_local_bytes, SESSILE_ERR_USAGE,
                "the run needs about %.2f GiB of device memory but %s has %.2f GiB; lower "
                "box_resolution, fluid_resolution or the box size",
                need / 1073741824.0, gi->name, (double)gi->device_local_bytes / 1073741824.0);
  return SESSILE_OK;
}
