/* GNU long options on the existing parsers (cli.h, docs/design.md "Command
 * line"): `--name=value` is split into `--name` `value` once, in main, and
 * the value's word is remembered, so that a flag given a value is refused. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

static char **words;     /* the split command line */
static char **made;      /* the "--name" copies made, to free */
static const char **attached; /* the values right of '=' */
static int nmade;

int cli_split_options(int argc, char **argv, int *nargc, char ***nargv) {
  words = calloc((size_t)argc * 2 + 1, sizeof *words);
  made = calloc((size_t)argc + 1, sizeof *made);
  attached = calloc((size_t)argc + 1, sizeof *attached);
  if (!words || !made || !attached) return cli_split_free(), -1;
  int n = 0;
  for (int i = 0; i < argc; i++) {
    const char *eq = strncmp(argv[i], "--", 2) ? NULL : strchr(argv[i], '=');
    /* "--=x" has no name: left whole, an unknown option */
    if (i == 0 || !eq || eq == argv[i] + 2) {
      words[n++] = argv[i];
      continue;
    }
    char *name = strndup(argv[i], (size_t)(eq - argv[i]));
    if (!name) return cli_split_free(), -1;
    made[nmade] = name;
    attached[nmade++] = eq + 1;
    words[n++] = name;
    words[n++] = (char *)(eq + 1);
  }
  words[n] = NULL;
  *nargc = n, *nargv = words;
  return 0;
}

void cli_split_free(void) {
  for (int k = 0; made && k < nmade; k++) free(made[k]);
  free(words), free(made), free(attached);
  words = made = NULL, attached = NULL, nmade = 0;
}

int cli_attached(const char *word) {
  for (int k = 0; word && k < nmade; k++)
    if (attached[k] == word) return 1;
  return 0;
}

int cli_stray_value(const char *cmd, char **argv, int i) {
  if (i < 1 || !cli_attached(argv[i])) return 0;
  char buf[CLI_SHORT_BUF];
  return cli_usage_error(cmd, "%s takes no value ('%s=%s')", argv[i - 1], argv[i - 1], cli_short(argv[i], buf));
}

int cli_version_option(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--version") || cli_attached(argv[i])) continue;
    if (i + 1 < argc && cli_attached(argv[i + 1])) return cli_stray_value(NULL, argv, i + 1);
    return cli_print_version();
  }
  return -1;
}
