/* sessile: grows 3-D models of marine sessile organisms from physics.
 * One table of subcommands drives both dispatch and `sessile --help`. */
#include <stdio.h>
#include <string.h>
#include "cli_generator.h"
#include "cmd_sweep.h"

static int cmd_version(int argc, char **argv, const cli_gpu_opts *g);
static int cmd_help(int argc, char **argv, const cli_gpu_opts *g);

static const cli_command commands[] = {
    {"coral", "corals after Coralize: 'coral lsystem' (stony), 'coral venation' (soft)", cmd_coral},
    {"sponge", "Coralize's particle-fed sponge: 'sponge particles'", cmd_sponge},
    {"sds", "SDS, a tetrahedral developmental system: 'sds run MODEL', 'sds models'", cmd_sds},
    {"sweep", "a study of many runs: 'sweep plan|run|submit|status|gather' (docs/sweep.md)", cmd_sweep},
    {"render", "pictures (PNG) of meshes through Vulkan; 'sessile render --help'", cmd_render},
    {"devices", "list the Vulkan devices and the one sessile uses", cmd_devices},
    {"bench", "benchmarks: 'bench la|grow|fluid|coral|sds|render' (figures, never pass/fail)", cmd_bench},
    {"help", "this text; 'sessile COMMAND --help' explains a command", cmd_help},
    {"version", "print the version", cmd_version},
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static void print_help(FILE *out) {
  fputs("usage: sessile [--device INDEX|NAME] [--precision 32|64] [--validation] COMMAND [OPTIONS]\n"
        "\n"
        "Grows 3-D models of marine sponges and corals from physics on any Vulkan device\n"
        "(GPU, or the CPU through Mesa lavapipe).\n"
        "\n"
        "commands:\n", out);
  for (int i = 0; i < NCOMMANDS; i++) fprintf(out, "  %-9s %s\n", commands[i].name, commands[i].summary);
  fputs("\ngenerators (each a run directory; 'sessile NAME --help'):\n", out);
  for (int k = 0; cli_generators[k]; k++)
    fprintf(out, "  %-16s %s\n", cli_generators[k]->name, cli_generators[k]->summary);
  fputs("\n"
        "options (before or after the command):\n"
        "  --device D      device index or name substring (default: discrete > integrated > CPU;\n"
        "                  environment SESSILE_DEVICE)\n"
        "  --precision P   Krylov and SDS kernel precision 64 or 32 (default 64 where the device\n"
        "                  has fp64; 32: mixed-precision refinement for the solvers, float SDS\n"
        "                  kernels; env SESSILE_PRECISION)\n"
        "  --validation    enable the Khronos validation layer (env SESSILE_VALIDATION=1); a message\n"
        "                  it prints fails the command (exit 1; its outputs are kept)\n"
        "  -h, --help      this text; after a command, that command's ('sessile grow --help')\n"
        "  --version       the version and commit, after any command too\n"
        "Every option's value may follow it ('--seed 7') or be joined by '=' ('--seed=7').\n"
        "\n"
        "Runs write a run directory (docs/run.md): manifest.json, records.jsonl, a checkpoint\n"
        "at every snapshot; SIGINT/SIGTERM stop a run at the end of its iteration (exit 130/143)\n"
        "and '--resume DIR' continues it to the same bytes.\n"
        "exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n"
        "sessile is free software under the GNU AGPL-3.0-or-later.\n", out);
}

static int cmd_version(int argc, char **argv, const cli_gpu_opts *g) {
  (void)g;
  if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
    fputs("usage: sessile version   (or sessile --version, after any command too)\n"
          "\n"
          "Prints the version and the commit sessile was built from ('unknown' when it was\n"
          "built outside a git checkout); manifest.json records both.\n", stdout);
    return EXIT_OK;
  }
  if (argc > 1) return cli_usage_error("version", "takes no arguments ('%s')", argv[1]);
  return cli_print_version();
}

static int cmd_help(int argc, char **argv, const cli_gpu_opts *g) {
  (void)argc, (void)argv, (void)g;
  print_help(stdout);
  return EXIT_OK;
}

static int run(int argc, char **argv) {
  cli_gpu_opts g = {0};
  int i = 1, rc = cli_version_option(argc, argv);
  if (rc >= 0) return rc;
  for (; i < argc && (argv[i][0] == '-' || cli_attached(argv[i])); i++) {
    if (cli_stray_value(NULL, argv, i)) return EXIT_USAGE;
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      print_help(stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option(NULL, argc, argv, &i, &g);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(NULL, "unknown option '%s'", argv[i]);
  }
  if (i >= argc) return cli_usage_error(NULL, "no command given");
  int words = 0;
  const sessile_generator *gen = cli_generator_find(argc - i, argv + i, &words);
  if (gen) return cli_generator_main(gen, argc - i - (words - 1), argv + i + (words - 1), &g);
  for (int c = 0; c < NCOMMANDS; c++)
    if (strcmp(argv[i], commands[c].name) == 0) return commands[c].run(argc - i, argv + i, &g);
  char names[256] = "";
  for (int c = 0; c < NCOMMANDS; c++) {
    size_t l = strlen(names);
    snprintf(names + l, sizeof names - l, "%s%s", c ? ", " : "", commands[c].name);
  }
  return cli_usage_error(NULL, "unknown command '%.60s' (commands: %s)", argv[i], names);
}

int main(int argc, char **argv) {
  /* Every command's output goes through stdout: a write error there (a full
   * disk, `> /dev/full`) is a failure, not a silent success. */
  cli_set_command_line(argc, argv); /* as typed: the manifest's "command" */
  int n = 0;
  char **words = NULL;
  if (cli_split_options(argc, argv, &n, &words) != 0) {
    fprintf(stderr, "sessile: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = run(n, words);
  /* A validation message is a bug of ours that lavapipe may forgive and a
   * GPU not: the command fails (its outputs stay), so that every test run
   * under the layer fails on one, not only those that read stderr. */
  unsigned long long v = cli_validation_messages();
  if (v) {
    fprintf(stderr, "sessile: error: the Vulkan validation layer printed %llu message%s (above): a bug in sessile\n",
            v, v == 1 ? "" : "s");
    if (rc == EXIT_OK) rc = EXIT_RUNTIME;
  }
  rc = cli_finish_stdout(rc);
  cli_split_free();
  return rc;
}
