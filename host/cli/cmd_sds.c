/* `sessile sds run MODEL` (the generator sessile_gen_sds on the generic
 * command, cli_generator.c) and `sessile sds models` (docs/sds.md). */
#include <stdio.h>
#include <string.h>
#include "cli_generator.h"
#include "cli_run.h"
#include "sessile/sds/sds_builtin.h"
#include "sessile/sds/sds_run.h"

static int list_models(void) {
  for (const embedded_text *b = sds_builtins; b->name; b++) {
    /* the first comment line says what it is */
    const char *t = b->text, *e = strchr(t, '\n');
    int n = e ? (int)(e - t) : (int)strlen(t);
    printf("%-14s %.*s\n", b->name, n > 2 ? n - 2 : 0, t + (n > 2 ? 2 : 0));
  }
  return EXIT_OK;
}

int cmd_sds(int argc, char **argv, const cli_gpu_opts *global) {
  if (argc < 2) return cli_usage_error("sds", "name a subcommand: run or models");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(sessile_gen_sds.help, stdout);
    return EXIT_OK;
  }
  if (!strcmp(argv[1], "models")) {
    if (argc > 2 && (!strcmp(argv[2], "--help") || !strcmp(argv[2], "-h"))) {
      fputs("usage: sessile sds models\n\nLists the built-in SDS models, one a line: its name for "
            "'sessile sds run MODEL'\nand what it grows (docs/sds.md).\n", stdout);
      return EXIT_OK;
    }
    if (argc > 2) return cli_usage_error("sds models", "takes no arguments");
    return list_models();
  }
  if (strcmp(argv[1], "run")) return cli_usage_error("sds", "unknown subcommand '%.60s' (run, models)", argv[1]);
  return cli_generator_main(&sessile_gen_sds, argc - 1, argv + 1, global);
}
