/* `sessile sponge particles` on the run framework: configuration for
 * resume, checkpoint sections, records, snapshots and the final meshes
 * (sessile/particle_sponge.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "psponge_internal.h"
#include "sessile/intersect.h"
#include "sessile/io.h"

cJSON *sessile_psponge_config(const sessile_psponge_params *p, const sessile_psponge_options *o) {
  cJSON *c = sessile_run_config_make(&sessile_psponge_param_table, p, o->seed, o->iterations, o->every);
  if (c && !cJSON_AddBoolToObject(c, "check", o->check)) {
    cJSON_Delete(c);
    return NULL;
  }
  return c;
}

sessile_status sessile_psponge_config_read(const cJSON *cfg, sessile_psponge_params *p,
                                           sessile_psponge_options *o) {
  uint64_t seed = 0;
  SESSILE_CALL(sessile_run_config_take(cfg, &sessile_psponge_param_table, p, &seed, &o->iterations, &o->every));
  o->seed = seed;
  const cJSON *check = cJSON_GetObjectItemCaseSensitive(cfg, "check");
  SESSILE_CHECK(cJSON_IsBool(check), SESSILE_ERR_USAGE, "the run's stored configuration is damaged");
  o->check = cJSON_IsTrue(check);
  return SESSILE_OK;
}

sessile_status sessile_psponge_checkpoint(sessile_psponge *ps, sessile_run *run) {
  const sessile_surface *s = &ps->surf;
  sessile_ckpt_section sec[6] = {
      {"rng", &ps->rng, sizeof ps->rng},
      {"positions", s->pos, (size_t)3 * s->nv * sizeof *s->pos},
      {"triangles", s->tri, (size_t)3 * s->nf * sizeof *s->tri},
      {"growth_counts", ps->counts, (size_t)s->nv * sizeof *ps->counts},
      {"particles", ps->ppos, (size_t)3 * ps->np * sizeof *ps->ppos},
      {"ages", ps->age, (size_t)ps->np * sizeof *ps->age}};
  return sessile_run_checkpoint(run, ps->iteration, 6, sec);
}

sessile_status sessile_psponge_restore(sessile_psponge *ps, const sessile_ckpt *ck) {
  size_t nr = 0, npos = 0, ntri = 0, ncnt = 0, npart = 0, nage = 0;
  const void *r = sessile_ckpt_get(ck, "rng", &nr), *pos = sessile_ckpt_get(ck, "positions", &npos);
  const void *tri = sessile_ckpt_get(ck, "triangles", &ntri), *cnt = sessile_ckpt_get(ck, "growth_counts", &ncnt);
  const void *part = sessile_ckpt_get(ck, "particles", &npart), *age = sessile_ckpt_get(ck, "ages", &nage);
  size_t nv = npos / (3 * sizeof(double)), nf = ntri / (3 * sizeof(uint32_t)), np = npart / (3 * sizeof(double));
  SESSILE_CHECK(r && pos && tri && cnt && part && age && nr == sizeof ps->rng && npos % 24 == 0 &&
                    ntri % 12 == 0 && npart % 24 == 0 && ncnt == nv * 4 && nage == np * 4 &&
                    nv <= UINT32_MAX && nf <= UINT32_MAX && np <= UINT32_MAX,
                SESSILE_ERR_IO, "the checkpoint's particle-sponge sections are damaged");
  sessile_surface s = {0};
  SESSILE_CALL(sessile_surface_reserve(&s, (uint32_t)nv, (uint32_t)nf));
  s.nv = (uint32_t)nv, s.nf = (uint32_t)nf;
  memcpy(s.pos, pos, npos);
  memcpy(s.tri, tri, ntri);
  sessile_status st = sessile_surface_check(&s, 2, 0.0);
  uint32_t *counts = st == SESSILE_OK ? malloc(ncnt + 4) : NULL;
  if (st == SESSILE_OK && !counts) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (st == SESSILE_OK) st = psponge_reserve_particles(ps, (uint32_t)np);
  if (st != SESSILE_OK) {
    sessile_surface_free(&s);
    free(counts);
    return sessile_error_set(st, "the checkpoint's surface: %s", sessile_error_message());
  }
  memcpy(counts, cnt, ncnt);
  sessile_surface_free(&ps->surf);
  ps->surf = s;
  free(ps->counts);
  ps->counts = counts;
  memcpy(ps->ppos, part, npart);
  memcpy(ps->age, age, nage);
  ps->np = (uint32_t)np;
  memcpy(&ps->rng, r, nr);
  ps->iteration = sessile_ckpt_iteration(ck);
  return SESSILE_OK;
}

sessile_status sessile_psponge_write_ply(const sessile_psponge *ps, const char *path) {
  const sessile_surface *s = &ps->surf;
  double *n = malloc(((size_t)s->nv + 1) * 3 * sizeof *n), *c = malloc(((size_t)s->nv + 1) * sizeof *c);
  if (!n || !c) {
    free(n), free(c);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  sessile_surface_normals(s, n);
  for (uint32_t v = 0; v < s->nv; v++) c[v] = ps->counts[v];
  const char *names[1] = {"growth_count"};
  const double *extra[1] = {c};
  sessile_status st = sessile_write_ply(path, s, n, 1, names, extra);
  free(n), free(c);
  return st;
}

static sessile_status write_ply(sessile_run *run, const char *rel, const sessile_psponge *ps) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  return sessile_psponge_write_ply(ps, path);
}

static sessile_status write_obj(sessile_run *run, const char *rel, const sessile_psponge *ps) {
  char path[4096];
  SESSILE_CALL(sessile_run_file(run, rel, path, sizeof path));
  const sessile_surface *s = &ps->surf;
  double *n = malloc(((size_t)s->nv + 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_surface_normals(s, n);
  sessile_status st = sessile_write_obj(path, s, n);
  free(n);
  return st;
}

/* The invariants, when asked for: closed oriented 2-manifold, no self-intersection. */
static sessile_status check(const sessile_psponge *ps, cJSON *rec) {
  SESSILE_CHECK(sessile_surface_check(&ps->surf, 2, 0.0) == SESSILE_OK, SESSILE_ERR_INTERNAL,
                "iteration %d: the surface is broken (%s): a bug", ps->iteration, sessile_error_message());
  uint64_t n = 0;
  SESSILE_CALL(sessile_surface_self_intersections(&ps->surf, 0, NULL, &n));
  cJSON_AddNumberToObject(rec, "self_intersections", (double)n);
  SESSILE_CHECK(n == 0, SESSILE_ERR_INTERNAL,
                "iteration %d: the surface intersects itself (%llu triangle pairs) although every step "
                "is guarded: a bug", ps->iteration, (unsigned long long)n);
  return SESSILE_OK;
}

static sessile_status record(sessile_run *run, const sessile_psponge *ps, const sessile_psponge_iter_stats *st,
                             int do_check) {
  cJSON *rec = cJSON_CreateObject();
  SESSILE_CHECK(rec, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddNumberToObject(rec, "iteration", ps->iteration);
  cJSON_AddNumberToObject(rec, "vertices", st->nv);
  cJSON_AddNumberToObject(rec, "triangles", st->nf);
  cJSON_AddNumberToObject(rec, "particles_alive", st->alive);
  cJSON_AddNumberToObject(rec, "spawned", st->spawned);
  cJSON_AddNumberToObject(rec, "hits", st->hits);
  cJSON_AddNumberToObject(rec, "fed_vertices", st->fed_vertices);
  cJSON_AddNumberToObject(rec, "died_fed", st->died_fed);
  cJSON_AddNumberToObject(rec, "died_age", st->died_age);
  cJSON_AddNumberToObject(rec, "died_outside", st->died_outside);
  cJSON_AddNumberToObject(rec, "held_back", st->held_back);
  cJSON_AddNumberToObject(rec, "remesh_refused", st->remesh_refused);
  cJSON_AddNumberToObject(rec, "collide_s", st->collide_s);
  cJSON_AddNumberToObject(rec, "grow_s", st->grow_s);
  cJSON_AddNumberToObject(rec, "remesh_s", st->remesh_s);
  sessile_status s = do_check ? check(ps, rec) : SESSILE_OK;
  if (s == SESSILE_OK) s = sessile_run_record(run, rec);
  cJSON_Delete(rec);
  return s;
}

static sessile_status loop(const sessile_psponge_options *o, sessile_psponge *ps, int *done) {
  const sessile_ckpt *ck = sessile_run_checkpoint_loaded(o->run);
  if (ck) {
    int k = sessile_ckpt_iteration(ck);
    SESSILE_CHECK(k <= o->iterations, SESSILE_ERR_USAGE,
                  "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
    SESSILE_CALL(sessile_psponge_restore(ps, ck));
    *done = k;
    /* the old last iteration was a snapshot only because it was the last */
    if (k < o->iterations && (o->every == 0 || k % o->every)) {
      char rel[64];
      snprintf(rel, sizeof rel, "sponge/iter_%04d.ply", k);
      SESSILE_CALL(sessile_run_remove_file(o->run, rel));
    }
  }
  for (int it = ps->iteration + 1; it <= o->iterations; it++) {
    sessile_psponge_iter_stats st;
    SESSILE_CALL(sessile_psponge_step(ps, &st));
    SESSILE_CALL(record(o->run, ps, &st, o->check));
    int snap = (o->every > 0 && it % o->every == 0) || it == o->iterations;
    if (snap) {
      char rel[64];
      snprintf(rel, sizeof rel, "sponge/iter_%04d.ply", it);
      SESSILE_CALL(write_ply(o->run, rel, ps));
    }
    *done = it;
    int stop = sessile_run_stop_requested(o->run);
    if (snap || stop) SESSILE_CALL(sessile_psponge_checkpoint(ps, o->run));
    if (stop && it < o->iterations)
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d after iteration %d", stop, it);
  }
  SESSILE_CALL(write_ply(o->run, "sponge/final.ply", ps));
  return write_obj(o->run, "sponge/final.obj", ps);
}

sessile_status sessile_psponge_run(const sessile_psponge_params *p, const sessile_psponge_options *o,
                                   int *done) {
  *done = 0;
  SESSILE_CHECK(o->run, SESSILE_ERR_USAGE, "sessile sponge particles needs a run directory");
  SESSILE_CALL(sessile_params_check(&sessile_psponge_param_table, p));
  cJSON *m = sessile_run_manifest(o->run);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "parameters");
  cJSON_AddItemToObject(m, "parameters", sessile_params_to_json(&sessile_psponge_param_table, p));
  sessile_psponge *ps = NULL;
  SESSILE_CALL(sessile_psponge_create(p, o->seed, o->gpu, &ps));
  sessile_status s = loop(o, ps, done);
  sessile_psponge_destroy(ps);
  return s;
}
