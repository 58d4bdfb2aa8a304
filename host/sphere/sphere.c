/* `sessile sphere` (sessile/sphere/sphere.h): per iteration every vertex's distance
 * from the centre is multiplied by 1 + noise * u, u uniform in [-1, 1) from
 * one splitmix64 stream seeded by --seed; the stream's state is
 * checkpointed.  The whole generator: a table and six callbacks. */
#include <math.h>
#include <stdlib.h>
#include "sessile/run/generator.h"
#include "sessile/io/io.h"
#include "sessile/rng.h"
#include "sessile/sphere/sphere.h"
#include "sessile/mesh/surface.h"

static const sessile_param_desc descs[] = {
    {"level", SESSILE_PT_INT, offsetof(sessile_sphere_params, level), 3, 1, 7, 0, "", "ours",
     "icosphere level: 1 = icosahedron (12 vertices), each level quadruples the triangles", NULL},
    {"radius", SESSILE_PT_REAL, offsetof(sessile_sphere_params, radius), 1, 0, 1e6,
     SESSILE_PARAM_LO_OPEN, "cm", "ours", "radius of the starting icosphere", NULL},
    {"noise", SESSILE_PT_REAL, offsetof(sessile_sphere_params, noise), 0.02, 0, 0.5, 0, "", "ours",
     "relative radial step per iteration (uniform in [-noise, noise])", NULL},
};
const sessile_param_table sessile_sphere_param_table = {
    "sphere", sizeof(sessile_sphere_params), (int)(sizeof descs / sizeof descs[0]), descs, NULL, NULL, NULL};

typedef struct sphere {
  sessile_sphere_params p;
  sessile_run *run;
  sessile_surface s;
  uint64_t rng;
} sphere;

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  sphere *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  *state = g;
  g->p = *(const sessile_sphere_params *)params, g->run = su->run, g->rng = su->seed;
  return sessile_surface_icosphere(g->p.level, g->p.radius, (const double[3]){0, 0, 0}, &g->s);
}

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  sphere *g = state;
  sec[0] = (sessile_ckpt_section){"rng", &g->rng, sizeof g->rng};
  sec[1] = (sessile_ckpt_section){"positions", g->s.pos, (size_t)3 * g->s.nv * sizeof *g->s.pos};
  *n = 2;
  return SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  sphere *g = state;
  SESSILE_CALL(sessile_ckpt_take(ck, "rng", &g->rng, sizeof g->rng));
  return sessile_ckpt_take(ck, "positions", g->s.pos, (size_t)3 * g->s.nv * sizeof *g->s.pos);
}

static sessile_status step(void *state, int it, cJSON *rec) {
  sphere *g = state;
  double lo = INFINITY, hi = 0, sum = 0;
  for (uint32_t v = 0; v < g->s.nv; v++) {
    double u = sessile_rng_range(&g->rng, -1, 1), *x = g->s.pos + 3 * v;
    for (int a = 0; a < 3; a++) x[a] *= 1 + g->p.noise * u;
    double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    lo = r < lo ? r : lo, hi = r > hi ? r : hi, sum += r;
  }
  cJSON_AddNumberToObject(rec, "radius_min_cm", lo);
  cJSON_AddNumberToObject(rec, "radius_mean_cm", sum / g->s.nv);
  cJSON_AddNumberToObject(rec, "radius_max_cm", hi);
  return SESSILE_OK;
}

/* The surface with each vertex's distance from the centre, its main scalar. */
static sessile_status snapshot(void *state, const char *rel) {
  sphere *g = state;
  double *r = malloc(((size_t)g->s.nv + 1) * sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t v = 0; v < g->s.nv; v++) {
    const double *x = g->s.pos + 3 * (size_t)v;
    r[v] = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  const char *names[1] = {"radius"};
  const double *extra[1] = {r};
  sessile_status st = sessile_run_write_surface(g->run, rel, &g->s, 1, names, extra);
  free(r);
  return st;
}

static sessile_status finish(void *state) { return snapshot(state, "sphere/final.ply"); }

static void destroy(void *state) {
  sphere *g = state;
  if (g) sessile_surface_free(&g->s);
  free(g);
}

const sessile_generator sessile_gen_sphere = {
    .name = "sphere",
    .summary = "the smallest generator: a seeded noisy icosphere through the run framework",
    .about = "The smallest generator, and the run framework's own test: an icosphere (level,\n"
    "radius) whose vertices take a seeded radial random walk (noise) for N\n"
    "iterations.  Writes sphere/iter_NNNN.ply every K iterations and at the last,\n"
    "sphere/final.ply, manifest.json, records.jsonl and a checkpoint at each snapshot,\n"
    "exactly as every generator does (docs/run.md).",
    .seed_help = "the random walk", .out_default = "runs/sphere", .table = &sessile_sphere_param_table,
    .snapshot_name = "sphere/iter_%04d.ply", .preview = "sphere/final.ply", .iterations = 10, .every = 5,
    SESSILE_GEN_CALLBACKS,
};
