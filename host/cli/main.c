/* sessile: grows 3-D models of marine sessile organisms from physics.
 * The entry point dispatches to one file per subcommand. */
#include <stdio.h>
#include <string.h>
#include "cli.h"

#ifndef SESSILE_VERSION
#define SESSILE_VERSION "dev"
#endif

static const char *help =
    "usage: sessile [--device INDEX|NAME] [--precision 32|64] [--validation] COMMAND [OPTIONS]\n"
    "\n"
    "Grows 3-D models of marine sponges and corals from physics on any Vulkan device\n"
    "(GPU, or the CPU through Mesa lavapipe).\n"
    "\n"
    "commands:\n"
    "  grow        grow a sponge (O'Hagan et al.'s accretive model); 'sessile grow --help'\n"
    "  devices     list the Vulkan devices and the one sessile uses\n"
    "  bench la    time the GPU linear algebra against the plain-C reference\n"
    "  bench grow  time each stage of the growth loop\n"
    "  bench fluid time the Navier-Stokes solve (Newton steps, linear iterations)\n"
    "  help        this text; 'sessile COMMAND --help' explains a command\n"
    "  version     print the version\n"
    "\n"
    "options (before or after the command):\n"
    "  --device D      device index or name substring (default: discrete > integrated > CPU;\n"
    "                  environment SESSILE_DEVICE)\n"
    "  --precision P   Krylov precision 64 or 32 (default 64 where the device has fp64;\n"
    "                  32 uses mixed-precision iterative refinement; env SESSILE_PRECISION)\n"
    "  --validation    enable the Khronos validation layer (env SESSILE_VALIDATION=1)\n"
    "\n"
    "exit codes: 0 success, 1 runtime failure, 2 bad usage or input.\n"
    "sessile is free software under the GNU AGPL-3.0-or-later.\n";

int main(int argc, char **argv) {
  cli_gpu_opts g = {0};
  int i = 1;
  for (; i < argc && argv[i][0] == '-'; i++) {
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (strcmp(argv[i], "--version") == 0) {
      printf("sessile %s\n", SESSILE_VERSION);
      return EXIT_OK;
    }
    int r = cli_gpu_option(NULL, argc, argv, &i, &g);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(NULL, "unknown option '%s'", argv[i]);
  }
  if (i >= argc) return cli_usage_error(NULL, "no command given");
  const char *cmd = argv[i];
  int sub_argc = argc - i;
  char **sub_argv = argv + i;
  if (strcmp(cmd, "help") == 0) {
    fputs(help, stdout);
    return EXIT_OK;
  }
  if (strcmp(cmd, "version") == 0) {
    printf("sessile %s\n", SESSILE_VERSION);
    return EXIT_OK;
  }
  if (strcmp(cmd, "devices") == 0) return cmd_devices(sub_argc, sub_argv, &g);
  if (strcmp(cmd, "bench") == 0) return cmd_bench(sub_argc, sub_argv, &g);
  if (strcmp(cmd, "grow") == 0) return cmd_grow(sub_argc, sub_argv, &g);
  return cli_usage_error(NULL, "unknown command '%s' (commands: grow, devices, bench, help, version)", cmd);
}
