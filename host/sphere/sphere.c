/* `sessile sphere` (sessile/sphere.h): per iteration every vertex's distance
 * from the centre is multiplied by 1 + noise * u, u uniform in [-1, 1] from
 * one splitmix64 stream seeded by --seed.  The stream's state is part of the
 * checkpoint, so a resumed run draws the same numbers. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io.h"
#include "sessile/sphere.h"
#include "sessile/surface.h"

static const sessile_param_desc descs[] = {
    {"level", SESSILE_PT_INT, offsetof(sessile_sphere_params, level), 3, 1, 7, 0, "", "ours",
     "icosphere level: 1 = icosahedron (12 vertices), each level quadruples the triangles", NULL},
    {"radius", SESSILE_PT_REAL, offsetof(sessile_sphere_params, radius), 1, 0, 1e6,
     SESSILE_PARAM_LO_OPEN, "cm", "ours", "radius of the starting icosphere", NULL},
    {"noise", SESSILE_PT_REAL, offsetof(sessile_sphere_params, noise), 0.02, 0, 0.5, 0, "", "ours",
     "relative radial step per iteration (uniform in [-noise, noise])", NULL},
};

const sessile_param_table sessile_sphere_param_table = {
    "sphere", sizeof(sessile_sphere_params), (int)(sizeof descs / sizeof descs[0]), descs, NULL};

static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

cJSON *sessile_sphere_config(const sessile_sphere_params *p, const sessile_sphere_options *o) {
  cJSON *c = sessile_run_config_make(&sessile_sphere_param_table, p, o->seed, o->iterations, o->every);
  return c;
}

sessile_status sessile_sphere_config_read(const cJSON *cfg, sessile_sphere_params *p, sessile_sphere_options *o) {
  uint64_t seed = 0;
  SESSILE_CALL(sessile_run_config_take(cfg, &sessile_sphere_param_table, p, &seed, &o->iterations, &o->every));
  o->seed = seed;
  return SESSILE_OK;
}

static sessile_status write_mesh(sessile_run *run, const char *rel, const sessile_surface *s) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  double *n = malloc((size_t)(s->nv ? s->nv : 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_surface_normals(s, n);
  sessile_status st = sessile_write_ply(path, s, n, 0, NULL, NULL);
  free(n);
  return st;
}

static sessile_status checkpoint(sessile_run *run, int it, const sessile_surface *s, uint64_t rng) {
  sessile_ckpt_section sec[2] = {{"rng", &rng, sizeof rng},
                                 {"positions", s->pos, (size_t)3 * s->nv * sizeof *s->pos}};
  return sessile_run_checkpoint(run, it, 2, sec);
}

static sessile_status restore(const sessile_ckpt *ck, sessile_surface *s, uint64_t *rng) {
  size_t n = 0;
  const void *r = sessile_ckpt_get(ck, "rng", &n);
  SESSILE_CHECK(r && n == sizeof *rng, SESSILE_ERR_IO, "the checkpoint's rng section is damaged");
  memcpy(rng, r, n);
  const void *p = sessile_ckpt_get(ck, "positions", &n);
  SESSILE_CHECK(p && n == (size_t)3 * s->nv * sizeof *s->pos, SESSILE_ERR_IO,
                "the checkpoint's positions do not fit this sphere");
  memcpy(s->pos, p, n);
  return SESSILE_OK;
}

static sessile_status record(sessile_run *run, int it, const sessile_surface *s) {
  double lo = INFINITY, hi = 0, sum = 0;
  for (uint32_t v = 0; v < s->nv; v++) {
    double r = sqrt(s->pos[3 * v] * s->pos[3 * v] + s->pos[3 * v + 1] * s->pos[3 * v + 1] +
                    s->pos[3 * v + 2] * s->pos[3 * v + 2]);
    lo = r < lo ? r : lo, hi = r > hi ? r : hi, sum += r;
  }
  cJSON *rec = cJSON_CreateObject();
  SESSILE_CHECK(rec, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddNumberToObject(rec, "iteration", it);
  cJSON_AddNumberToObject(rec, "radius_min_cm", lo);
  cJSON_AddNumberToObject(rec, "radius_mean_cm", sum / s->nv);
  cJSON_AddNumberToObject(rec, "radius_max_cm", hi);
  sessile_status st = sessile_run_record(run, rec);
  cJSON_Delete(rec);
  return st;
}

static sessile_status loop(const sessile_sphere_params *p, const sessile_sphere_options *o,
                           sessile_surface *s, int *done) {
  const double c[3] = {0, 0, 0};
  SESSILE_CALL(sessile_surface_icosphere(p->level, p->radius, c, s));
  uint64_t rng = o->seed;
  int first = 1;
  const sessile_ckpt *ck = sessile_run_checkpoint_loaded(o->run);
  if (ck) {
    int k = sessile_ckpt_iteration(ck);
    SESSILE_CHECK(k <= o->iterations, SESSILE_ERR_USAGE,
                  "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
    SESSILE_CALL(restore(ck, s, &rng));
    first = k + 1;
    *done = k;
    /* the old last iteration was a snapshot only because it was the last */
    if (k < o->iterations && (o->every == 0 || k % o->every)) {
      char rel[64];
      snprintf(rel, sizeof rel, "sphere/iter_%04d.ply", k);
      SESSILE_CALL(sessile_run_remove_file(o->run, rel));
    }
  }
  for (int it = first; it <= o->iterations; it++) {
    for (uint32_t v = 0; v < s->nv; v++) {
      double u = (double)(splitmix64(&rng) >> 11) * (2.0 / 9007199254740992.0) - 1.0;
      for (int a = 0; a < 3; a++) s->pos[3 * v + a] *= 1 + p->noise * u;
    }
    SESSILE_CALL(record(o->run, it, s));
    int snap = (o->every > 0 && it % o->every == 0) || it == o->iterations;
    if (snap) {
      char rel[64];
      snprintf(rel, sizeof rel, "sphere/iter_%04d.ply", it);
      SESSILE_CALL(write_mesh(o->run, rel, s));
    }
    *done = it;
    int stop = sessile_run_stop_requested(o->run);
    if (snap || stop) SESSILE_CALL(checkpoint(o->run, it, s, rng));
    if (stop && it < o->iterations)
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d after iteration %d", stop, it);
  }
  return write_mesh(o->run, "sphere/final.ply", s);
}

sessile_status sessile_sphere_run(const sessile_sphere_params *p, const sessile_sphere_options *o, int *done) {
  *done = 0;
  SESSILE_CHECK(o->run, SESSILE_ERR_USAGE, "sessile sphere needs a run directory");
  SESSILE_CALL(sessile_params_check(&sessile_sphere_param_table, p));
  cJSON *m = sessile_run_manifest(o->run);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "parameters");
  cJSON_AddItemToObject(m, "parameters", sessile_params_to_json(&sessile_sphere_param_table, p));
  sessile_surface s = {0};
  sessile_status st = loop(p, o, &s, done);
  sessile_surface_free(&s);
  return st;
}
