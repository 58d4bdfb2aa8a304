/* The command-line interface: shared option parsing and exit codes. */
#ifndef SESSILE_CLI_H
#define SESSILE_CLI_H
#include "sessile/gpu.h"
#include "sessile/params.h"

enum { EXIT_OK = 0, EXIT_RUNTIME = 1, EXIT_USAGE = 2 };

/* Options every command that uses the device accepts. */
typedef struct {
  const char *device;
  int precision; /* 0 auto */
  int validation;
} cli_gpu_opts;

/* Prints "sessile: error: ..." (one line) and returns EXIT_USAGE. */
int cli_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Prints the library's last message and returns the exit code for s. */
int cli_fail(sessile_status s);
/* Parses an unsigned integer in [lo, hi]; returns 0 on success. */
int cli_parse_uint(const char *cmd, const char *opt, const char *val, unsigned lo, unsigned hi,
                   unsigned *out);
/* Consumes a device option at argv[*i] (--device X, --precision P,
 * --validation); returns 1 if consumed, 0 if not one, -1 on a usage error. */
int cli_gpu_option(const char *cmd, int argc, char **argv, int *i, cli_gpu_opts *o);
sessile_status cli_gpu_create(const cli_gpu_opts *o, sessile_gpu **g);
/* Applies one --set KEY=VALUE to p (SESSILE_ERR_USAGE with a message on bad input). */
sessile_status cli_params_set_kv(sessile_params *p, const char *kv);

int cmd_devices(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench(int argc, char **argv, const cli_gpu_opts *global);
int cmd_grow(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_grow(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_fluid(int argc, char **argv, const cli_gpu_opts *global);
#endif
