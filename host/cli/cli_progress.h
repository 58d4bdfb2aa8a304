/* The CLI's one progress reporter (docs/run.md "Progress"): the library's
 * reports (sessile/progress.h) become a status line rewritten in place on a
 * terminal, a line at each tenth of a stage in a log, JSON lines, or
 * nothing; warnings go to stderr whatever the mode. */
#ifndef SESSILE_CLI_PROGRESS_H
#define SESSILE_CLI_PROGRESS_H
#include "sessile/progress.h"
#include "sessile/run/generator.h"

/* --progress MODE; 0: not given (--quiet then means none). */
enum { CLI_PROGRESS_AUTO = 1, CLI_PROGRESS_TTY, CLI_PROGRESS_LINES, CLI_PROGRESS_JSON, CLI_PROGRESS_NONE };

typedef struct cli_progress {
  const char *cmd;   /* "grow", "sds run" */
  int mode;          /* TTY, LINES, JSON or NONE */
  double t0;         /* the command's start (wall clock) */
  double drawn;      /* when a status within a stage was last shown */
  double f0;         /* the fraction of the first report (a resume starts part way) */
  int reports;       /* reports heard */
  int showing;       /* a status line is on the terminal */
  char stage[32];    /* LINES: the stage of the last line */
  int tenth;         /* LINES: the tenth of the work of the last line */
} cli_progress;

/* The option --progress MODE at argv[*i] (auto, tty, lines, json, none):
 * 1 consumed (*mode set), 0 not it, -1 after a usage error. */
int cli_progress_option(const char *cmd, int argc, char **argv, int *i, int *mode);
/* mode: --progress's (0: not given); quiet: --quiet, which means none
 * unless --progress is given.  auto: tty when stderr is a terminal, else lines. */
void cli_progress_start(cli_progress *p, const char *cmd, int mode, int quiet);
/* A sessile_progress_fn; user is the cli_progress. */
void cli_progress_report(void *user, const sessile_progress *e);
/* A sessile_gen_say_fn for a generator's lines: warnings always, the
 * status line cleared first; other lines as status on a terminal only. */
void cli_progress_say(void *user, sessile_monitor_kind kind, const char *line);
/* Ends a status line left on the terminal. */
void cli_progress_end(cli_progress *p);
/* The lines of --help for --progress (each ends in a newline). */
extern const char cli_progress_help[];
#endif
