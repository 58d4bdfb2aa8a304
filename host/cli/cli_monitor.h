/* Where a generator's monitor lines go: progress to stderr (rewritten in
 * place on a terminal, one line per iteration in a log), warnings always. */
#ifndef SESSILE_CLI_MONITOR_H
#define SESSILE_CLI_MONITOR_H
#include "sessile/run/generator.h"

typedef struct cli_monitor {
  const char *cmd; /* "grow" */
  int quiet;       /* progress off (warnings stay) */
  int tty;         /* stderr is a terminal */
  int showing;     /* a status line is on screen */
} cli_monitor;

void cli_monitor_line(void *user, sessile_monitor_kind kind, const char *line);
/* Ends a status line left on screen. */
void cli_monitor_end(cli_monitor *m);
#endif
