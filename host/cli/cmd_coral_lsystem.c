/* PLACEHOLDER until the generator lands (replaced by its owner). */
#include "cli.h"
int cmd_coral_lsystem(int argc, char **argv, const cli_gpu_opts *global) {
  (void)argc, (void)global;
  return cli_usage_error(argv[0], "not built yet");
}
