/* Shared option parsing: one-line errors and exit code 2 for bad usage. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

int cli_usage_error(const char *cmd, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "sessile%s%s: error: ", cmd ? " " : "", cmd ? cmd : "");
  vfprintf(stderr, fmt, ap);
  fprintf(stderr, " (see 'sessile%s%s --help')\n", cmd ? " " : "", cmd ? cmd : "");
  va_end(ap);
  return EXIT_USAGE;
}

int cli_fail(sessile_status s) { return cli_fail_in(NULL, s); }

int cli_fail_in(const char *cmd, sessile_status s) {
  /* copy first: the message buffer is the library's */
  char msg[1100];
  snprintf(msg, sizeof msg, "%s", sessile_error_message());
  fprintf(stderr, "sessile%s%s: error: %s\n", cmd ? " " : "", cmd ? cmd : "", msg);
  return s == SESSILE_ERR_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
}

const char *cli_value(const char *cmd, int argc, char **argv, int *i) {
  const char *opt = argv[*i];
  if (*i + 1 >= argc || strncmp(argv[*i + 1], "--", 2) == 0) {
    cli_usage_error(cmd, "%s needs a value", opt);
    return NULL;
  }
  return argv[++*i];
}

int cli_parse_seed(const char *cmd, const char *val, unsigned long long *out) {
  int ok = val && *val && strlen(val) <= 20;
  for (const char *c = val; ok && *c; c++) ok = *c >= '0' && *c <= '9';
  errno = 0;
  char *end = NULL;
  unsigned long long v = ok ? strtoull(val, &end, 10) : 0;
  if (!ok || errno == ERANGE || *end)
    return cli_usage_error(cmd, "--seed: '%.40s' is not an integer in 0..18446744073709551615", val ? val : "");
  *out = v;
  return 0;
}

int cli_finish_stdout(int rc) {
  /* a command that failed has said why already: one line, not two */
  if (rc != EXIT_OK) return rc;
  if (fflush(stdout) != 0 || ferror(stdout)) {
    int e = errno;
    fprintf(stderr, "sessile: error: cannot write the output: %s\n", e ? strerror(e) : "write error");
    return EXIT_RUNTIME;
  }
  return rc;
}

int cli_parse_uint(const char *cmd, const char *opt, const char *val, unsigned lo, unsigned hi,
                   unsigned *out) {
  char *end = NULL;
  if (!val || !*val) return cli_usage_error(cmd, "%s needs a value", opt);
  errno = 0;
  unsigned long v = strtoul(val, &end, 10);
  if (*end || val[0] < '0' || val[0] > '9' || errno == ERANGE || v < lo || v > hi)
    return cli_usage_error(cmd, "%s: '%s' is not an integer in %u..%u", opt, val, lo, hi);
  *out = (unsigned)v;
  return 0;
}

int cli_gpu_option(const char *cmd, int argc, char **argv, int *i, cli_gpu_opts *o) {
  const char *a = argv[*i];
  if (strcmp(a, "--validation") == 0) {
    o->validation = 1;
    return 1;
  }
  if (strcmp(a, "--device") != 0 && strcmp(a, "--precision") != 0) return 0;
  const char *v = cli_value(cmd, argc, argv, i);
  if (!v) return -1;
  if (strcmp(a, "--device") == 0) {
    if (!*v) {
      cli_usage_error(cmd, "--device needs an index or a name substring");
      return -1;
    }
    o->device = v;
    return 1;
  }
  if (strcmp(v, "32") == 0) o->precision = 32;
  else if (strcmp(v, "64") == 0) o->precision = 64;
  else {
    cli_usage_error(cmd, "--precision: '%s' must be 32 or 64", v);
    return -1;
  }
  return 1;
}

sessile_status cli_gpu_create(const cli_gpu_opts *o, sessile_gpu **g) {
  sessile_gpu_options go;
  sessile_gpu_options_default(&go);
  go.device = o->device;
  go.precision = o->precision;
  if (o->validation) go.validation = 1;
  return sessile_gpu_create(&go, g);
}

sessile_status cli_params_set_kv(sessile_grow_params *p, const char *kv) {
  return sessile_params_set_kv(&sessile_grow_param_table, p, kv);
}

static int cmd_argc;
static char **cmd_argv;

void cli_set_command_line(int argc, char **argv) {
  cmd_argc = argc;
  cmd_argv = argv;
}

void cli_command_line(int *argc, char ***argv) {
  *argc = cmd_argc;
  *argv = cmd_argv;
}
