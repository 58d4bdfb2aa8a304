/* sds/steps.csv, one row per physics step (sds_sim.h): the paper's Figure
 * 12 per step (step, time, dt, cells, tets, wall ms, divisions, inversions). */
#include <stdio.h>
#include <stdlib.h>
#include "sds/sds_sim.h"

#define STEPLOG "sds/steps.csv"
#define STEPLOG_FLUSH ((size_t)1 << 20) /* bytes of rows kept between appends at most */
static const char STEPLOG_HEADER[] = "step,time,dt,cells,tets,ms,divisions,inversions\n";

sessile_status sds_steplog_start(sessile_run *run) {
  return sessile_run_log(run, STEPLOG, STEPLOG_HEADER, sizeof STEPLOG_HEADER - 1);
}

/* One row: the step just made, its wall time and its events. */
sessile_status sds_steplog_row(sds_sim *s, sessile_run *run, double dt, double ms, uint64_t divisions,
                               uint64_t inversions) {
  if (s->steplog_cap - s->steplog_len < 160) {
    size_t cap = s->steplog_cap ? 2 * s->steplog_cap : 1u << 16;
    char *b = realloc(s->steplog, cap);
    SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the step log");
    s->steplog = b, s->steplog_cap = cap;
  }
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
  if (!s->steplog_len) return SESSILE_OK;
  sessile_status st = sessile_run_log(run, STEPLOG, s->steplog, s->steplog_len);
  s->steplog_len = 0;
  return st;
}
