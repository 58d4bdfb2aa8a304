/* Shared generator options and the run directory's life (cli_run.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli_progress.h"
#include "cli_run.h"

int cli_run_args_init(cli_run_args *a, int argc, unsigned long long seed, int iterations, int every) {
  memset(a, 0, sizeof *a);
  a->seed = seed, a->iterations = iterations, a->every = every;
  a->configs = calloc((size_t)argc + 1, sizeof *a->configs);
  a->sets = calloc((size_t)argc + 1, sizeof *a->sets);
  return a->configs && a->sets ? 0 : -1;
}

void cli_run_args_free(cli_run_args *a) {
  free(a->configs);
  free(a->sets);
}

int cli_run_option(const char *cmd, int argc, char **argv, int *i, cli_run_args *a) {
  const char *opt = argv[*i];
  unsigned u = 0;
  if (!strcmp(opt, "--print-config")) return a->print_config = a->have_run_option = 1;
  if (!strcmp(opt, "--quiet")) return a->quiet = 1;
  if (!strcmp(opt, "--no-preview")) return a->no_preview = 1;
  if (!strcmp(opt, "--glb")) return a->glb = 1;
  if (!strcmp(opt, "--obj-axes")) { /* like --glb: how this invocation writes, also with --resume */
    const char *v = cli_value(cmd, argc, argv, i);
    if (!v || cli_once(cmd, opt, opt)) return -1;
    if (!sessile_obj_axes_parse(v, &a->obj_axes)) return 1;
    cli_usage_error(cmd, "--obj-axes takes zup-cm (sessile's z up, cm) or yup-m (y up, metres), not '%.40s'", v);
    return -1;
  }
  if (!strcmp(opt, "--force")) return a->force = a->have_run_option = 1;
  int r = cli_progress_option(cmd, argc, argv, i, &a->progress);
  if (r) return r;
  static const char *valued[] = {"--config", "--set", "--out", "--resume", "--iterations", "--every", "--seed"};
  int k = 0;
  while (k < 7 && strcmp(opt, valued[k])) k++;
  if (k == 7) return 0;
  const char *v = cli_value(cmd, argc, argv, i);
  if (!v) return -1;
  if (k >= 2 && cli_once(cmd, opt, opt)) return -1; /* --config and --set repeat */
  if (k != 3 && k != 4) a->have_run_option = 1;
  switch (k) {
  case 0: a->configs[a->nconfigs++] = v; break;
  case 1: a->sets[a->nsets++] = v; break;
  case 2: a->out = v; break;
  case 3: a->resume = v; break;
  case 4:
    if (cli_parse_uint(cmd, opt, v, 0, 10000000, &u)) return -1;
    a->iterations = (int)u, a->have_iterations = 1;
    break;
  case 5:
    if (cli_parse_uint(cmd, opt, v, 0, 10000000, &u)) return -1;
    a->every = (int)u;
    break;
  default:
    if (cli_parse_seed(cmd, v, &a->seed)) return -1;
  }
  return 1;
}

int cli_run_args_check(const char *cmd, const cli_run_args *a) {
  if (a->resume && a->have_run_option)
    return cli_usage_error(cmd, "--resume continues a run with its own configuration: only "
                                "--iterations, --quiet, --progress and device options go with it");
  return -1;
}

sessile_status cli_run_apply_params(const sessile_param_table *t, void *values, const cli_run_args *a) {
  for (int k = 0; k < a->nconfigs; k++) SESSILE_CALL(sessile_params_load_json(t, values, a->configs[k]));
  for (int k = 0; k < a->nsets; k++) SESSILE_CALL(sessile_params_set_kv(t, values, a->sets[k]));
  return SESSILE_OK;
}

sessile_status cli_run_admit(const char *generator, int argc, char **argv, const cli_run_args *a,
                             const char *dir, volatile sig_atomic_t *stop, sessile_run **run) {
  /* the manifest records the whole command line, global options included */
  cli_command_line(&argc, &argv);
  sessile_run_options ro = {.dir = dir, .generator = generator, .version = cli_version(), .commit = cli_commit(),
                            .argc = argc, .argv = argv,
                            .mode = a->resume ? SESSILE_RUN_RESUME
                                    : a->force ? SESSILE_RUN_REPLACE : SESSILE_RUN_NEW,
                            .stop = stop};
  return sessile_run_admit(&ro, run);
}

sessile_status cli_run_open(const char *generator, int argc, char **argv, const cli_run_args *a,
                            const char *dir, volatile sig_atomic_t *stop, sessile_run **run) {
  SESSILE_CALL(cli_run_admit(generator, argc, argv, a, dir, stop, run));
  sessile_status s = sessile_run_start(*run);
  if (s != SESSILE_OK) {
    sessile_run_close(*run, s); /* not started: writes nothing */
    *run = NULL;
  }
  return s;
}

void cli_run_note_device(sessile_run *run, sessile_gpu *g) {
  cJSON *m = run && g ? sessile_run_manifest(run) : NULL;
  cJSON *d = m ? cJSON_CreateObject() : NULL;
  if (!d) return; /* the manifest goes without it: out of host memory */
  const sessile_gpu_info *gi = sessile_gpu_info_of(g);
  cJSON_AddStringToObject(d, "name", gi->name);
  cJSON_AddStringToObject(d, "type", gi->type);
  cJSON_AddStringToObject(d, "driver", gi->driver);
  cJSON_AddNumberToObject(d, "precision_bits", gi->precision);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "device");
  cJSON_AddItemToObject(m, "device", d);
}

int cli_run_exit(const char *cmd, sessile_status s, const char *dir, const volatile sig_atomic_t *stop,
                 int iterations_done) {
  if (s == SESSILE_ERR_INTERRUPTED) {
    fprintf(stderr, "sessile %s: interrupted (signal %d) after iteration %d; its state is saved: "
                    "continue with 'sessile %s --resume %s'\n", cmd, (int)*stop, iterations_done, cmd, dir);
    return cli_signal_exit_code((int)*stop);
  }
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
