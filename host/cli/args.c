/* Shared option parsing: one-line errors and exit code 2 for bad usage. */
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

int cli_fail(sessile_status s) {
  fprintf(stderr, "sessile: error: %s\n", sessile_error_message());
  return s == SESSILE_ERR_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
}

int cli_parse_uint(const char *cmd, const char *opt, const char *val, unsigned lo, unsigned hi,
                   unsigned *out) {
  char *end = NULL;
  if (!val || !*val) return cli_usage_error(cmd, "%s needs a value", opt);
  unsigned long v = strtoul(val, &end, 10);
  if (*end || val[0] == '-' || v < lo || v > hi)
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
  if (*i + 1 >= argc) {
    cli_usage_error(cmd, "%s needs a value", a);
    return -1;
  }
  const char *v = argv[++*i];
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

sessile_status cli_params_set_kv(sessile_params *p, const char *kv) {
  char key[128];
  const char *eq = strchr(kv, '=');
  if (!eq || eq == kv || (size_t)(eq - kv) >= sizeof key)
    return sessile_error_set(SESSILE_ERR_USAGE, "--set '%s' must be KEY=VALUE", kv);
  memcpy(key, kv, (size_t)(eq - kv));
  key[eq - kv] = 0;
  return sessile_params_set(p, key, eq + 1);
}
