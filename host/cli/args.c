/* Shared option parsing: one-line errors and exit code 2 for bad usage. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include "cli.h"
#include "cli_gpu_env.h"

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
  if (*i + 1 < argc && cli_attached(argv[*i + 1])) return argv[++*i]; /* --out=X: X, whatever it holds */
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
    return cli_usage_error(cmd, "%s: '%.40s' is not an integer in %u..%u", opt, val, lo, hi);
  *out = (unsigned)v;
  return 0;
}

int cli_is_decimal(const char *v) {
  /* [sign] digits [. digits] [e [sign] digits], at least one digit before the exponent */
  const char *c = v;
  int digits = 0;
  if (!c) return 0;
  if (*c == '-' || *c == '+') c++;
  for (; *c >= '0' && *c <= '9'; c++) digits++;
  if (*c == '.')
    for (c++; *c >= '0' && *c <= '9'; c++) digits++;
  if (!digits) return 0;
  if (*c == 'e' || *c == 'E') {
    c++;
    if (*c == '-' || *c == '+') c++;
    if (*c < '0' || *c > '9') return 0;
    while (*c >= '0' && *c <= '9') c++;
  }
  return *c == 0;
}

int cli_parse_double(const char *cmd, const char *opt, const char *val, double lo, double hi, double *out) {
  if (!val || !*val) return cli_usage_error(cmd, "%s needs a value", opt);
  double x = cli_is_decimal(val) ? strtod(val, NULL) : NAN;
  if (!isfinite(x) || x < lo || x > hi)
    return cli_usage_error(cmd, "%s: '%.40s' is not a decimal number in [%g, %g]", opt, val, lo, hi);
  *out = x;
  return 0;
}

/* The valued options given so far on this command line (one per process):
 * global options and the command's share it, so that `sessile --device 0
 * grow --device 1` is refused too. */
static const char *seen_opts[64];
static int nseen_opts;

int cli_once(const char *cmd, const char *key, const char *typed) {
  for (int k = 0; k < nseen_opts; k++)
    if (!strcmp(seen_opts[k], key)) {
      cli_usage_error(cmd, "%s given twice", typed ? typed : key);
      return -1;
    }
  if (nseen_opts < (int)(sizeof seen_opts / sizeof seen_opts[0])) seen_opts[nseen_opts++] = key;
  return 0;
}

const char *cli_short(const char *name, char buf[CLI_SHORT_BUF]) {
  size_t n = name ? strlen(name) : 0;
  if (n <= 60) return name ? name : "";
  snprintf(buf, CLI_SHORT_BUF, "%.60s...", name);
  return buf;
}

int cli_gpu_option(const char *cmd, int argc, char **argv, int *i, cli_gpu_opts *o) {
  const char *a = argv[*i];
  if (strcmp(a, "--validation") == 0) {
    o->validation = 1;
    return 1;
  }
  if (strcmp(a, "--device") != 0 && strcmp(a, "--precision") != 0) return 0;
  const char *v = cli_value(cmd, argc, argv, i);
  if (!v || cli_once(cmd, a, a)) return -1;
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

/* Below this address space a Vulkan driver can die inside device or
 * pipeline creation (lavapipe: SIGSEGV or a double free under ulimit -v
 * 400000, measured) instead of failing: refuse before creating it. */
#define CLI_MIN_ADDRESS_SPACE (1024.0 * 1048576.0)

static _Atomic unsigned long long validation_messages;

/* The library's default line, counted (the layer may call from any thread). */
static void on_validation(void *user, int is_error, const char *msg) {
  (void)user;
  validation_messages++;
  fprintf(stderr, "sessile: vulkan validation %s: %s\n", is_error ? "error" : "warning", msg);
}

unsigned long long cli_validation_messages(void) { return validation_messages; }

sessile_status cli_gpu_create(const cli_gpu_opts *o, sessile_gpu **g) {
  struct rlimit rl;
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur < CLI_MIN_ADDRESS_SPACE)
    return sessile_error_set(SESSILE_ERR_NO_MEMORY,
                             "the address-space limit (ulimit -v) is %.0f MiB: a Vulkan device needs at least "
                             "%.0f MiB of address space (its driver's code, threads and heaps); raise the limit",
                             (double)rl.rlim_cur / 1048576.0, CLI_MIN_ADDRESS_SPACE / 1048576.0);
  sessile_gpu_options go;
  sessile_gpu_options_default(&go);
  go.device = o->device;
  go.precision = o->precision;
  if (o->validation) go.validation = 1;
  go.validation_message = on_validation;
  cli_gpu_env_store st;
  SESSILE_CALL(cli_gpu_env(&go, &st));
  return sessile_gpu_create(&go, g);
}

sessile_status cli_gpu_check(const cli_gpu_opts *o) {
  return sessile_gpu_check_device(cli_env_device(o->device));
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
