/* `sessile devices`: list the Vulkan devices and the one sessile would use. */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "cli_gpu_env.h"

static const char *help =
    "usage: sessile devices [--device INDEX|NAME]\n"
    "\n"
    "Lists every Vulkan device: type, driver, memory heaps, subgroup size, fp64\n"
    "support (shaderFloat64), maxStorageBufferRange and maxComputeWorkGroupInvocations.\n"
    "The device marked * is the one sessile uses: discrete > integrated > virtual >\n"
    "CPU, unless --device or SESSILE_DEVICE names another (index or name substring).\n"
    "No device listed: apt-get install mesa-vulkan-drivers (CPU driver lavapipe).\n";

int cmd_devices(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts o = *global;
  for (int i = 1; i < argc; i++) {
    if (cli_stray_value("devices", argv, i)) return EXIT_USAGE;
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option("devices", argc, argv, &i, &o);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error("devices", "unknown option '%s'", argv[i]);
  }
  sessile_status s = sessile_gpu_print_devices(stdout, cli_env_device(o.device));
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
