/* The growth members of a run's manifest.json (every parameter with its
 * unit and source, seed, device, box, initial sponge, slices; totals at each
 * checkpoint and at the end) and the per-iteration record appended to
 * records.jsonl (stage timings, solver iterations and true residuals, remesh
 * counts, mesh statistics).  The run framework writes both. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"
#include "sessile/io/io.h"

static void add_vec3(cJSON *o, const char *name, const double v[3]) {
  cJSON *a = cJSON_AddArrayToObject(o, name);
  for (int i = 0; i < 3; i++) cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
}

void grow_manifest_surface_stats(cJSON *obj, const sessile_surface *s) {
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  cJSON_AddNumberToObject(obj, "vertices", st.nv);
  cJSON_AddNumberToObject(obj, "triangles", st.nf);
  cJSON_AddNumberToObject(obj, "edges", st.ne);
  cJSON_AddNumberToObject(obj, "area_cm2", st.area);
  cJSON_AddNumberToObject(obj, "volume_cm3", st.volume);
  cJSON_AddNumberToObject(obj, "edge_min_cm", st.edge_min);
  cJSON_AddNumberToObject(obj, "edge_mean_cm", st.edge_mean);
  cJSON_AddNumberToObject(obj, "edge_max_cm", st.edge_max);
  cJSON_AddNumberToObject(obj, "triangle_area_min_cm2", st.tri_area_min);
  add_vec3(obj, "bbox_min_cm", st.bbox_min);
  add_vec3(obj, "bbox_max_cm", st.bbox_max);
}

sessile_status grow_manifest_begin(grow_run *r) {
  cJSON *m = sessile_run_manifest(r->o->run);
  const char *mine[] = {"model", "preset", "seed", "iterations_requested", "snapshot_every", "device",
                        "parameters", "box", "initial_sponge", "slices", "fluid", "totals"};
  for (size_t i = 0; i < sizeof mine / sizeof mine[0]; i++) cJSON_DeleteItemFromObjectCaseSensitive(m, mine[i]);
  cJSON_AddStringToObject(m, "model", "O'Hagan, Chalmers, Rhee: accretive sponge growth (Crella incrustans)");
  cJSON_AddStringToObject(m, "preset", r->o->preset ? r->o->preset : "");
  /* The seed as a string: JSON numbers lose 64-bit integers past 2^53. */
  char seed[32];
  snprintf(seed, sizeof seed, "%llu", (unsigned long long)r->o->seed);
  cJSON_AddStringToObject(m, "seed", seed);
  cJSON_AddNumberToObject(m, "iterations_requested", r->o->iterations);
  cJSON_AddNumberToObject(m, "snapshot_every", r->o->every);

  const sessile_gpu_info *gi = sessile_gpu_info_of(r->gpu);
  cJSON *dev = cJSON_AddObjectToObject(m, "device");
  cJSON_AddStringToObject(dev, "name", gi->name);
  cJSON_AddStringToObject(dev, "type", gi->type);
  cJSON_AddStringToObject(dev, "driver", gi->driver);
  cJSON_AddNumberToObject(dev, "precision_bits", gi->precision);

  cJSON *params = sessile_params_to_json(&sessile_grow_param_table, r->p);
  SESSILE_CHECK(params, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest");
  cJSON_AddItemToObject(m, "parameters", params);

  cJSON *box = cJSON_AddObjectToObject(m, "box");
  double mx[3], n[3] = {r->box.n[0], r->box.n[1], r->box.n[2]};
  sessile_box_max(&r->box, mx);
  add_vec3(box, "origin_cm", r->box.origin);
  add_vec3(box, "max_cm", mx);
  add_vec3(box, "nodes_per_axis", n);
  cJSON_AddNumberToObject(box, "nodes", sessile_box_nodes(&r->box));
  cJSON_AddNumberToObject(box, "tetrahedra", 6.0 * sessile_box_cells(&r->box));
  cJSON_AddNumberToObject(box, "spacing_cm", r->box.h);
  cJSON *sp = cJSON_AddObjectToObject(m, "initial_sponge");
  add_vec3(sp, "center_cm", r->center);
  grow_manifest_surface_stats(sp, &r->surf);
  cJSON *planes = cJSON_AddArrayToObject(m, "slices");
  for (int i = 0; i < r->nplanes; i++) {
    cJSON *pl = cJSON_CreateObject();
    cJSON_AddStringToObject(pl, "name", r->planes[i].name);
    char ax[2] = {(char)('x' + r->planes[i].axis), 0};
    cJSON_AddStringToObject(pl, "axis", ax);
    cJSON_AddNumberToObject(pl, "value_cm", r->planes[i].value);
    cJSON_AddItemToArray(planes, pl);
  }
  cJSON_AddStringToObject(m, "fluid",
                          !r->p->diffusion_limited ? "solved every iteration: it advects the nutrient"
                          : r->p->fluid_every_iteration
                              ? "solved every iteration on request; it does not feed the growth "
                                "(diffusion_limited = true: the nutrient is a Laplace problem)"
                              : "solved only at snapshot iterations, for the slices and fields; it does "
                                "not feed the growth (diffusion_limited = true: the nutrient is a "
                                "Laplace problem)");
  return SESSILE_OK;
}

sessile_status grow_manifest_totals(grow_run *r) {
  cJSON *m = sessile_run_manifest(r->o->run);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "totals");
  cJSON *tot = cJSON_AddObjectToObject(m, "totals");
  SESSILE_CHECK(tot, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest");
  cJSON_AddNumberToObject(tot, "iterations_done", r->sum.iterations);
  cJSON_AddNumberToObject(tot, "wall_seconds_this_start", sessile_wall_seconds() - r->t_start);
  cJSON_AddNumberToObject(tot, "solver_iterations", (double)r->sum.solver_iterations);
  cJSON_AddNumberToObject(tot, "worst_true_relres", r->sum.worst_relres);
  cJSON *st = cJSON_AddObjectToObject(tot, "stage_seconds");
  for (int s = 0; s < SESSILE_STAGE_COUNT; s++)
    cJSON_AddNumberToObject(st, sessile_grow_stage_name(s), r->sum.stage_seconds[s]);
  cJSON *fin = cJSON_AddObjectToObject(tot, "surface");
  grow_manifest_surface_stats(fin, &r->surf);
  return SESSILE_OK;
}
