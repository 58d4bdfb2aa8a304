/* `sessile reef SCENE.json` (docs/reef.md): the reef generator's table on
 * the run framework.  Iteration 1 runs the brushes, iterations 2.. the
 * growth steps; finish computes the exposure to currents, generates the
 * organisms (cli_reef_organisms.c) and writes reef.glb, placements.json,
 * reef/reef.ply (every organism merged) and the preview's instanced scene
 * (cli_reef_preview.c). */
#include <stdlib.h>
#include <string.h>
#include "cli_reef.h"
#include "sessile/io/io.h"

typedef struct reef_params {
  int device_exposure;
} reef_params;

static const sessile_param_desc descs[] = {
    {"device_exposure", SESSILE_PT_BOOL, offsetof(reef_params, device_exposure), 1, 0, 1, 0, "", "ours",
     "exposure to currents on the device (false: the host reference)", NULL},
};
static const sessile_param_table table = {"reef", sizeof(reef_params), 1, descs, NULL, NULL, NULL};

typedef struct reef_args {
  char *path, *text;
  sessile_reef_scene scene;
  int parsed;
} reef_args;

typedef struct reef {
  const reef_args *a;
  sessile_run *run;
  sessile_gpu *gpu;
  int device;
  sessile_reef_seabed seabed;
  sessile_reef_placements pl;
  uint32_t count; /* pl.n, as a checkpoint section */
  uint64_t seed;
} reef;

static sessile_status load(reef_args *a, const char *text, size_t len) {
  sessile_reef_scene_free(&a->scene), a->parsed = 0;
  SESSILE_CALL(sessile_reef_scene_parse(text, len, a->path ? a->path : "scene", &a->scene));
  a->parsed = 1;
  return SESSILE_OK;
}

static sessile_status arg(void *extra, int argc, char **argv, int *i, int *taken) {
  reef_args *a = extra;
  (void)argc;
  if (argv[*i][0] == '-') return *taken = 0, SESSILE_OK;
  SESSILE_CHECK(!a->path, SESSILE_ERR_USAGE, "one scene only ('%.60s' is a second)", argv[*i]);
  *taken = 1;
  size_t len = 0;
  SESSILE_CHECK(a->path = strdup(argv[*i]), SESSILE_ERR_NO_MEMORY, "out of host memory");
  SESSILE_CALL(sessile_read_small_file(a->path, 16u << 20, "scene", &a->text, &len));
  return load(a, a->text, len);
}

/* The scene without SCENE.json: a small reef of spheres (docs/reef.md). */
static const char builtin[] =
    "{\"seabed\": {\"noise\": {\"seed\": 1, \"resolution\": [17, 17], \"extent\": [4, 4], \"height_scale\": 0.5,"
    " \"base\": -3, \"wavelength\": 3, \"octaves\": 2}},"
    " \"pool\": [{\"name\": \"ball\", \"generator\": \"sphere\", \"parameters\": [\"level=2\", \"iterations=2\"],"
    " \"colour\": [0.9, 0.45, 0.3, 1], \"bias\": 60, \"size\": [0.25, 0.3]},"
    " {\"name\": \"pebble\", \"generator\": \"sphere\", \"parameters\": [\"level=1\", \"iterations=2\"],"
    " \"colour\": [0.3, 0.5, 0.9, 1], \"bias\": 40, \"size\": [0.2, 0.25], \"rotate\": [\"x\", \"y\", \"z\"]}],"
    " \"brushes\": [{\"points\": [[1, 1], [3, 3]], \"size\": 0.8, \"density\": 2}],"
    " \"currents\": [{\"origin\": [0, 2, -2], \"direction\": [1, 0, 0], \"strength\": 4, \"nutrition_range\": 0.5}],"
    " \"growth\": {\"steps\": 2, \"spacing\": 1}}";

static sessile_status defaults(void *params, void *extra) {
  reef_args *a = extra;
  sessile_params_defaults(&table, params);
  if (a->parsed) return SESSILE_OK;
  SESSILE_CHECK((a->path = strdup("(built-in scene)")) && (a->text = strdup(builtin)), SESSILE_ERR_NO_MEMORY,
                "out of host memory");
  return load(a, a->text, strlen(a->text));
}

static sessile_status config_write(const void *extra, cJSON *cfg) {
  const reef_args *a = extra;
  int ok = cJSON_AddStringToObject(cfg, "scene", a->path) && cJSON_AddStringToObject(cfg, "scene_text", a->text);
  SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "out of host memory");
  return SESSILE_OK;
}

static sessile_status config_read(void *extra, const cJSON *cfg) {
  reef_args *a = extra;
  const cJSON *p = cJSON_GetObjectItemCaseSensitive(cfg, "scene"), *t = cJSON_GetObjectItemCaseSensitive(cfg, "scene_text");
  SESSILE_CHECK(cJSON_IsString(p) && cJSON_IsString(t), SESSILE_ERR_USAGE, "the run holds no reef scene (damaged?)");
  SESSILE_CHECK(!a->text || !strcmp(a->text, t->valuestring), SESSILE_ERR_USAGE,
                "%s differs from the scene the run started with", a->path);
  free(a->path), free(a->text);
  SESSILE_CHECK((a->path = strdup(p->valuestring)) && (a->text = strdup(t->valuestring)), SESSILE_ERR_NO_MEMORY,
                "out of host memory");
  return load(a, a->text, strlen(a->text));
}

static void extra_free(void *extra) {
  reef_args *a = extra;
  sessile_reef_scene_free(&a->scene);
  free(a->path), free(a->text);
}

static sessile_status check(const void *params, const sessile_gen_setup *su) {
  const reef_args *a = su->extra;
  SESSILE_CHECK(a && a->parsed, SESSILE_ERR_USAGE, "needs a scene: sessile reef SCENE.json (docs/reef.md)");
  int device = ((const reef_params *)params)->device_exposure;
  for (int k = 0; k < a->scene.nentries; k++)
    SESSILE_CALL(cli_reef_check_entry(a->path, k, &a->scene.entries[k], device));
  double estimate;
  SESSILE_CALL_AT(sessile_reef_check(&a->scene, &estimate), "%s", a->path);
  return SESSILE_OK;
}

static sessile_status schedule(const void *params, sessile_gen_setup *su) {
  const reef_args *a = su->extra;
  /* --iterations N: N - 1 growth steps whatever the scene says */
  if (su->iterations == 0) su->iterations = 1 + a->scene.growth_steps;
  return SESSILE_OK;
}

static int needs_device(const void *params) { return ((const reef_params *)params)->device_exposure; }

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  reef *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  *state = r;
  r->a = su->extra, r->run = su->run, r->seed = su->seed, r->gpu = su->gpu, r->device = needs_device(params);
  return sessile_reef_seabed_make(&r->a->scene, &r->seabed);
}

static sessile_status step(void *state, int it, cJSON *rec) {
  reef *r = state;
  uint32_t added = 0;
  if (it == 1) {
    SESSILE_CALL(sessile_reef_place(&r->a->scene, &r->seabed, r->seed, &r->pl));
    added = r->pl.n;
  } else
    SESSILE_CALL(sessile_reef_grow_step(&r->a->scene, &r->seabed, it - 1, &r->pl, &added));
  r->count = r->pl.n;
  int ok = cJSON_AddNumberToObject(rec, "organisms", r->pl.n) && cJSON_AddNumberToObject(rec, "added", added);
  SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "out of host memory");
  return SESSILE_OK;
}

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  reef *r = state;
  r->count = r->pl.n;
  sec[0] = (sessile_ckpt_section){"count", &r->count, sizeof r->count};
  sec[1] = (sessile_ckpt_section){"placements", r->pl.p, (size_t)r->pl.n * sizeof *r->pl.p};
  *n = 2;
  return SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  reef *r = state;
  SESSILE_CALL(sessile_ckpt_take(ck, "count", &r->count, sizeof r->count));
  SESSILE_CHECK(r->count <= SESSILE_REEF_MAX_ORGANISMS, SESSILE_ERR_IO, "the checkpoint's placement count is damaged");
  sessile_reef_placements_free(&r->pl);
  r->pl.p = malloc(((size_t)r->count + 1) * sizeof *r->pl.p);
  SESSILE_CHECK(r->pl.p, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->pl.n = r->pl.cap = r->count;
  return sessile_ckpt_take(ck, "placements", r->pl.p, (size_t)r->count * sizeof *r->pl.p);
}

sessile_status cli_reef_write_json(sessile_run *run, const char *rel, cJSON *j) {
  char path[4096], *text = j ? cJSON_Print(j) : NULL;
  cJSON_Delete(j);
  SESSILE_CHECK(text, SESSILE_ERR_NO_MEMORY, "out of host memory for %s", rel);
  sessile_status s = sessile_run_file(run, rel, path, sizeof path);
  if (s == SESSILE_OK) s = sessile_write_file_atomic(path, text, strlen(text));
  free(text);
  return s;
}

static sessile_status snapshot(void *state, const char *rel) {
  reef *r = state;
  return cli_reef_write_json(r->run, rel, sessile_reef_placements_json(&r->a->scene, &r->pl, NULL));
}

/* Every placed organism in one mesh (cm, z up): reef/reef.ply. */
static sessile_status merged(const sessile_reef_gltf *g, sessile_surface *out) {
  uint64_t nv = 0, nf = 0;
  for (uint32_t k = 0; k < g->scene.nnodes; k++)
    nv += g->surfaces[g->nodes[k].mesh].nv, nf += g->surfaces[g->nodes[k].mesh].nf;
  SESSILE_CHECK(nv < UINT32_MAX / 4 && nf < UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "the reef is too large to preview");
  SESSILE_CALL(sessile_surface_reserve(out, (uint32_t)nv, (uint32_t)nf));
  for (uint32_t k = 0; k < g->scene.nnodes; k++) {
    const sessile_surface *s = &g->surfaces[g->nodes[k].mesh];
    const double *m = g->nodes[k].matrix;
    for (uint32_t v = 0; v < s->nv; v++) {
      const double *p = s->pos + 3 * v;
      double *q = out->pos + 3 * ((size_t)out->nv + v);
      for (int i = 0; i < 3; i++) q[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i];
    }
    for (uint32_t f = 0; f < 3 * s->nf; f++) out->tri[3 * (size_t)out->nf + f] = s->tri[f] + out->nv;
    out->nv += s->nv, out->nf += s->nf;
  }
  return SESSILE_OK;
}

static sessile_status finish(void *state) {
  reef *r = state;
  const sessile_reef_scene *s = &r->a->scene;
  if (r->device && r->gpu) SESSILE_CALL(sessile_reef_exposure_gpu(r->gpu, s, &r->seabed, &r->pl, 0));
  else sessile_reef_exposure_ref(s, &r->seabed, &r->pl, 0);
  cli_reef_organisms org = {.gpu = r->gpu, .run = r->run, .where = r->a->path};
  sessile_reef_gltf g;
  SESSILE_CALL(sessile_reef_gltf_make(s, &r->seabed, &r->pl, cli_reef_organism, &org, &g));
  char path[4096];
  sessile_surface all = {0};
  sessile_status st = SESSILE_OK;
  g.scene.generator = "sessile (reef)";
  st = sessile_run_file(r->run, "reef.glb", path, sizeof path);
  if (st == SESSILE_OK) st = sessile_gltf_write(path, &g.scene);
  if (st == SESSILE_OK) st = cli_reef_write_json(r->run, "placements.json", sessile_reef_placements_json(s, &r->pl, &g));
  if (st == SESSILE_OK) st = merged(&g, &all);
  if (st == SESSILE_OK) st = sessile_run_write_surface(r->run, "reef/reef.ply", &all, 0, NULL, NULL);
  if (st == SESSILE_OK) st = cli_reef_preview_scene(r->run, &g);
  if (st == SESSILE_OK) {
    cJSON *m = cJSON_CreateObject();
    int ok = m && cJSON_AddItemToObject(sessile_run_manifest(r->run), "reef", m) &&
             cJSON_AddNumberToObject(m, "placements", r->pl.n) && cJSON_AddNumberToObject(m, "meshes", g.scene.nmeshes) &&
             cJSON_AddNumberToObject(m, "materials", g.scene.nmaterials);
    if (!ok) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  sessile_surface_free(&all);
  sessile_reef_gltf_free(&g);
  return st;
}

static void destroy(void *state) {
  reef *r = state;
  if (!r) return;
  sessile_reef_placements_free(&r->pl);
  sessile_reef_seabed_free(&r->seabed);
  free(r);
}

const sessile_generator sessile_gen_reef = {
    .name = "reef",
    .summary = "a reef scene (Coralize §4): seabed, brushes, growth and currents, written as glTF",
    .about = "A reef from a scene file (docs/reef.md): a seeded seabed, brush strokes that\n"
    "place organisms of a pool of generators, reef growth and water currents\n"
    "(Liapis et al., Coralize, §4).  Writes reef.glb (one mesh per distinct\n"
    "organism, a node per placement), placements.json, reef/reef.ply, the\n"
    "preview's scene (reef/scene.json, reef/meshes.ply) and preview.png.\n"
    "Iteration 1 runs the brushes, iterations 2.. the growth steps\n"
    "(--iterations 0, the default: 1 + the scene's growth.steps).  Without\n"
    "SCENE.json: a small built-in scene.  usage: sessile reef [SCENE.json] [options]",
    .help = NULL,
    .seed_help = "the brushes", .out_default = "runs/reef", .table = &table,
    .snapshot_name = "reef/placements_%04d.json", .preview = "reef/scene.json", .iterations = 0, .every = 0,
    .needs_device = needs_device, .check = check,
    .extra_size = sizeof(reef_args), .arg = arg, .defaults = defaults, .schedule = schedule, .config_write = config_write,
    .config_read = config_read, .extra_free = extra_free,
    SESSILE_GEN_CALLBACKS,
};
