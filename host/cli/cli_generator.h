/* The generic command of every registered generator (cli_generator.c) and
 * the registry fed by generators.def. */
#ifndef SESSILE_CLI_GENERATOR_H
#define SESSILE_CLI_GENERATOR_H
#include "cli.h"
#include "sessile/run/generator.h"

/* `sessile NAME ...` for generator g: argv[0] is the generator's last word. */
int cli_generator_main(const sessile_generator *g, int argc, char **argv, const cli_gpu_opts *global);

/* Every generator of generators.def, in its order; NULL-terminated. */
extern const sessile_generator *const cli_generators[];
/* The generator whose name is argv[0] (one word) or argv[0] argv[1] ("coral
 * venation"); *words set to 1 or 2.  NULL when none. */
const sessile_generator *cli_generator_find(int argc, char **argv, int *words);
#endif
