/* `sessile coral venation` on the run framework (sessile/venation.h): the
 * configuration a resume restarts from, per-iteration records, snapshots,
 * the checkpoint (vein graph, auxins, rng state) and the final meshes. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io.h"
#include "venation_internal.h"

cJSON *sessile_venation_config(const sessile_venation_params *p, const sessile_venation_options *o) {
  cJSON *c = sessile_run_config_make(&sessile_venation_param_table, p, o->seed, o->iterations, o->every);
  return c;
}

sessile_status sessile_venation_config_read(const cJSON *cfg, sessile_venation_params *p,
                                            sessile_venation_options *o) {
  uint64_t seed = 0;
  SESSILE_CALL(sessile_run_config_take(cfg, &sessile_venation_param_table, p, &seed, &o->iterations, &o->every));
  o->seed = seed;
  return SESSILE_OK;
}

/* The mesh (tubes or weld) with the thickness index per vertex: PLY, and OBJ
 * at the end. */
static sessile_status write_mesh(const sessile_venation *v, const sessile_venation_params *p,
                                 const sessile_venation_options *o, const char *rel, int obj) {
  sessile_skeleton sk = {0};
  sessile_surface m = {0};
  double *val = NULL;
  char path[4096];
  sessile_status s = sessile_venation_skeleton(v, p, &sk);
  if (s == SESSILE_OK && sk.n == 0) s = sessile_error_set(SESSILE_ERR_INTERNAL, "no vein has grown");
  if (s == SESSILE_OK) {
    if (p->geometry == SESSILE_VENATION_WELD) {
      sessile_weld_params wp = {.cell = p->weld_cell, .blend = p->weld_blend};
      s = o->gpu ? sessile_skeleton_weld(o->gpu, &sk, &wp, &m, &val)
                 : sessile_error_set(SESSILE_ERR_NO_DEVICE, "geometry = weld needs a device");
      if (s == SESSILE_ERR_NO_MEMORY) /* the mesh layer's message names no parameter of ours */
        s = sessile_error_set(s, "%s (raise weld_cell)", sessile_error_message());
    } else {
      s = sessile_skeleton_tubes(&sk, p->mesh_detail, &m, &val);
    }
  }
  if (s == SESSILE_OK) s = sessile_run_file(o->run, rel, path, sizeof path);
  if (s == SESSILE_OK) {
    const char *names[1] = {"thickness_index"};
    const double *extra[1] = {val};
    s = sessile_write_ply(path, &m, NULL, 1, names, extra);
  }
  if (s == SESSILE_OK && obj) {
    char orel[256];
    snprintf(orel, sizeof orel, "%.*s.obj", (int)(strlen(rel) - 4), rel);
    s = sessile_run_file(o->run, orel, path, sizeof path);
    if (s == SESSILE_OK) s = sessile_write_obj(path, &m, NULL);
  }
  free(val);
  sessile_surface_free(&m);
  sessile_skeleton_free(&sk);
  return s;
}

static sessile_status checkpoint(sessile_run *run, const sessile_venation *v) {
  uint32_t counts[3] = {v->n, v->ne, v->na};
  sessile_ckpt_section sec[7] = {
      {"counts", counts, sizeof counts},
      {"rng", &v->rng, sizeof v->rng},
      {"positions", v->pos, (size_t)3 * v->n * sizeof *v->pos},
      {"parents", v->parent, (size_t)v->n * sizeof *v->parent},
      {"thickness_index", v->ti, (size_t)v->n * sizeof *v->ti},
      {"edges", v->edge, (size_t)2 * v->ne * sizeof *v->edge},
      {"auxins", v->aux, (size_t)3 * v->na * sizeof *v->aux},
  };
  return sessile_run_checkpoint(run, v->iteration, 7, sec);
}

static sessile_status section(const sessile_ckpt *ck, const char *name, void *dst, size_t bytes) {
  size_t n = 0;
  const void *src = sessile_ckpt_get(ck, name, &n);
  SESSILE_CHECK(src && n == bytes, SESSILE_ERR_IO, "the checkpoint's %s section is damaged", name);
  if (bytes) memcpy(dst, src, bytes);
  return SESSILE_OK;
}

static sessile_status restore(const sessile_ckpt *ck, sessile_venation *v) {
  uint32_t c[3];
  SESSILE_CALL(section(ck, "counts", c, sizeof c));
  SESSILE_CHECK(c[0] >= 1 && c[0] < 0x40000000u && c[1] < 0x40000000u && c[2] < 0x40000000u, SESSILE_ERR_IO,
                "the checkpoint's counts are damaged");
  uint32_t ncap = c[0] > v->cap ? c[0] : v->cap, ecap = c[1] > v->ecap ? c[1] : v->ecap;
  uint32_t acap = c[2] > v->acap ? c[2] : v->acap;
  double *pos = realloc(v->pos, (size_t)3 * ncap * sizeof *pos);
  if (pos) v->pos = pos;
  uint32_t *par = pos ? realloc(v->parent, (size_t)ncap * sizeof *par) : NULL;
  if (par) v->parent = par;
  uint32_t *ti = par ? realloc(v->ti, (size_t)ncap * sizeof *ti) : NULL;
  if (ti) v->ti = ti, v->cap = ncap;
  uint32_t *e = ti ? realloc(v->edge, (size_t)2 * ecap * sizeof *e) : NULL;
  if (e) v->edge = e, v->ecap = ecap;
  double *aux = e ? realloc(v->aux, (size_t)3 * acap * sizeof *aux) : NULL;
  SESSILE_CHECK(aux, SESSILE_ERR_NO_MEMORY, "out of host memory for the checkpoint's vein graph");
  v->aux = aux, v->acap = acap;
  v->n = c[0], v->ne = c[1], v->na = c[2];
  SESSILE_CALL(section(ck, "rng", &v->rng, sizeof v->rng));
  SESSILE_CALL(section(ck, "positions", v->pos, (size_t)3 * v->n * sizeof *v->pos));
  SESSILE_CALL(section(ck, "parents", v->parent, (size_t)v->n * sizeof *v->parent));
  SESSILE_CALL(section(ck, "thickness_index", v->ti, (size_t)v->n * sizeof *v->ti));
  SESSILE_CALL(section(ck, "edges", v->edge, (size_t)2 * v->ne * sizeof *v->edge));
  SESSILE_CALL(section(ck, "auxins", v->aux, (size_t)3 * v->na * sizeof *v->aux));
  /* parents precede their children (what the skeleton's frames rely on) */
  for (uint32_t i = 1; i < v->n; i++)
    SESSILE_CHECK(v->parent[i] < i, SESSILE_ERR_IO, "the checkpoint's vein graph is damaged");
  for (uint32_t k = 0; k < 2 * v->ne; k++)
    SESSILE_CHECK(v->edge[k] < v->n, SESSILE_ERR_IO, "the checkpoint's vein edges are damaged");
  v->iteration = sessile_ckpt_iteration(ck);
  return SESSILE_OK;
}

static sessile_status record(sessile_run *run, const sessile_venation *v, double seconds) {
  cJSON *rec = cJSON_CreateObject();
  SESSILE_CHECK(rec, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddNumberToObject(rec, "iteration", v->iteration);
  cJSON_AddNumberToObject(rec, "nodes", v->n);
  cJSON_AddNumberToObject(rec, "edges", v->n - 1 + v->ne);
  cJSON_AddNumberToObject(rec, "auxins", v->na);
  cJSON_AddNumberToObject(rec, "auxins_placed", v->placed);
  cJSON_AddNumberToObject(rec, "auxins_removed", v->removed);
  cJSON_AddNumberToObject(rec, "nodes_grown", v->grown);
  cJSON_AddNumberToObject(rec, "joins", v->merged);
  cJSON_AddNumberToObject(rec, "seconds", seconds);
  sessile_status st = sessile_run_record(run, rec);
  cJSON_Delete(rec);
  return st;
}

static sessile_status loop(const sessile_venation_params *p, const sessile_venation_options *o,
                           sessile_venation *v, sessile_venation_gpu *vg, int *done) {
  const sessile_ckpt *ck = sessile_run_checkpoint_loaded(o->run);
  if (ck) {
    int k = sessile_ckpt_iteration(ck);
    SESSILE_CHECK(k <= o->iterations, SESSILE_ERR_USAGE,
                  "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
    SESSILE_CALL(restore(ck, v));
    *done = k;
    /* the old last iteration was a snapshot only because it was the last */
    if (k < o->iterations && (o->every == 0 || k % o->every)) {
      char rel[64];
      snprintf(rel, sizeof rel, "coral/iter_%04d.ply", k);
      SESSILE_CALL(sessile_run_remove_file(o->run, rel));
    }
  }
  for (int it = v->iteration + 1; it <= o->iterations; it++) {
    double t0 = sessile_wall_seconds();
    SESSILE_CALL(sessile_venation_step(v, p, vg));
    /* times vary between runs: records, never meshes, hold them */
    SESSILE_CALL(record(o->run, v, sessile_wall_seconds() - t0));
    int snap = (o->every > 0 && it % o->every == 0) || it == o->iterations;
    if (snap) {
      char rel[64];
      snprintf(rel, sizeof rel, "coral/iter_%04d.ply", it);
      SESSILE_CALL(write_mesh(v, p, o, rel, 0));
    }
    *done = it;
    int stop = sessile_run_stop_requested(o->run);
    if (snap || stop) SESSILE_CALL(checkpoint(o->run, v));
    if (stop && it < o->iterations)
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d after iteration %d", stop, it);
  }
  return write_mesh(v, p, o, "coral/final.ply", 1);
}

sessile_status sessile_venation_run(const sessile_venation_params *p, const sessile_venation_options *o,
                                    int *done) {
  *done = 0;
  SESSILE_CHECK(o->run, SESSILE_ERR_USAGE, "sessile coral venation needs a run directory");
  SESSILE_CALL(sessile_params_check(&sessile_venation_param_table, p));
  cJSON *m = sessile_run_manifest(o->run);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "parameters");
  cJSON_AddItemToObject(m, "parameters", sessile_params_to_json(&sessile_venation_param_table, p));
  sessile_venation v;
  sessile_venation_gpu *vg = NULL;
  SESSILE_CALL(sessile_venation_init(&v, o->seed));
  sessile_status s = SESSILE_OK;
  if (p->search == SESSILE_VENATION_GPU) {
    s = o->gpu ? sessile_venation_gpu_create(o->gpu, &vg)
               : sessile_error_set(SESSILE_ERR_NO_DEVICE, "search = gpu needs a device (or set search=host)");
  }
  if (s == SESSILE_OK) s = loop(p, o, &v, vg, done);
  sessile_venation_gpu_destroy(vg);
  sessile_venation_free(&v);
  return s;
}
