/* The command-line interface: shared option parsing and exit codes. */
#ifndef SESSILE_CLI_H
#define SESSILE_CLI_H
#include <signal.h>
#include <stdio.h>
#include "sessile/gpu/gpu.h"
#include "sessile/run/param_table.h"
#include "sessile/growth/grow_params.h"

enum { EXIT_OK = 0, EXIT_RUNTIME = 1, EXIT_USAGE = 2 };

/* Options every command that uses the device accepts. */
typedef struct {
  const char *device;
  int precision; /* 0 auto */
  int validation;
} cli_gpu_opts;

/* The version, "0.1.0", and the commit the binary was built from, "ab63207"
 * (git describe --always --dirty at build time; "unknown" without git). */
const char *cli_version(void);
const char *cli_commit(void);
/* Prints "sessile 0.1.0 (commit ab63207)"; returns EXIT_OK. */
int cli_print_version(void);

/* GNU long options (docs/design.md "Command line"): every `--name=value`
 * word becomes the two words `--name` `value` before any command parses,
 * so each parser's `--name value` handling takes both forms.  Returns 0,
 * or -1 out of host memory; cli_split_free releases what it made. */
int cli_split_options(int argc, char **argv, int *nargc, char ***nargv);
void cli_split_free(void);
/* Whether word came from the right of a `--name=value` (pointer identity). */
int cli_attached(const char *word);
/* Every option loop calls it first for argv[i]: an attached value that no
 * option took (`--force=1`) is refused, "--force takes no value"; returns
 * EXIT_USAGE then, else 0. */
int cli_stray_value(const char *cmd, char **argv, int i);
/* `--version` anywhere on the (split) command line: prints "sessile 0.1.0
 * (commit ab63207)" and returns EXIT_OK; -1 when absent; EXIT_USAGE for
 * `--version=x`. */
int cli_version_option(int argc, char **argv);

/* Prints "sessile: error: ..." (one line) and returns EXIT_USAGE. */
int cli_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Prints the library's last message and returns the exit code for s. */
int cli_fail(sessile_status s);
/* The same, naming the command: "sessile coral venation: error: ...". */
int cli_fail_in(const char *cmd, sessile_status s);
/* The value of the option at argv[*i] (advancing *i), or NULL after a
 * usage error when it is missing or starts with "--" ("--out needs a
 * value": `--out --print-config` must not make a folder named so); an
 * attached value (`--out=X`) is taken whatever it holds. */
const char *cli_value(const char *cmd, int argc, char **argv, int *i);
/* Parses a seed: decimal digits only, within 0..2^64-1. */
int cli_parse_seed(const char *cmd, const char *val, unsigned long long *out);
/* Parses an unsigned integer in [lo, hi]; returns 0 on success. */
int cli_parse_uint(const char *cmd, const char *opt, const char *val, unsigned lo, unsigned hi,
                   unsigned *out);
/* Whether v is a plain decimal number: [sign] digits [. digits] [e [sign]
 * digits], the whole string (no blanks, hex, inf or nan). */
int cli_is_decimal(const char *v);
/* Parses a decimal number (cli_is_decimal) that is finite and in [lo, hi];
 * returns 0 on success, else prints a usage error and returns EXIT_USAGE. */
int cli_parse_double(const char *cmd, const char *opt, const char *val, double lo, double hi, double *out);
/* A valued option that may be given once: records key (the option's
 * canonical name, e.g. "--out" for -o too); the second time prints "TYPED
 * given twice" and returns -1.  Repeatable options (--set, --config,
 * --define, --caption) do not call it.  One command line per process. */
int cli_once(const char *cmd, const char *key, const char *typed);
/* A name for a message: itself up to 60 characters, else its first 60 and
 * "..." (in buf), so that the reason after it is never cut. */
enum { CLI_SHORT_BUF = 64 };
const char *cli_short(const char *name, char buf[CLI_SHORT_BUF]);
/* Consumes a device option at argv[*i] (--device X, --precision P,
 * --validation); returns 1 if consumed, 0 if not one, -1 on a usage error. */
int cli_gpu_option(const char *cmd, int argc, char **argv, int *i, cli_gpu_opts *o);
sessile_status cli_gpu_create(const cli_gpu_opts *o, sessile_gpu **g);
/* Validation-layer messages printed so far by the contexts cli_gpu_create
 * made (each as "sessile: vulkan validation error|warning: ..."): main fails
 * a command that printed any (docs/design.md, "Errors and diagnostics"). */
unsigned long long cli_validation_messages(void);
/* The device the options (or $SESSILE_DEVICE) name exists: cheap (lists the
 * devices, creates none), so that a command refuses an unknown device
 * before it writes anything.  SESSILE_OK when none is named. */
sessile_status cli_gpu_check(const cli_gpu_opts *o);
/* Applies one --set KEY=VALUE to p (SESSILE_ERR_USAGE with a message on bad input). */
sessile_status cli_params_set_kv(sessile_grow_params *p, const char *kv);
/* Writes stdout's pending output and reports a failure (a full disk, a
 * closed pipe): returns EXIT_RUNTIME then, else rc. */
int cli_finish_stdout(int rc);

/* SIGINT/SIGTERM: the first sets the returned flag to the signal number
 * (the run stops at its next safe point and saves its state); a second one
 * ends the process at once. */
volatile sig_atomic_t *cli_stop_flag_install(void);
/* 130 for SIGINT, 143 for SIGTERM. */
int cli_signal_exit_code(int signo);

/* The whole command line (global options included), for the manifest. */
void cli_set_command_line(int argc, char **argv);
void cli_command_line(int *argc, char ***argv);

/* One subcommand: name, one-line summary for `sessile --help`, entry. */
typedef struct cli_command {
  const char *name, *summary;
  int (*run)(int argc, char **argv, const cli_gpu_opts *global);
} cli_command;

int cmd_devices(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_grow(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_fluid(int argc, char **argv, const cli_gpu_opts *global);
/* User + system CPU seconds of the whole process so far (cli_cpu.c; lavapipe's threads too). */
double cli_cpu_seconds(void);
/* The kernels' device times recorded under sessile_gpu_profile, dearest
 * first, with their share of wall_s (cli_kernels.c; bench --kernels). */
void cli_print_kernels(sessile_gpu *g, const char *what, double wall_s);
/* `sessile coral lsystem|venation` (cmd_coral.c dispatches). */
int cmd_coral(int argc, char **argv, const cli_gpu_opts *global);
int cmd_coral_lsystem(int argc, char **argv, const cli_gpu_opts *global);
/* `sessile sponge particles`: Coralize's particle-fed sponge. */
int cmd_sponge(int argc, char **argv, const cli_gpu_opts *global);
/* `sessile sds run MODEL`, `sessile sds models` (cmd_sds.c). */
int cmd_sds(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_sds(int argc, char **argv, const cli_gpu_opts *global);
/* `sessile render FILE -o OUT.png` (cmd_render.c); `sessile bench render`. */
int cmd_render(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_render(int argc, char **argv, const cli_gpu_opts *global);
/* `sessile bench coral` and `bench sponge`: one section per generator
 * (cmd_bench_coral_*.c, cmd_bench_sponge_*.c). */
int cmd_bench_coral(int argc, char **argv, const cli_gpu_opts *global);
int cmd_bench_sponge(int argc, char **argv, const cli_gpu_opts *global);
typedef struct bench_section_opts {
  int quick; /* smaller sizes: a smoke run for the tests */
} bench_section_opts;
typedef sessile_status bench_section_fn(sessile_gpu *g, const bench_section_opts *o, FILE *out);
sessile_status bench_coral_lsystem(sessile_gpu *g, const bench_section_opts *o, FILE *out);
sessile_status bench_coral_weld(sessile_gpu *g, const bench_section_opts *o, FILE *out);
sessile_status bench_coral_venation(sessile_gpu *g, const bench_section_opts *o, FILE *out);
sessile_status bench_sponge_particles(sessile_gpu *g, const bench_section_opts *o, FILE *out);
#endif
