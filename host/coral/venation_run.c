/* `sessile coral venation` on the run framework (sessile/coral/venation.h): the
 * configuration a resume restarts from, per-iteration records, snapshots,
 * the checkpoint (vein graph, auxins, rng state) and the final meshes. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sessile/run/generator.h"
#include "venation_internal.h"

/* The generator's state: the vein graph and what writes it. */
typedef struct venation_gen {
  sessile_venation_params p;
  sessile_venation v;
  sessile_venation_gpu *vg;
  sessile_run *run;
  sessile_gpu *gpu;
  uint32_t counts[3]; /* what a checkpoint's "counts" section holds */
} venation_gen;

/* The mesh (tubes or weld) with the thickness index per vertex: PLY, and OBJ
 * at the end. */
static sessile_status write_mesh(const venation_gen *g, const char *rel, int obj) {
  const sessile_venation *v = &g->v;
  const sessile_venation_params *p = &g->p;
  sessile_skeleton sk = {0};
  sessile_surface m = {0};
  double *val = NULL;
  sessile_status s = sessile_venation_skeleton(v, p, &sk);
  if (s == SESSILE_OK && sk.n == 0) s = sessile_error_set(SESSILE_ERR_INTERNAL, "no vein has grown");
  if (s == SESSILE_OK) {
    if (p->geometry == SESSILE_VENATION_WELD) {
      sessile_weld_params wp = {.cell = p->weld_cell, .blend = p->weld_blend};
      s = g->gpu ? sessile_skeleton_weld(g->gpu, &sk, &wp, &m, &val)
                 : sessile_error_set(SESSILE_ERR_NO_DEVICE, "geometry = weld needs a device");
      if (s == SESSILE_ERR_NO_MEMORY) /* the mesh layer's message names no parameter of ours */
        s = sessile_error_set(s, "%s (raise weld_cell)", sessile_error_message());
    } else {
      s = sessile_skeleton_tubes(&sk, p->mesh_detail, &m, &val);
    }
  }
  sessile_mesh_info mi;
  sessile_run_mesh_info(g->run, &mi);
  if (s == SESSILE_OK) {
    const char *names[1] = {"thickness_index"};
    const double *extra[1] = {val};
    sessile_mesh_part part = {"surface", m.pos, m.nv, m.tri, m.nf, NULL, extra};
    s = sessile_run_write_mesh(g->run, rel, 1, &part, 1, names, &mi, NULL); /* PLY and .vtp */
  }
  if (s == SESSILE_OK && obj) {
    char orel[256];
    snprintf(orel, sizeof orel, "%.*s.obj", (int)(strlen(rel) - 4), rel);
    s = sessile_run_write_obj(g->run, orel, &m, NULL, &mi, NULL);
  }
  free(val);
  sessile_surface_free(&m);
  sessile_skeleton_free(&sk);
  return s;
}

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  venation_gen *g = state;
  const sessile_venation *v = &g->v;
  g->counts[0] = v->n, g->counts[1] = v->ne, g->counts[2] = v->na;
  sec[0] = (sessile_ckpt_section){"counts", g->counts, sizeof g->counts};
  sec[1] = (sessile_ckpt_section){"rng", &v->rng, sizeof v->rng};
  sec[2] = (sessile_ckpt_section){"positions", v->pos, (size_t)3 * v->n * sizeof *v->pos};
  sec[3] = (sessile_ckpt_section){"parents", v->parent, (size_t)v->n * sizeof *v->parent};
  sec[4] = (sessile_ckpt_section){"thickness_index", v->ti, (size_t)v->n * sizeof *v->ti};
  sec[5] = (sessile_ckpt_section){"edges", v->edge, (size_t)2 * v->ne * sizeof *v->edge};
  sec[6] = (sessile_ckpt_section){"auxins", v->aux, (size_t)3 * v->na * sizeof *v->aux};
  *n = 7;
  return SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  sessile_venation *v = &((venation_gen *)state)->v;
  uint32_t c[3];
  SESSILE_CALL(sessile_ckpt_take(ck, "counts", c, sizeof c));
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
  SESSILE_CALL(sessile_ckpt_take(ck, "rng", &v->rng, sizeof v->rng));
  SESSILE_CALL(sessile_ckpt_take(ck, "positions", v->pos, (size_t)3 * v->n * sizeof *v->pos));
  SESSILE_CALL(sessile_ckpt_take(ck, "parents", v->parent, (size_t)v->n * sizeof *v->parent));
  SESSILE_CALL(sessile_ckpt_take(ck, "thickness_index", v->ti, (size_t)v->n * sizeof *v->ti));
  SESSILE_CALL(sessile_ckpt_take(ck, "edges", v->edge, (size_t)2 * v->ne * sizeof *v->edge));
  SESSILE_CALL(sessile_ckpt_take(ck, "auxins", v->aux, (size_t)3 * v->na * sizeof *v->aux));
  /* parents precede their children (what the skeleton's frames rely on) */
  for (uint32_t i = 1; i < v->n; i++)
    SESSILE_CHECK(v->parent[i] < i, SESSILE_ERR_IO, "the checkpoint's vein graph is damaged");
  for (uint32_t k = 0; k < 2 * v->ne; k++)
    SESSILE_CHECK(v->edge[k] < v->n, SESSILE_ERR_IO, "the checkpoint's vein edges are damaged");
  v->iteration = sessile_ckpt_iteration(ck);
  return SESSILE_OK;
}

static sessile_status step(void *state, int it, cJSON *rec) {
  venation_gen *g = state;
  const sessile_venation *v = &g->v;
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_venation_step(&g->v, &g->p, g->vg));
  /* times vary between runs: records, never meshes, hold them */
  double seconds = sessile_wall_seconds() - t0;
  cJSON_AddNumberToObject(rec, "nodes", v->n);
  cJSON_AddNumberToObject(rec, "edges", v->n - 1 + v->ne);
  cJSON_AddNumberToObject(rec, "auxins", v->na);
  cJSON_AddNumberToObject(rec, "auxins_placed", v->placed);
  cJSON_AddNumberToObject(rec, "auxins_removed", v->removed);
  cJSON_AddNumberToObject(rec, "nodes_grown", v->grown);
  cJSON_AddNumberToObject(rec, "joins", v->merged);
  cJSON_AddNumberToObject(rec, "seconds", seconds);
  return SESSILE_OK;
}

static sessile_status snapshot(void *state, const char *rel) { return write_mesh(state, rel, 0); }
static sessile_status finish(void *state) { return write_mesh(state, "coral/final.ply", 1); }

static void destroy(void *state) {
  venation_gen *g = state;
  if (!g) return;
  sessile_venation_gpu_destroy(g->vg);
  sessile_venation_free(&g->v);
  free(g);
}

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  venation_gen *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  g->p = *(const sessile_venation_params *)params, g->run = su->run, g->gpu = su->gpu;
  sessile_status s = sessile_venation_init(&g->v, su->seed);
  if (s != SESSILE_OK) {
    free(g);
    return s;
  }
  *state = g;
  if (g->p.search != SESSILE_VENATION_GPU) return SESSILE_OK;
  SESSILE_CHECK(g->gpu, SESSILE_ERR_NO_DEVICE, "search = gpu needs a device (or set search=host)");
  return sessile_venation_gpu_create(g->gpu, &g->vg);
}

/* The device only when a kernel needs it. */
static int needs_device(const void *params) {
  const sessile_venation_params *p = params;
  return p->search == SESSILE_VENATION_GPU || p->geometry == SESSILE_VENATION_WELD;
}

/* Refuse what cannot fit before anything is written: at most
 * iterations x auxins_per_iteration auxins live at once (24 bytes each, and
 * the search's 40 bytes of work per auxin). */
static sessile_status check_size(const void *params, const sessile_gen_setup *su) {
  const sessile_venation_params *p = params;
  SESSILE_CHECK(su->iterations >= 1, SESSILE_ERR_USAGE,
                "--iterations 0: a venation run grows its veins in iterations (1 or more)");
  double aux = (double)su->iterations * p->auxins_per_iteration;
  SESSILE_CHECK(aux <= 5e7, SESSILE_ERR_USAGE,
                "%d iterations x %d auxins per iteration could hold %.3g auxins (about %.1f GB): at most 5e7",
                su->iterations, p->auxins_per_iteration, aux, aux * 64e-9);
  return SESSILE_OK;
}

const sessile_generator sessile_gen_coral_venation = {
    .name = "coral venation",
    .summary = "soft corals by open or closed leaf venation (Coralize 3.2)",
    .about = "Soft corals by leaf venation in 3-D (Coralize Section 3.2, after Runions et al. 2005):\n"
    "auxins thrown per iteration into a leaf blade bounded by two Bezier curves that widens\n"
    "every iteration (or into a 3-D box: planar=false) attract vein nodes, which grow toward\n"
    "them; open venation (open=true) grows a tree, closed venation rejoins veins.  Veins\n"
    "thicken with their thickness index (a thickness curve) and are meshed as tubes.\n"
    "Writes coral/iter_NNNN.ply every K iterations and at the last, coral/final.ply and\n"
    "coral/final.obj (PLY: per-vertex thickness_index), manifest.json, records.jsonl and a\n"
    "checkpoint at each snapshot (docs/run.md).",
    .seed_help = "the auxins' placement",
    .out_default = "runs/coral-venation",
    .snapshot_name = "coral/iter_%04d.ply",
    .preview = "coral/final.ply",
    .table = &sessile_venation_param_table,
    .iterations = 60,
    .every = 20,
    .needs_device = needs_device,
    .check = check_size,
    SESSILE_GEN_CALLBACKS,
};
