/* The run loop's progress reports and its estimate of the time left
 * (sessile/run/generator.h; docs/run.md "Progress").  Iterations with a
 * snapshot can cost many times the others (grow's flow solve, the files),
 * so the two kinds are measured apart and the iterations left are counted
 * by kind from --every. */
#include <stdio.h>
#include "run_internal.h"

/* The snapshot iterations in (it, n]: the --every grid, and the last one. */
static int snapshots_after(const sessile_gen_setup *su, int it) {
  int n = su->iterations, every = su->every;
  if (it >= n) return 0;
  int k = every > 0 ? n / every - it / every : 0;
  return k + (every <= 0 || n % every ? 1 : 0);
}

/* The expected seconds of an iteration of kind k (1: with a snapshot): its
 * kind's mean in this process, else the other kind's (*min set: a snapshot's
 * cost is not known yet), else guess. */
static double mean_of(const sessile_gen_meter *m, int k, double guess, int *min) {
  if (m->n[k]) return m->sum[k] / m->n[k];
  if (k == 1) *min = 1;
  return m->n[1 - k] ? m->sum[1 - k] / m->n[1 - k] : guess;
}

/* Seconds left when part of iteration it is done, it_s seconds into it;
 * -1 when nothing is measured and part says nothing. */
static double left_at(const sessile_gen_setup *su, const sessile_gen_meter *m, int it, double part, double it_s,
                      int *min) {
  double guess = part > 0 ? it_s / part : -1; /* the running iteration, projected */
  if (!m->n[0] && !m->n[1] && guess < 0) return -1;
  int snaps = snapshots_after(su, it), plain = su->iterations - it - snaps;
  double rest = 0;
  if (part < 1) {
    rest = mean_of(m, sessile_gen_snapshot_kind(su, it) != 0, guess, min) - it_s;
    if (rest < 0) rest = 0; /* slower than its kind's mean: the rest is unknown, not negative */
  }
  return rest + plain * mean_of(m, 0, guess, min) + snaps * mean_of(m, 1, guess, min);
}

static void report(const sessile_gen_setup *su, const char *stage, double part, int ended) {
  const sessile_gen_meter *m = su->meter;
  int n = su->iterations > 0 ? su->iterations : 1;
  double it_s = sessile_wall_seconds() - m->t_it;
  sessile_progress p = {.stage = stage, .step = m->it, .steps = su->iterations,
                        .fraction = (m->it - 1 + part) / n, .ended = ended,
                        .detail = ended && m->detail[0] ? m->detail : NULL};
  p.left_s = left_at(su, m, m->it, part, it_s, &p.left_min);
  if (p.fraction > 1) p.fraction = 1;
  m->fn(m->user, &p);
}

void sessile_gen_progress(const sessile_gen_setup *su, const char *stage, double part, const char *detail) {
  sessile_gen_meter *m = su ? su->meter : NULL;
  if (!m || !m->fn) return;
  if (detail) snprintf(m->detail, sizeof m->detail, "%s", detail);
  if (stage) report(su, stage, part < 0 ? 0 : part > 1 ? 1 : part, 0);
}

void run_progress_begin(const sessile_gen_setup *su, int it) {
  sessile_gen_meter *m = su->meter;
  m->it = it, m->t_it = sessile_wall_seconds(), m->detail[0] = 0;
}

void run_progress_end(const sessile_gen_setup *su, int it) {
  sessile_gen_meter *m = su->meter;
  int k = sessile_gen_snapshot_kind(su, it) != 0;
  m->sum[k] += sessile_wall_seconds() - m->t_it, m->n[k]++;
  if (m->fn) report(su, m->unit, 1, 1);
}

void run_progress_finish(const sessile_gen_setup *su, int ended) {
  const sessile_gen_meter *m = su->meter;
  if (!m->fn) return;
  sessile_progress p = {.stage = "final outputs", .fraction = 1, .left_s = ended ? 0 : -1, .ended = ended};
  m->fn(m->user, &p);
}
