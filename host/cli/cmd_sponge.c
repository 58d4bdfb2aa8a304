/* PLACEHOLDER until the generator lands (replaced by its owner). */
#include "cli.h"
int cmd_sponge(int argc, char **argv, const cli_gpu_opts *global) {
  (void)argc, (void)global;
  return cli_usage_error(argv[0], "not built yet");
}
