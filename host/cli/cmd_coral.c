/* `sessile coral lsystem|venation`: Coralize's coral generators (docs/coral.md). */
#include <stdio.h>
#include <string.h>
#include "cli.h"

static const char *help =
    "usage: sessile coral lsystem|venation [OPTIONS]   ('sessile coral NAME --help')\n"
    "\n"
    "Corals after Liapis et al., Coralize (docs/coral.md):\n"
    "  lsystem   stony corals from a stochastic parametric L-system grammar (Section 3.1)\n"
    "  venation  soft corals by open or closed venation in 3-D (Section 3.2)\n";

int cmd_coral(int argc, char **argv, const cli_gpu_opts *global) {
  if (argc < 2) return cli_usage_error("coral", "name a generator: lsystem or venation");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(help, stdout);
    return EXIT_OK;
  }
  if (!strcmp(argv[1], "lsystem")) return cmd_coral_lsystem(argc - 1, argv + 1, global);
  return cli_usage_error("coral", "unknown generator '%.60s' (available: lsystem, venation)", argv[1]);
}
