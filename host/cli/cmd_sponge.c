/* `sessile sponge`: the sponge generators' group.  `sponge particles`
 * itself runs through the generic command (cli_generator.c). */
#include <stdio.h>
#include <string.h>
#include "cli.h"

int cmd_sponge(int argc, char **argv, const cli_gpu_opts *global) {
  static const char *top =
      "usage: sessile sponge particles [OPTIONS]   ('sessile sponge particles --help')\n"
      "\n"
      "Sponges after Liapis et al., Coralize (docs/sponge_particles.md):\n"
      "  particles  a hemisphere in a cube fed by falling nutrient particles (Section 3.3)\n";
  if (argc < 2) return cli_usage_error("sponge", "name a generator: particles");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(top, stdout);
    return EXIT_OK;
  }
  return cli_usage_error("sponge", "unknown generator '%.60s' (available: particles)", argv[1]);
}
