/* The version and the commit the binary was built from (cli.h). */
#include <stdio.h>
#include "cli.h"
#include "sessile_commit.h" /* SESSILE_COMMIT: generated at build time (cmake/commit.cmake) */

#ifndef SESSILE_VERSION
#define SESSILE_VERSION "dev"
#endif

const char *cli_version(void) { return SESSILE_VERSION; }
const char *cli_commit(void) { return SESSILE_COMMIT; }

int cli_print_version(void) {
  printf("sessile %s (commit %s)\n", SESSILE_VERSION, SESSILE_COMMIT);
  return EXIT_OK;
}
