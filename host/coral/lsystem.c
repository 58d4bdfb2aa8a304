/* `sessile coral lsystem` (sessile/coral/lsystem.h, docs/lsystem.md): derive the
 * grammar, interpret it with the turtle into a skeleton, mesh it as tubes
 * (Coralize's way) or as one welded surface, and write the run's files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sessile/io/io.h"
#include "sessile/run/generator.h"
#include "sessile/coral/lsystem.h"
#include "sessile/rng.h"
#include "sessile/mesh/skeleton.h"

static const char *const grammar_names[] = {"lophelia1", "lophelia2", "flat", NULL};
static const char *const geometry_names[] = {"tubes", "weld", NULL};

#define OFF(f) offsetof(sessile_coral_lsystem_params, f)
static const sessile_param_desc descs[] = {
    {"grammar", SESSILE_PT_ENUM, OFF(grammar), 0, 0, 2, 0, "", "Grammar",
     "shipped grammar: lophelia1, lophelia2 (Lophelia pertusa) or flat (a plate); --grammar FILE.lsys for your own",
     grammar_names},
    {"step", SESSILE_PT_REAL, OFF(step), 0.5, 0, 100, SESSILE_PARAM_LO_OPEN, "cm", "F steps",
     "length of one unit of F (and f)", NULL},
    {"thickness", SESSILE_PT_REAL, OFF(thickness), 0.2, 0, 10, SESSILE_PARAM_LO_OPEN, "cm", "Thickness",
     "starting radius; # and ! with a parameter p set the radius to p * thickness", NULL},
    {"thickness_variance", SESSILE_PT_REAL, OFF(thickness_variance), 0.1, 0, 0.9, 0, "", "Thickness Variance",
     "each # and ! scales the new radius by 1 + v u, u uniform in [-1, 1]", NULL},
    {"mesh_detail", SESSILE_PT_INT, OFF(mesh_detail), 8, 3, 64, 0, "", "Mesh Detail",
     "sides of each tube (geometry=tubes)", NULL},
    {"geometry", SESSILE_PT_ENUM, OFF(geometry), 0, 0, 1, 0, "", "ours",
     "tubes: one closed tube per segment (Coralize); weld: one welded watertight surface (GPU)", geometry_names},
    {"weld_blend", SESSILE_PT_REAL, OFF(weld_blend), 0.05, 0, 10, 0, "cm", "ours",
     "smooth-union radius at junctions (geometry=weld; 0: the plain union)", NULL},
    {"weld_cell", SESSILE_PT_REAL, OFF(weld_cell), 0, 0, 10, 0, "cm", "ours",
     "weld grid spacing (0: from weld_cells)", NULL},
    {"weld_cells", SESSILE_PT_INT, OFF(weld_cells), 256, 16, 1024, 0, "", "ours",
     "weld grid cells along the longest side of the bounds (with weld_cell = 0)", NULL},
    {"tropism_x", SESSILE_PT_REAL, OFF(tropism_x), 0, -1, 1, 0, "", "ours (ABOP T)",
     "x of the tropism direction T (light, current; normalised)", NULL},
    {"tropism_y", SESSILE_PT_REAL, OFF(tropism_y), 0, -1, 1, 0, "", "ours (ABOP T)", "y of T", NULL},
    {"tropism_z", SESSILE_PT_REAL, OFF(tropism_z), 1, -1, 1, 0, "", "ours (ABOP T)", "z of T (+z: up)", NULL},
    {"tropism_strength", SESSILE_PT_REAL, OFF(tropism_strength), 0.1, -1, 1, 0, "rad", "ours (ABOP e)",
     "after each F the heading turns toward T by e |H x T| (0: none)", NULL},
    {"min_radius", SESSILE_PT_REAL, OFF(min_radius), 0.01, 0, 1, SESSILE_PARAM_LO_OPEN, "cm", "ours",
     "radii never fall below this", NULL},
    {"max_modules", SESSILE_PT_INT, OFF(max_modules), 4000000, 1, 50000000, 0, "", "ours",
     "refuse a derivation whose string would exceed this many modules (6 bytes + 8 per parameter each)", NULL},
    {"taper", SESSILE_PT_BOOL, OFF(taper), 1, 0, 1, 0, "", "ours",
     "segments run from the radius the previous one ended with to the current one (false: cylinders, Coralize)",
     NULL},
};
#undef OFF

static sessile_status validate(const void *values) {
  const sessile_coral_lsystem_params *p = values;
  double t2 = p->tropism_x * p->tropism_x + p->tropism_y * p->tropism_y + p->tropism_z * p->tropism_z;
  SESSILE_CHECK(p->tropism_strength == 0 || t2 > 1e-12, SESSILE_ERR_USAGE,
                "coral lsystem: tropism_strength %g needs a nonzero direction (tropism_x, tropism_y, tropism_z)",
                p->tropism_strength);
  return SESSILE_OK;
}

const sessile_param_table sessile_coral_lsystem_param_table = {"coral lsystem", sizeof(sessile_coral_lsystem_params),
                                                               (int)(sizeof descs / sizeof descs[0]), descs, validate, NULL, NULL};

void sessile_coral_lsystem_result_free(sessile_coral_lsystem_result *r) {
  if (!r) return;
  sessile_lsys_string_free(&r->str);
  sessile_skeleton_free(r->skel);
  free(r->skel);
  sessile_surface_free(&r->mesh);
  free(r->vertex_value);
  free(r->modules_per_step);
  memset(r, 0, sizeof *r);
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

enum { STREAM_DERIVE = 1, STREAM_TURTLE = 2 };

/* A raised stop flag ends the build where it is (nothing is written yet). */
static sessile_status stopped(const volatile sig_atomic_t *stop) {
  if (!stop || !*stop) return SESSILE_OK;
  return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d", (int)*stop);
}

static sessile_status build(const sessile_coral_lsystem_params *p, const sessile_lsys *g, int iterations,
                            uint64_t seed, sessile_gpu *gpu, const volatile sig_atomic_t *stop,
                            sessile_coral_lsystem_result *r) {
  r->iterations = iterations < 0 ? sessile_lsys_iterations(g) : iterations;
  r->modules_per_step = calloc((size_t)r->iterations + 1, sizeof *r->modules_per_step);
  SESSILE_CHECK(r->modules_per_step, SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint64_t rng = sessile_rng_stream(seed, STREAM_DERIVE);
  double t0 = now_s();
  SESSILE_CALL(sessile_lsys_derive(g, 0, &rng, (uint64_t)p->max_modules, &r->str));
  r->modules_per_step[0] = r->str.n;
  sessile_lsys_string next = {0};
  for (int it = 1; it <= r->iterations; it++) {
    sessile_status s = stopped(stop);
    if (s == SESSILE_OK) s = sessile_lsys_step(g, &r->str, &rng, (uint64_t)p->max_modules, &next);
    if (s != SESSILE_OK) {
      sessile_lsys_string_free(&next);
      return sessile_error_set(s, "iteration %d: %s", it, sessile_error_message());
    }
    sessile_lsys_string t = r->str;
    r->str = next, next = t;
    r->modules_per_step[it] = r->str.n;
  }
  if (sessile_lsys_has_homomorphism(g)) {
    sessile_status s = sessile_lsys_homomorphism(g, &r->str, &rng, (uint64_t)p->max_modules, &next);
    if (s != SESSILE_OK) {
      sessile_lsys_string_free(&next);
      return sessile_error_set(s, "homomorphism: %s", sessile_error_message());
    }
    sessile_lsys_string t = r->str;
    r->str = next, next = t;
  }
  sessile_lsys_string_free(&next);
  double t1 = now_s();
  r->derive_s = t1 - t0;
  sessile_turtle_params tp = {.step = p->step,
                              .angle = sessile_lsys_angle(g),
                              .thickness = p->thickness,
                              .thickness_variance = p->thickness_variance,
                              .width_factor = sessile_lsys_width_factor(g),
                              .tropism = {p->tropism_x, p->tropism_y, p->tropism_z},
                              .tropism_strength = p->tropism_strength,
                              .min_radius = p->min_radius,
                              .taper = p->taper};
  uint64_t trng = sessile_rng_stream(seed, STREAM_TURTLE);
  r->skel = calloc(1, sizeof *r->skel);
  SESSILE_CHECK(r->skel, SESSILE_ERR_NO_MEMORY, "out of host memory");
  SESSILE_CALL(stopped(stop));
  SESSILE_CALL(sessile_turtle_interpret(&r->str, &tp, &trng, r->skel, &r->turtle));
  SESSILE_CALL(stopped(stop));
  double t2 = now_s();
  r->turtle_s = t2 - t1;
  SESSILE_CHECK(r->skel->n > 0, SESSILE_ERR_USAGE,
                "the derived string (%u modules) draws nothing: it has no F with a positive length", r->str.n);
  if (p->geometry == 0) {
    SESSILE_CALL(sessile_skeleton_tubes_stop(r->skel, p->mesh_detail, stop, &r->mesh, &r->vertex_value));
  } else {
    SESSILE_CHECK(gpu, SESSILE_ERR_USAGE, "geometry=weld needs a device");
    sessile_weld_params wp = {.cell = p->weld_cell, .max_cells = (uint32_t)p->weld_cells, .blend = p->weld_blend};
    sessile_status s = sessile_skeleton_weld(gpu, r->skel, &wp, &r->mesh, &r->vertex_value);
    if (s == SESSILE_ERR_NO_MEMORY) /* the mesh layer's message names no parameter of ours */
      return sessile_error_set(s, "%s (raise weld_cell, or with weld_cell = 0 lower weld_cells)", sessile_error_message());
    SESSILE_CALL(s);
  }
  r->mesh_s = now_s() - t2;
  return stopped(stop);
}

sessile_status sessile_coral_lsystem_build(const sessile_coral_lsystem_params *p, const sessile_lsys *g,
                                           int iterations, uint64_t seed, sessile_gpu *gpu,
                                           const volatile sig_atomic_t *stop, sessile_coral_lsystem_result *out) {
  memset(out, 0, sizeof *out);
  SESSILE_CALL(sessile_params_check(&sessile_coral_lsystem_param_table, p));
  SESSILE_CHECK(iterations <= 1000, SESSILE_ERR_USAGE, "iterations %d: at most 1000", iterations);
  sessile_status s = build(p, g, iterations, seed, gpu, stop, out);
  if (s != SESSILE_OK) sessile_coral_lsystem_result_free(out);
  return s;
}

static sessile_status write_meshes(sessile_run *run, const sessile_coral_lsystem_result *r,
                                   const volatile sig_atomic_t *stop) {
  const sessile_surface *m = &r->mesh;
  double *n = malloc((size_t)(m->nv ? m->nv : 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", m->nv);
  sessile_surface_normals(m, n);
  sessile_status s0 = stopped(stop);
  if (s0 != SESSILE_OK) {
    free(n);
    return s0;
  }
  const char *names[1] = {"value"};
  const double *extra[1] = {r->vertex_value};
  /* PLY and .vtp coloured by the value (the height without one; docs/io.md) */
  sessile_mesh_part part = {"surface", m->pos, m->nv, m->tri, m->nf, n, extra};
  sessile_mesh_info mi;
  sessile_run_mesh_info(run, &mi);
  mi.iteration = r->iterations;
  sessile_status s = sessile_run_write_mesh(run, "coral/final.ply", 1, &part, r->vertex_value ? 1 : 0, names, &mi, stop);
  if (s == SESSILE_OK) s = stopped(stop);
  if (s == SESSILE_OK) s = sessile_run_write_obj(run, "coral/final.obj", m, n, &mi, stop);
  free(n);
  return s;
}

sessile_status sessile_coral_lsystem_write(sessile_run *run, const sessile_coral_lsystem_params *p,
                                           const sessile_lsys *g, const char *grammar_name, const char *text,
                                           size_t len, const sessile_coral_lsystem_result *r,
                                           const sessile_gpu *gpu, const volatile sig_atomic_t *stop) {
  char path[4096];
  SESSILE_CALL(stopped(stop));
  SESSILE_CALL(sessile_run_file(run, "coral/grammar.lsys", path, sizeof path));
  SESSILE_CALL(sessile_write_file_atomic(path, text, len));
  for (int it = 0; it <= r->iterations; it++) {
    cJSON *rec = cJSON_CreateObject();
    SESSILE_CHECK(rec, SESSILE_ERR_NO_MEMORY, "out of host memory");
    cJSON_AddNumberToObject(rec, "iteration", it);
    cJSON_AddNumberToObject(rec, "modules", r->modules_per_step[it]);
    sessile_status s = sessile_run_record(run, rec);
    cJSON_Delete(rec);
    SESSILE_CALL(s);
  }
  SESSILE_CALL(write_meshes(run, r, stop));
  cJSON *m = sessile_run_manifest(run);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "parameters");
  cJSON_AddItemToObject(m, "parameters", sessile_params_to_json(&sessile_coral_lsystem_param_table, p));
  cJSON *gj = cJSON_CreateObject();
  SESSILE_CHECK(gj, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddStringToObject(gj, "name", grammar_name);
  cJSON_AddNumberToObject(gj, "iterations", r->iterations);
  cJSON_AddNumberToObject(gj, "angle_deg", sessile_lsys_angle(g));
  cJSON_AddNumberToObject(gj, "width_factor", sessile_lsys_width_factor(g));
  cJSON *defs = cJSON_AddObjectToObject(gj, "defines");
  for (int i = 0; defs && i < sessile_lsys_define_count(g); i++) {
    double v;
    const char *nm = sessile_lsys_define_name(g, i, &v);
    cJSON_AddNumberToObject(defs, nm, v);
  }
  cJSON_DeleteItemFromObjectCaseSensitive(m, "grammar");
  cJSON_AddItemToObject(m, "grammar", gj);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "device");
  if (gpu) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(gpu);
    cJSON *dev = cJSON_AddObjectToObject(m, "device");
    if (dev) {
      cJSON_AddStringToObject(dev, "name", gi->name);
      cJSON_AddStringToObject(dev, "type", gi->type);
      cJSON_AddStringToObject(dev, "driver", gi->driver);
    }
  } else {
    cJSON_AddStringToObject(m, "device", "none: every stage ran on the host");
  }
  cJSON *st = cJSON_CreateObject();
  SESSILE_CHECK(st, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddNumberToObject(st, "modules", r->modules_per_step[r->iterations]);
  cJSON_AddNumberToObject(st, "modules_drawn", r->str.n); /* after the homomorphism */
  cJSON_AddNumberToObject(st, "segments", r->turtle.segments);
  cJSON_AddNumberToObject(st, "branches", r->turtle.branches);
  cJSON_AddNumberToObject(st, "max_branch_order", r->turtle.max_depth);
  cJSON_AddNumberToObject(st, "drawn_length_cm", r->turtle.length);
  cJSON_AddNumberToObject(st, "vertices", r->mesh.nv);
  cJSON_AddNumberToObject(st, "triangles", r->mesh.nf);
  double lo[3], hi[3];
  sessile_skeleton_bounds(r->skel, lo, hi);
  cJSON_AddItemToObject(st, "bounds_min_cm", cJSON_CreateDoubleArray(lo, 3));
  cJSON_AddItemToObject(st, "bounds_max_cm", cJSON_CreateDoubleArray(hi, 3));
  cJSON_AddNumberToObject(st, "derive_s", r->derive_s);
  cJSON_AddNumberToObject(st, "turtle_s", r->turtle_s);
  cJSON_AddNumberToObject(st, "mesh_s", r->mesh_s);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "result");
  cJSON_AddItemToObject(m, "result", st);
  return sessile_run_write_manifest(run);
}
