/* The CLI's progress reporter (cli_progress.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"
#include "cli_progress.h"

const char cli_progress_help[] =
    "  --progress M    progress on stderr: auto (a status line on a terminal, else a line\n"
    "                  at each tenth of a stage), tty, lines, json (one JSON object a line:\n"
    "                  stage, step, steps, percent, elapsed_s, left_s; docs/run.md) or none\n"
    "                  (default auto; none with --quiet)\n";

static const char *const modes[] = {"auto", "tty", "lines", "json", "none"};

int cli_progress_option(const char *cmd, int argc, char **argv, int *i, int *mode) {
  if (strcmp(argv[*i], "--progress")) return 0;
  const char *v = cli_value(cmd, argc, argv, i);
  if (!v || cli_once(cmd, "--progress", "--progress")) return -1;
  for (int k = 0; k < 5; k++)
    if (!strcmp(v, modes[k])) return *mode = CLI_PROGRESS_AUTO + k, 1;
  cli_usage_error(cmd, "--progress: '%.40s' is not auto, tty, lines, json or none", v);
  return -1;
}

void cli_progress_start(cli_progress *p, const char *cmd, int mode, int quiet) {
  memset(p, 0, sizeof *p);
  p->cmd = cmd, p->t0 = sessile_wall_seconds(), p->tenth = -1;
  if (!mode) mode = quiet ? CLI_PROGRESS_NONE : CLI_PROGRESS_AUTO;
  if (mode == CLI_PROGRESS_AUTO) mode = isatty(STDERR_FILENO) ? CLI_PROGRESS_TTY : CLI_PROGRESS_LINES;
  p->mode = mode;
}

/* "4.2 s", "42 s", "3m05s", "2h07m": a duration at the precision a person reads. */
static const char *duration(double s, char *buf, size_t n) {
  long t = lround(s < 0 ? 0 : s);
  if (s < 9.95) snprintf(buf, n, "%.1f s", s < 0 ? 0 : s);
  else if (t < 60) snprintf(buf, n, "%ld s", t);
  else if (t < 3600) snprintf(buf, n, "%ldm%02lds", t / 60, t % 60);
  else snprintf(buf, n, "%ldh%02ldm", t / 3600, t / 60 % 60);
  return buf;
}

/* The report's estimate of seconds left, else the fraction's extrapolation
 * over this process's time (< 0: unknown yet). */
static double left_of(const cli_progress *p, const sessile_progress *e, double el) {
  if (e->left_s >= 0) return e->left_s;
  double f = e->fraction - p->f0;
  return f > 0 ? el * (1 - e->fraction) / f : -1;
}

/* "grow  34% [17/50] fluid, 1m02s elapsed, ~2m10s left". */
static void format(const cli_progress *p, const sessile_progress *e, double el, double left, char *out, size_t n) {
  char a[32], b[32], count[48] = "";
  if (e->steps > 0) snprintf(count, sizeof count, "[%d/%d] ", e->step, e->steps);
  int k = snprintf(out, n, "%s %3.0f%% %s%s%s, %s elapsed", p->cmd, 100 * e->fraction, count, e->stage,
                   e->ended && e->steps > 0 ? " done" : "", duration(el, a, sizeof a));
  if (left >= 0 && k > 0 && (size_t)k < n)
    k += snprintf(out + k, n - (size_t)k, ", %s%s left", e->left_min ? ">" : "~", duration(left, b, sizeof b));
  if (e->detail && k > 0 && (size_t)k < n) snprintf(out + k, n - (size_t)k, " (%s)", e->detail);
}

static void json(const cli_progress *p, const sessile_progress *e, double el, double left) {
  cJSON *o = cJSON_CreateObject();
  if (!o) return; /* out of host memory: this report goes unsaid */
  cJSON_AddStringToObject(o, "command", p->cmd);
  cJSON_AddStringToObject(o, "stage", e->stage);
  cJSON_AddNumberToObject(o, "step", e->step);
  cJSON_AddNumberToObject(o, "steps", e->steps);
  cJSON_AddNumberToObject(o, "percent", round(1000 * e->fraction) / 10);
  cJSON_AddNumberToObject(o, "elapsed_s", round(100 * el) / 100);
  if (left >= 0) cJSON_AddNumberToObject(o, "left_s", round(100 * left) / 100);
  else cJSON_AddNullToObject(o, "left_s");
  cJSON_AddBoolToObject(o, "left_min", e->left_min);
  cJSON_AddBoolToObject(o, "ended", e->ended);
  if (e->detail) cJSON_AddStringToObject(o, "detail", e->detail);
  char *t = cJSON_PrintUnformatted(o);
  if (t) fprintf(stderr, "%s\n", t);
  free(t);
  cJSON_Delete(o);
}

/* LINES: a stage's end without a count, a stage's last step, a new stage,
 * or a new tenth of the work; never a status within a step. */
static int log_line(cli_progress *p, const sessile_progress *e) {
  if (!e->ended) return 0;
  int tenth = (int)floor(10 * e->fraction + 1e-9);
  int line = e->steps <= 0 || e->step >= e->steps || strcmp(p->stage, e->stage) || tenth > p->tenth;
  if (line) snprintf(p->stage, sizeof p->stage, "%s", e->stage), p->tenth = tenth;
  return line;
}

void cli_progress_report(void *user, const sessile_progress *e) {
  cli_progress *p = user;
  if (p->mode == CLI_PROGRESS_NONE) return;
  double now = sessile_wall_seconds(), el = now - p->t0;
  if (!p->reports++) p->f0 = e->ended ? 0 : e->fraction;
  /* a status within a step: at most 10 a second on a terminal, 1 in JSON */
  double gap = p->mode == CLI_PROGRESS_JSON ? 1.0 : 0.1;
  if (!e->ended && (p->mode == CLI_PROGRESS_LINES || now - p->drawn < gap)) return;
  if (!e->ended) p->drawn = now;
  double left = left_of(p, e, el);
  if (p->mode == CLI_PROGRESS_JSON) {
    json(p, e, el, left);
    return;
  }
  if (p->mode == CLI_PROGRESS_LINES && !log_line(p, e)) return;
  char line[512];
  format(p, e, el, left, line, sizeof line);
  if (p->mode == CLI_PROGRESS_TTY) {
    fprintf(stderr, "\r\033[K%s", line);
    p->showing = 1;
  } else {
    fprintf(stderr, "%s: %s\n", p->cmd, line + strlen(p->cmd) + 1);
  }
}

void cli_progress_say(void *user, sessile_monitor_kind kind, const char *line) {
  cli_progress *p = user;
  if (kind == SESSILE_MONITOR_WARNING) {
    if (p->showing) fputs("\r\033[K", stderr);
    p->showing = 0;
    fprintf(stderr, "sessile %s: warning: %s\n", p->cmd, line);
  } else if (p->mode == CLI_PROGRESS_TTY) {
    fprintf(stderr, "\r\033[K%s", line);
    p->showing = 1;
  }
}

void cli_progress_end(cli_progress *p) {
  if (p->showing) fputc('\n', stderr);
  p->showing = 0;
}
