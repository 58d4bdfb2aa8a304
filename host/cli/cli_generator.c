/* The one command every registered generator runs through (cli_generator.h):
 * parse, --help, --set/--config/--print-config, the device, admit the run
 * directory, refuse what cannot run before anything is written, start,
 * sessile_run_loop, preview, close, exit code. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli_generator.h"
#include "cli_progress.h"
#include "cli_run.h"

static void print_help(const sessile_generator *g) {
  if (g->help) {
    fputs(g->help, stdout);
    return;
  }
  int pad = (int)strlen(g->name) + 15;
  char out[512];
  snprintf(out, sizeof out, g->out_default, g->presets ? g->presets->fallback : ""); /* "runs/%s": the preset's */
  printf("usage: sessile %s%s [--config FILE.json]... [--set KEY=VALUE]... [--seed N]\n"
         "%*s[--iterations N] [--every K] [--out DIR] [--force] [--print-config]\n"
         "%*s[--quiet] [--progress auto|tty|lines|json|none]\n",
         g->name, g->presets ? " [--preset NAME]" : "", pad, "", pad, "");
  for (int k = 0; k < g->noptions; k++) printf("%*s[%s %s]\n", pad, "", g->options[k].option, g->options[k].metavar);
  for (int k = 0; k < g->nflags; k++) printf("%*s[%s]\n", pad, "", g->flags[k].option);
  if (g->needs_device) printf("%*s[--device D] [--precision 32|64]\n", pad, "");
  printf("       sessile %s --resume DIR [--iterations N]\n\n%s\n"
         "Parameters, units and sources: --print-config.\n\n", g->name, g->about);
  if (g->presets) printf("  --preset NAME   the parameters' starting point (default %s):\n%s\n", g->presets->fallback,
                         g->presets->help);
  printf("  --seed N        seed of %s, 0..2^64-1 (default 1)\n"
         "  --iterations N  iterations (default %d)      --every K  snapshot interval (default %d)\n"
         "  --out DIR       run directory (default %s); must be new or empty\n"
         "  --force         replace the earlier sessile run in DIR     --resume DIR  continue it\n"
         "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
         "  --glb           the final mesh as glTF 2.0 binary too (.glb beside the .ply; docs/io.md)\n"
         "  --obj-axes A    OBJ files (where written) in zup-cm, sessile's z up and cm (default),\n"
         "                  or yup-m, y up and metres for Blender and other DCC tools (docs/io.md)\n"
         "  --quiet         no progress and no summary line\n"
         "%s"
         "  --max-memory G  stop with the state saved once the process holds more than G GiB\n"
         "                  after an iteration (default: half the machine's memory; also with --resume)\n",
         g->seed_help, g->iterations, g->every, out, cli_progress_help);
  for (int k = 0; k < g->noptions; k++) {
    char head[64];
    snprintf(head, sizeof head, "%s %s", g->options[k].option, g->options[k].metavar);
    printf("  %-15s %s (default '%s')\n", head, g->options[k].help, g->options[k].fallback);
  }
  for (int k = 0; k < g->nflags; k++) printf("  %-15s %s\n", g->flags[k].option, g->flags[k].help);
  if (g->needs_device) printf("  --device D      the device, when the configuration needs one (sessile --help)\n");
  printf("Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n");
}

typedef struct gen_cmd {
  const sessile_generator *g;
  cli_run_args a;
  cli_gpu_opts go;
  sessile_gen_setup su;
  sessile_gen_result result;
  cJSON *stored; /* a resume's stored configuration: su's strings point into it */
  char out_default[512];
  char params[4096] __attribute__((aligned(16))); /* the table's struct */
} gen_cmd;

/* The generator's own options with a value, and --preset: 1 consumed, 0
 * not one, -1 usage error.  An empty value is a value (--slices ''). */
static int option(gen_cmd *c, int argc, char **argv, int *i) {
  const sessile_generator *g = c->g;
  int k = 0, n = g->noptions < SESSILE_GEN_MAX_OPTIONS ? g->noptions : SESSILE_GEN_MAX_OPTIONS;
  while (k < n && strcmp(argv[*i], g->options[k].option)) k++;
  const char **to = k < n ? &c->su.values[k] : NULL;
  if (!to && g->presets && !strcmp(argv[*i], "--preset")) to = &c->su.preset;
  if (!to) return 0;
  if (cli_once(g->name, argv[*i], argv[*i])) return -1; /* the last one winning hid mistakes */
  if (*i + 1 < argc && !argv[*i + 1][0]) *to = argv[++*i];
  else if (!(*to = cli_value(g->name, argc, argv, i))) return -1;
  c->a.have_run_option = 1;
  return 1;
}

static int parse(gen_cmd *c, int argc, char **argv) {
  const char *name = c->g->name;
  for (int i = 1; i < argc; i++) {
    if (cli_stray_value(name, argv, i)) return EXIT_USAGE;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      print_help(c->g);
      return EXIT_OK;
    }
    if (c->g->arg) {
      int taken = 0;
      sessile_status s = c->g->arg(c->su.extra, argc, argv, &i, &taken);
      if (s != SESSILE_OK) return cli_fail_in(name, s);
      if (taken == 1) c->a.have_run_option = 1;
      if (taken) continue;
    }
    int k = 0;
    while (k < c->g->nflags && strcmp(argv[i], c->g->flags[k].option)) k++;
    if (k < c->g->nflags) {
      c->su.flags |= 1u << k;
      c->a.have_run_option = 1;
      continue;
    }
    if (!strcmp(argv[i], "--max-memory")) {
      const char *v = cli_value(name, argc, argv, &i);
      char *end = NULL;
      double gib = v ? strtod(v, &end) : 0;
      if (!v) return EXIT_USAGE;
      if (cli_once(name, "--max-memory", "--max-memory")) return EXIT_USAGE;
      if (end == v || *end || !(gib > 0 && gib <= 1e6) || strpbrk(v, "xXnNiI"))
        return cli_usage_error(name, "--max-memory takes GiB, a number above 0 (not '%.40s')", v);
      c->su.max_memory = gib * 1073741824.0;
      continue;
    }
    int r = option(c, argc, argv, &i);
    if (r == 0) r = cli_gpu_option(name, argc, argv, &i, &c->go);
    if (r == 0) r = cli_run_option(name, argc, argv, &i, &c->a);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(name, "unknown option '%.60s'", argv[i]);
  }
  if (c->g->no_iterations && (c->a.have_iterations || c->a.every != c->g->every))
    return cli_usage_error(name, "%s", c->g->no_iterations);
  return cli_run_args_check(name, &c->a);
}

/* Everything that can be refused before the run directory is touched. */
static sessile_status configure(gen_cmd *c) {
  const sessile_generator *g = c->g;
  SESSILE_CHECK(g->table->struct_size <= sizeof c->params, SESSILE_ERR_INTERNAL, "%s: parameters too large", g->name);
  if (g->defaults && !c->a.resume) SESSILE_CALL(g->defaults(c->params, c->su.extra));
  else sessile_params_defaults(g->table, c->params);
  c->su.seed = c->a.seed, c->su.iterations = c->a.iterations, c->su.every = c->a.every;
  if (c->a.resume) return SESSILE_OK; /* the stored configuration, once admitted */
  if (g->presets) SESSILE_CALL(g->presets->apply(c->su.preset, c->params));
  SESSILE_CALL(cli_run_apply_params(g->table, c->params, &c->a));
  SESSILE_CALL(sessile_params_check(g->table, c->params));
  if (g->check) SESSILE_CALL(g->check(c->params, &c->su));
  return g->schedule && !c->a.print_config ? g->schedule(c->params, &c->su) : SESSILE_OK;
}

/* A resume: the stored configuration, --iterations, and the checkpoint's
 * iteration, all before the folder is written. */
static sessile_status resume_config(gen_cmd *c, sessile_run *run) {
  const sessile_generator *g = c->g;
  c->stored = cJSON_Duplicate(sessile_run_config(run), 1); /* the run's copy is replaced at start */
  SESSILE_CHECK(c->stored, SESSILE_ERR_NO_MEMORY, "out of host memory");
  SESSILE_CALL(sessile_gen_config_read(g, c->stored, c->params, &c->su));
  if (c->a.have_iterations) c->su.iterations = c->a.iterations;
  int k = sessile_ckpt_iteration(sessile_run_checkpoint_loaded(run));
  SESSILE_CHECK(k <= c->su.iterations, SESSILE_ERR_USAGE,
                "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
  return g->check ? g->check(c->params, &c->su) : SESSILE_OK;
}

/* The device, and the checks that need it, before the folder is touched. */
static sessile_status device(gen_cmd *c, sessile_gpu **gpu) {
  SESSILE_CALL(cli_gpu_create(&c->go, gpu));
  c->su.gpu = *gpu;
  sessile_status s = c->g->check ? c->g->check(c->params, &c->su) : SESSILE_OK;
  c->su.gpu = NULL;
  return s;
}

static int run_generator(gen_cmd *c, int argc, char **argv) {
  const sessile_generator *g = c->g;
  const char *name = g->name;
  sessile_status s = configure(c);
  if (s != SESSILE_OK) return cli_fail_in(name, s);
  if (c->a.print_config) {
    s = sessile_params_print(g->table, c->params, stdout);
    return s == SESSILE_OK ? EXIT_OK : cli_fail_in(name, s);
  }
  char out[256];
  if (g->out_dir) g->out_dir(c->su.extra, out, sizeof out);
  else snprintf(out, sizeof out, g->out_default, c->su.preset ? c->su.preset : "");
  snprintf(c->out_default, sizeof c->out_default, "%s", out);
  const char *dir = c->a.resume ? c->a.resume : c->a.out ? c->a.out : c->out_default;
  /* an unknown --device is refused before any file, even where only the
   * preview would use it */
  if ((s = cli_gpu_check(&c->go)) != SESSILE_OK) return cli_fail_in(name, s);
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_gpu *gpu = NULL;
  /* a new run's device first: an unknown --device writes nothing */
  if (!c->a.resume && g->needs_device && g->needs_device(c->params)) s = device(c, &gpu);
  sessile_run *run = NULL;
  if (s == SESSILE_OK) s = cli_run_admit(g->generator ? g->generator : name, argc, argv, &c->a, dir, stop, &run);
  if (s == SESSILE_OK && c->a.resume) s = resume_config(c, run);
  if (s == SESSILE_OK && c->a.resume && g->needs_device && g->needs_device(c->params))
    s = device(c, &gpu);
  if (s == SESSILE_OK) s = sessile_run_start(run);
  if (s == SESSILE_OK) {
    cJSON *cfg = sessile_gen_config(g, c->params, &c->su);
    s = cfg ? sessile_run_set_config(run, cfg) : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  if (s == SESSILE_OK) cli_run_note_device(run, gpu);
  if (s == SESSILE_OK) cli_run_obj_style(name, &c->a, run);
  int done = 0;
  c->su.run = run, c->su.gpu = gpu, c->su.result = &c->result;
  cli_progress mon;
  cli_progress_start(&mon, name, c->a.progress, c->a.quiet);
  c->su.say = cli_progress_say, c->su.say_user = &mon;
  if (s == SESSILE_OK) s = sessile_run_loop(g, c->params, &c->su, cli_progress_report, &mon, &done);
  cli_progress_end(&mon);
  if (s == SESSILE_OK && g->preview) s = cli_run_glb(name, &c->a, run, g->preview);
  if (s == SESSILE_OK && g->preview) cli_run_preview(name, &c->a, run, g->preview, gpu, &c->go);
  s = sessile_run_close(run, s);
  sessile_gpu_destroy(gpu);
  if (s == SESSILE_OK && !c->a.quiet && c->result.summary[0]) printf("%s; run in %s\n", c->result.summary, dir);
  else if (s == SESSILE_OK && !c->a.quiet) printf("%s: %d iterations; run in %s\n", name, done, dir);
  if (s != SESSILE_OK && s != SESSILE_ERR_INTERRUPTED) {
    int rc = cli_fail_in(name, s);
    return c->result.exit_code ? c->result.exit_code : rc;
  }
  return cli_run_exit(name, s, dir, stop, done);
}

int cli_generator_main(const sessile_generator *g, int argc, char **argv, const cli_gpu_opts *global) {
  static gen_cmd c;
  memset(&c, 0, sizeof c);
  c.g = g, c.go = *global;
  c.su.max_memory = 0.5 * sessile_physical_memory();
  if (g->extra_size && !(c.su.extra = calloc(1, g->extra_size))) {
    fprintf(stderr, "sessile %s: error: out of host memory\n", g->name);
    return EXIT_RUNTIME;
  }
  for (int k = 0; k < g->noptions && k < SESSILE_GEN_MAX_OPTIONS; k++) c.su.values[k] = g->options[k].fallback;
  if (g->presets) c.su.preset = g->presets->fallback;
  if (cli_run_args_init(&c.a, argc, 1, g->iterations, g->every) != 0) {
    cli_run_args_free(&c.a);
    fprintf(stderr, "sessile %s: error: out of host memory\n", g->name);
    return EXIT_RUNTIME;
  }
  int rc = parse(&c, argc, argv);
  if (rc < 0) rc = run_generator(&c, argc, argv);
  cli_run_args_free(&c.a);
  if (g->extra_free && c.su.extra) g->extra_free(c.su.extra);
  free(c.su.extra);
  cJSON_Delete(c.stored);
  return rc;
}
