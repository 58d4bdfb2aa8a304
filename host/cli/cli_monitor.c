/* The CLI's monitor (cli_monitor.h). */
#include <stdio.h>
#include "cli_monitor.h"

void cli_monitor_line(void *user, sessile_monitor_kind kind, const char *line) {
  cli_monitor *m = user;
  if (kind == SESSILE_MONITOR_WARNING) {
    if (m->showing) fputs("\r\033[K", stderr);
    m->showing = 0;
    fprintf(stderr, "sessile %s: warning: %s\n", m->cmd, line);
    return;
  }
  if (m->quiet) return;
  if (m->tty) {
    fprintf(stderr, "\r\033[K%s", line);
    m->showing = 1;
  } else if (kind == SESSILE_MONITOR_ITERATION) {
    fprintf(stderr, "%s\n", line);
  }
}

void cli_monitor_end(cli_monitor *m) {
  if (m->showing) fputc('\n', stderr);
  m->showing = 0;
}
