/* sessile — progress reports (base layer).  Library code never prints: a
 * computation that can run past a few seconds says where it stands through
 * a callback, and the caller (the CLI's reporter) formats it as a terminal
 * status line, a log line, or JSON.  docs/run.md, "Progress". */
#ifndef SESSILE_PROGRESS_H
#define SESSILE_PROGRESS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_progress {
  const char *stage;  /* what runs now: "iteration", "frame", "fluid", "picture", "point" */
  int step, steps;    /* the count of the stage: iteration 3 of 50 (steps 0: none) */
  double fraction;    /* of the whole command's work done, in [0, 1] */
  double left_s;      /* the reporter's estimate of seconds left; < 0: none (the caller extrapolates) */
  int left_min;       /* 1: left_s leaves out expensive steps not measured yet (a lower bound) */
  int ended;          /* 1: step `step` of the stage has just ended; 0: a status within it */
  const char *detail; /* what the step made ("1234 vertices"), or NULL */
} sessile_progress;

/* Where reports go; user is the caller's.  The report is valid during the call only. */
typedef void (*sessile_progress_fn)(void *user, const sessile_progress *p);

/* A report of the stage `stage` with nothing estimated: for computations
 * that know only their count (pictures, sweep points). */
static inline void sessile_progress_count(sessile_progress_fn fn, void *user, const char *stage, int step, int steps,
                                          int ended) {
  if (!fn) return;
  double f = steps > 0 ? (double)step / steps : 0;
  sessile_progress p = {stage, step, steps, f < 1 ? f : 1, -1, 0, ended, 0};
  fn(user, &p);
}

#ifdef __cplusplus
}
#endif
#endif
