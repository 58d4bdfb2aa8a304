/* The registry: generators.def expanded once.  The test tree builds this
 * file again with a generators.def of one more line (tests/run/testgen). */
#include <string.h>
#include "cli_generator.h"

#define SESSILE_GENERATOR(sym) extern const sessile_generator sym;
#include "generators.def"
#undef SESSILE_GENERATOR

#define SESSILE_GENERATOR(sym) &sym,
const sessile_generator *const cli_generators[] = {
#include "generators.def"
    NULL};
#undef SESSILE_GENERATOR

const sessile_generator *cli_generator_find(int argc, char **argv, int *words) {
  for (int k = 0; cli_generators[k]; k++) {
    const char *n = cli_generators[k]->name, *sp = strchr(n, ' ');
    if (!sp && argc >= 1 && !strcmp(argv[0], n)) return *words = 1, cli_generators[k];
    if (sp && argc >= 2 && !strncmp(argv[0], n, (size_t)(sp - n)) && !argv[0][sp - n] && !strcmp(argv[1], sp + 1))
      return *words = 2, cli_generators[k];
  }
  return NULL;
}
