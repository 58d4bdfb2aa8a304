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
#include "sessile/coral/lsystem.h"
#include "sessile/io/io_read.h"
#include "sessile/sds/sds_run.h"

/* Each generator's parameters that exposure thickens (§4.3, Figure 13;
 * docs/reef.md says why these). */
static const struct {
  const char *generator, *params[4];
} thickness[] = {
    {"sphere", {"radius"}},
    {"coral venation", {"thickness_0", "thickness_1", "thickness_2", "thickness_3"}},
    {"coral lsystem", {"thickness"}},
    {"sponge particles", {"growth_fraction"}},
    {"grow", {"growth_rate", "max_growth"}},
};

/* Generators on the run framework whose commands are their own
 * (cmd_coral_lsystem.c, cmd_sds.c), so not in generators.def: a pool holds
 * them too. */
static const sessile_generator *const own_command[] = {&sessile_gen_coral_lsystem, &sessile_gen_sds, NULL};

static const sessile_generator *find(const char *name) {
  for (int k = 0; cli_generators[k]; k++)
    if (!strcmp(cli_generators[k]->name, name) && strcmp(name, "reef")) return cli_generators[k];
  for (int k = 0; own_command[k]; k++)
    if (!strcmp(own_command[k]->name, name)) return own_command[k];
  return NULL;
}

typedef struct organism_params {
  char values[4096] __attribute__((aligned(16)));
  int iterations;
  void *extra; /* the generator's own options (its extra_size bytes) */
} organism_params;

static void params_free(const sessile_generator *g, organism_params *p) {
  if (p->extra && g->extra_free) g->extra_free(p->extra);
  free(p->extra), p->extra = NULL;
}

/* The entry's own arguments through the generator's parser, as its command
 * line would give them; *bad the one refused. */
static sessile_status arguments_of(const sessile_generator *g, const sessile_reef_entry *e, organism_params *p,
                                   int *bad) {
  char *argv[258] = {(char *)g->name};
  int argc = 1 + e->narguments;
  SESSILE_CHECK(e->narguments <= 256, SESSILE_ERR_USAGE, "more than 256 arguments");
  for (int k = 0; k < e->narguments; k++) argv[1 + k] = e->arguments[k];
  for (int i = 1; i < argc; i++) {
    *bad = i - 1;
    int taken = 0;
    SESSILE_CHECK(g->arg, SESSILE_ERR_USAGE, "%s takes no arguments", g->name);
    SESSILE_CALL(g->arg(p->extra, argc, argv, &i, &taken));
    SESSILE_CHECK(taken, SESSILE_ERR_USAGE, "'%.60s' is no argument of %s", argv[i], g->name);
  }
  return SESSILE_OK;
}

/* The entry's parameters: its arguments, the generator's defaults (its
 * preset fallback), then each "name=value"; "iterations=N" sets the
 * iterations; then the generator's checks and schedule.  *where: what a
 * failure names ("parameters[1]", "arguments[0]"). */
static sessile_status params_of(const sessile_generator *g, const sessile_reef_entry *e, organism_params *p,
                                sessile_gen_setup *su, char *where, size_t n) {
  SESSILE_CHECK(g->table->struct_size <= sizeof p->values, SESSILE_ERR_INTERNAL, "%s: parameters too large", g->name);
  int bad = 0;
  snprintf(where, n, "arguments");
  if (g->extra_size) SESSILE_CHECK(p->extra = calloc(1, g->extra_size), SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status s = e->narguments ? arguments_of(g, e, p, &bad) : SESSILE_OK;
  if (s != SESSILE_OK) return snprintf(where, n, "arguments[%d]", bad), s;
  if (g->defaults) SESSILE_CALL(g->defaults(p->values, p->extra));
  else sessile_params_defaults(g->table, p->values);
  snprintf(where, n, "parameters");
  if (g->presets) SESSILE_CALL(g->presets->apply(g->presets->fallback, p->values));
  p->iterations = g->iterations;
  for (bad = 0; bad < e->nsettings; bad++) {
    const char *kv = e->settings[bad];
    snprintf(where, n, "parameters[%d]", bad);
    if (!strncmp(kv, "iterations=", 11)) {
      char *end = NULL;
      long it = strtol(kv + 11, &end, 10);
      SESSILE_CHECK(!g->no_iterations, SESSILE_ERR_USAGE, "%s", g->no_iterations ? g->no_iterations : "");
      SESSILE_CHECK(end != kv + 11 && !*end && it >= 1 && it <= 100000, SESSILE_ERR_USAGE,
                    "iterations must be an integer 1..100000 (not '%.40s')", kv + 11);
      p->iterations = (int)it;
    } else
      SESSILE_CALL(sessile_params_set_kv(g->table, p->values, kv));
  }
  snprintf(where, n, "parameters");
  SESSILE_CALL(sessile_params_check(g->table, p->values));
  *su = (sessile_gen_setup){.seed = su->seed, .gpu = su->gpu, .iterations = p->iterations, .extra = p->extra};
  for (int k = 0; k < g->noptions && k < SESSILE_GEN_MAX_OPTIONS; k++) su->values[k] = g->options[k].fallback;
  if (g->presets) su->preset = g->presets->fallback;
  if (g->check) SESSILE_CALL(g->check(p->values, su));
  return g->schedule ? g->schedule(p->values, su) : SESSILE_OK;
}

sessile_status cli_reef_check_entry(const char *where, int k, const sessile_reef_entry *e, int device) {
  const sessile_generator *g = find(e->generator);
  if (!g) {
    char known[512] = "";
    for (int i = 0; cli_generators[i]; i++)
      if (strcmp(cli_generators[i]->name, "reef"))
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", known[0] ? ", " : "",
                 cli_generators[i]->name);
    for (int i = 0; own_command[i]; i++)
      snprintf(known + strlen(known), sizeof known - strlen(known), ", %s", own_command[i]->name);
    return sessile_error_set(SESSILE_ERR_USAGE, "%s: pool[%d].generator: '%.60s' is no generator a pool can hold "
                             "(known: %s)", where, k, e->generator, known);
  }
  static organism_params p;
  sessile_gen_setup su = {.seed = 1};
  char at[64];
  sessile_status s = params_of(g, e, &p, &su, at, sizeof at);
  int needs = s == SESSILE_OK && g->needs_device && g->needs_device(p.values);
  params_free(g, &p);
  if (s != SESSILE_OK) return sessile_error_pass(s, "%s: pool[%d].%s", where, k, at);
  SESSILE_CHECK(!needs || device, SESSILE_ERR_USAGE,
                "%s: pool[%d].generator: %s needs a device here: keep --set device_exposure=true", where, k,
                e->generator);
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

static sessile_status run_in(const sessile_generator *g, organism_params *p, sessile_gen_setup *su,
                             const char *dir, sessile_surface *out, sessile_reef_scalars *scalars) {
  sessile_run_options o = {.dir = dir, .generator = g->generator ? g->generator : g->name,
                           .version = "reef organism", .mode = SESSILE_RUN_NEW};
  sessile_run *run = NULL;
  SESSILE_CALL(sessile_run_open(&o, &run));
  su->run = run;
  sessile_status s = SESSILE_OK;
  if (g->needs_device && g->needs_device(p->values) && !su->gpu)
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s needs a device", g->name);
  int done = 0;
  if (s == SESSILE_OK) s = sessile_run_loop(g, p->values, su, NULL, NULL, &done);
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

sessile_status cli_reef_organism(void *ctx, const sessile_reef_entry *e, uint64_t seed, double exposure,
                                 sessile_surface *out, sessile_reef_scalars *scalars) {
  cli_reef_organisms *c = ctx;
  /* the reef's last iteration is checkpointed: a resume runs finish again */
  int stop = c->run ? sessile_run_stop_requested(c->run) : 0;
  SESSILE_CHECK(!stop, SESSILE_ERR_INTERRUPTED, "stopped by signal %d while generating organisms", stop);
  const sessile_generator *g = find(e->generator);
  SESSILE_CHECK(g, SESSILE_ERR_USAGE, "unknown generator '%.60s'", e->generator);
  static organism_params p;
  char at[64];
  sessile_gen_setup su = {.seed = seed};
  sessile_status s = params_of(g, e, &p, &su, at, sizeof at);
  if (s == SESSILE_OK) {
    thicken(g, p.values, exposure);
    su.gpu = g->needs_device && g->needs_device(p.values) ? c->gpu : NULL;
  }
  const char *tmp = getenv("TMPDIR");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/sessile-reef-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  if (s == SESSILE_OK && !mkdtemp(dir))
    s = sessile_error_set(SESSILE_ERR_IO, "cannot make a temporary folder in %s", tmp && tmp[0] ? tmp : "/tmp");
  else if (s == SESSILE_OK) {
    char sub[4200];
    snprintf(sub, sizeof sub, "%s/run", dir);
    s = run_in(g, &p, &su, sub, out, scalars);
    cli_reef_remove_tree(dir);
  }
  params_free(g, &p);
  if (s == SESSILE_OK) c->made++;
  return s;
}
