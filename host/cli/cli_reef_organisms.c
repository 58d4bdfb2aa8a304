/* The reef's organisms (docs/reef.md, "Organisms"): a pool entry's
 * generator runs in-process through its own table and the run framework,
 * into a private temporary run directory, and its final mesh (the file its
 * preview draws) is read back with the io reader; the directory is removed
 * after.  Exposure to currents scales the generator's thickness parameters
 * (the table below) by 1 + exposure, within their ranges. */
#define _XOPEN_SOURCE 700
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli_generator.h"
#include "cli_reef.h"
#include "sessile/io/io_read.h"

/* Each generator's parameters that exposure thickens (§4.3, Figure 13). */
static const struct {
  const char *generator, *params[4];
} thickness[] = {
    {"sphere", {"radius"}},
    {"coral venation", {"thickness_0", "thickness_1", "thickness_2", "thickness_3"}},
    {"sponge particles", {"growth_fraction"}},
};

static const sessile_generator *find(const char *name) {
  for (int k = 0; cli_generators[k]; k++)
    if (!strcmp(cli_generators[k]->name, name)) return cli_generators[k];
  return NULL;
}

typedef struct organism_params {
  char values[4096] __attribute__((aligned(16)));
  int iterations;
} organism_params;

/* The entry's parameters: the table's defaults (the generator's preset
 * fallback), then each "name=value"; "iterations=N" sets the iterations. */
static sessile_status params_of(const sessile_generator *g, const char *const *settings, int n, organism_params *p,
                                int *bad) {
  SESSILE_CHECK(g->table->struct_size <= sizeof p->values, SESSILE_ERR_INTERNAL, "%s: parameters too large", g->name);
  sessile_params_defaults(g->table, p->values);
  if (g->presets) SESSILE_CALL(g->presets->apply(g->presets->fallback, p->values));
  p->iterations = g->iterations;
  for (*bad = 0; *bad < n; ++*bad) {
    const char *kv = settings[*bad];
    if (!strncmp(kv, "iterations=", 11)) {
      char *end = NULL;
      long it = strtol(kv + 11, &end, 10);
      SESSILE_CHECK(end != kv + 11 && !*end && it >= 1 && it <= 100000, SESSILE_ERR_USAGE,
                    "iterations must be an integer 1..100000 (not '%.40s')", kv + 11);
      p->iterations = (int)it;
    } else
      SESSILE_CALL(sessile_params_set_kv(g->table, p->values, kv));
  }
  *bad = -1;
  return sessile_params_check(g->table, p->values);
}

sessile_status cli_reef_check_entry(const char *where, int k, const sessile_reef_entry *e) {
  const sessile_generator *g = find(e->generator);
  if (!g || g->arg || !strcmp(e->generator, "reef")) {
    char known[512] = "";
    for (int i = 0; cli_generators[i]; i++)
      if (!cli_generators[i]->arg && strcmp(cli_generators[i]->name, "reef"))
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", known[0] ? ", " : "",
                 cli_generators[i]->name);
    return sessile_error_set(SESSILE_ERR_USAGE, "%s: pool[%d].generator: '%.60s' is no generator a pool can hold "
                             "(known: %s)", where, k, e->generator, known);
  }
  static organism_params p;
  int bad;
  sessile_status s = params_of(g, (const char *const *)e->settings, e->nsettings, &p, &bad);
  if (s != SESSILE_OK && bad >= 0)
    return sessile_error_pass(s, "%s: pool[%d].parameters[%d]", where, k, bad);
  if (s != SESSILE_OK) return sessile_error_pass(s, "%s: pool[%d].parameters", where, k);
  return SESSILE_OK;
}

static void thicken(const sessile_generator *g, void *values, double exposure) {
  for (size_t k = 0; k < sizeof thickness / sizeof thickness[0]; k++) {
    if (strcmp(thickness[k].generator, g->name)) continue;
    for (int i = 0; i < 4 && thickness[k].params[i]; i++) {
      const sessile_param_desc *d = sessile_params_find(g->table, thickness[k].params[i]);
      if (!d || d->type != SESSILE_PT_REAL) continue;
      double *v = (double *)((char *)values + d->offset), x = *v * (1 + exposure);
      *v = x < d->lo ? d->lo : x > d->hi ? d->hi : x;
    }
  }
}

static int unlink_one(const char *path, const struct stat *st, int flag, struct FTW *f) {
  (void)st, (void)flag, (void)f;
  return remove(path);
}

void cli_reef_remove_tree(const char *dir) { nftw(dir, unlink_one, 16, FTW_DEPTH | FTW_PHYS); }

static sessile_status run_in(const sessile_generator *g, organism_params *p, uint64_t seed, sessile_gpu *gpu,
                             const char *dir, sessile_surface *out, sessile_reef_scalars *scalars) {
  sessile_run_options o = {.dir = dir, .generator = g->name, .version = "reef organism", .mode = SESSILE_RUN_NEW};
  sessile_run *run = NULL;
  SESSILE_CALL(sessile_run_open(&o, &run));
  sessile_gen_setup su = {.run = run, .gpu = g->needs_device && g->needs_device(p->values) ? gpu : NULL,
                          .seed = seed, .iterations = p->iterations, .every = 0};
  for (int k = 0; k < g->noptions && k < SESSILE_GEN_MAX_OPTIONS; k++) su.values[k] = g->options[k].fallback;
  if (g->presets) su.preset = g->presets->fallback;
  sessile_status s = g->check ? g->check(p->values, &(sessile_gen_setup){.seed = seed, .iterations = p->iterations,
                                                                        .gpu = su.gpu}) : SESSILE_OK;
  if (s == SESSILE_OK && g->needs_device && g->needs_device(p->values) && !gpu)
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s needs a device", g->name);
  int done = 0;
  if (s == SESSILE_OK) s = sessile_run_loop(g, p->values, &su, NULL, NULL, &done);
  s = sessile_run_close(run, s);
  char path[8400];
  snprintf(path, sizeof path, "%s/%s", dir, g->preview ? g->preview : "");
  sessile_mesh_in m = {0};
  if (s == SESSILE_OK && !g->preview) s = sessile_error_set(SESSILE_ERR_USAGE, "%s writes no mesh", g->name);
  if (s == SESSILE_OK) s = sessile_read_ply(path, &(sessile_mesh_read_opts){.triangles_only = 1, .keep_props = 1}, &m);
  if (s == SESSILE_OK) s = sessile_surface_reserve(out, m.nv, m.nf);
  if (s == SESSILE_OK) {
    memcpy(out->pos, m.pos, 3 * (size_t)m.nv * sizeof *m.pos);
    memcpy(out->tri, m.tri, 3 * (size_t)m.nf * sizeof *m.tri);
    out->nv = m.nv, out->nf = m.nf;
    /* the PLY's vertex properties (thickness_index, growth_count...) go on as they are */
    scalars->n = (uint32_t)m.nprops, scalars->names = m.prop_names, scalars->values = m.props;
    m.nprops = 0, m.prop_names = NULL, m.props = NULL;
  }
  sessile_mesh_in_free(&m);
  return s;
}

sessile_status cli_reef_organism(void *ctx, const char *generator, const char *const *settings, int nsettings,
                                 uint64_t seed, double exposure, sessile_surface *out,
                                 sessile_reef_scalars *scalars) {
  cli_reef_organisms *c = ctx;
  /* the reef's last iteration is checkpointed: a resume runs finish again */
  int stop = c->run ? sessile_run_stop_requested(c->run) : 0;
  SESSILE_CHECK(!stop, SESSILE_ERR_INTERRUPTED, "stopped by signal %d while generating organisms", stop);
  const sessile_generator *g = find(generator);
  SESSILE_CHECK(g, SESSILE_ERR_USAGE, "unknown generator '%.60s'", generator);
  static organism_params p;
  int bad;
  SESSILE_CALL(params_of(g, settings, nsettings, &p, &bad));
  thicken(g, p.values, exposure);
  const char *tmp = getenv("TMPDIR");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/sessile-reef-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  SESSILE_CHECK(mkdtemp(dir), SESSILE_ERR_IO, "cannot make a temporary folder in %s", tmp && tmp[0] ? tmp : "/tmp");
  char sub[4200];
  snprintf(sub, sizeof sub, "%s/run", dir);
  sessile_status s = run_in(g, &p, seed, c->gpu, sub, out, scalars);
  cli_reef_remove_tree(dir);
  if (s == SESSILE_OK) c->made++;
  return s;
}
