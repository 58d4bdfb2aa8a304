/* sds/steps.csv, one row per physics step (sds_sim.h): the paper's Figure
 * 12 per step (step, time, dt, cells, tets, wall ms, divisions, inversions);
 * sds/divisions.csv, one row per division.  Rows gather in memory and are
 * appended together before each checkpoint (which keeps each log's length:
 * a resume cuts what lies past it and makes those rows again). */
#include <stdio.h>
#include <stdlib.h>
#include "sds/sds_sim.h"

#define STEPLOG "sds/steps.csv"
#define STEPLOG_FLUSH ((size_t)1 << 20) /* bytes of rows kept between appends at most */
static const char STEPLOG_HEADER[] = "step,time,dt,cells,tets,ms,divisions,inversions\n";
#define DIVLOG "sds/divisions.csv"
static const char DIVLOG_HEADER[] = "time,cell,daughter,x,y,z,radius\n";

sessile_status sds_steplog_start(sessile_run *run) {
  SESSILE_CALL(sessile_run_log(run, STEPLOG, STEPLOG_HEADER, sizeof STEPLOG_HEADER - 1));
  return sessile_run_log(run, DIVLOG, DIVLOG_HEADER, sizeof DIVLOG_HEADER - 1);
}

/* Room for one more row of at most `row` bytes in *buf. */
static sessile_status room(char **buf, size_t len, size_t *cap, size_t row) {
  if (*cap - len >= row) return SESSILE_OK;
  size_t c = *cap ? 2 * *cap : 1u << 16;
  char *b = realloc(*buf, c);
  SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the step and division logs");
  *buf = b, *cap = c;
  return SESSILE_OK;
}

/* One division, at the end of the step that asked for it (s->time: the
 * same in the host's loop and after a batch on the device). */
sessile_status sds_divlog_row(sds_sim *s, uint32_t cell, uint32_t daughter, const double x[3], double r) {
  SESSILE_CALL(room(&s->divlog, s->divlog_len, &s->divlog_cap, 200));
  int k = snprintf(s->divlog + s->divlog_len, s->divlog_cap - s->divlog_len, "%.17g,%u,%u,%.17g,%.17g,%.17g,%.17g\n",
                   s->time, cell, daughter, x[0], x[1], x[2], r);
  SESSILE_CHECK(k > 0 && (size_t)k < s->divlog_cap - s->divlog_len, SESSILE_ERR_INTERNAL, "sds: division row too long");
  s->divlog_len += (size_t)k;
  return SESSILE_OK;
}

/* One row: the step just made, its wall time and its events. */
sessile_status sds_steplog_row(sds_sim *s, sessile_run *run, double dt, double ms, uint64_t divisions,
                               uint64_t inversions) {
  SESSILE_CALL(room(&s->steplog, s->steplog_len, &s->steplog_cap, 160));
  int k = snprintf(s->steplog + s->steplog_len, s->steplog_cap - s->steplog_len,
                   "%llu,%.17g,%.17g,%u,%u,%.4f,%llu,%llu\n", (unsigned long long)s->st->steps, s->time, dt,
                   s->o.ncells, s->o.ntets, ms, (unsigned long long)divisions, (unsigned long long)inversions);
  SESSILE_CHECK(k > 0 && (size_t)k < s->steplog_cap - s->steplog_len, SESSILE_ERR_INTERNAL, "sds: step log row too long");
  s->steplog_len += (size_t)k;
  return s->steplog_len >= STEPLOG_FLUSH ? sds_steplog_flush(s, run) : SESSILE_OK;
}

/* Appends the rows kept so far: before every checkpoint (the checkpoint keeps
 * the log's length), when a MiB has gathered between frames (a long frame
 * interval must not hold millions of rows; a resume cuts what lies past the
 * checkpoint), and at the end of the run, whatever its end. */
sessile_status sds_steplog_flush(sds_sim *s, sessile_run *run) {
  sessile_status st = SESSILE_OK;
  if (s->steplog_len) st = sessile_run_log(run, STEPLOG, s->steplog, s->steplog_len);
  if (st == SESSILE_OK && s->divlog_len) st = sessile_run_log(run, DIVLOG, s->divlog, s->divlog_len);
  s->steplog_len = s->divlog_len = 0;
  return st;
}
