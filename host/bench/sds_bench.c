/* `sessile bench sds`: (1) time per force + integrate step against cells
 * (icosphere imports, levels 2-5, and the Figure 9 body over its rock), GPU
 * against the C reference, the loop's host-driven step against the same
 * steps in device batches (sessile_sds_gpu_batch), with the share of the
 * contact stages (surface
 * hash build and queries, obstacle queries); (2) the Figure 9 model (rock)
 * run through the loop (sessile_sds_run) into a temporary run directory,
 * against the paper's 5.7 minutes.  Figures, never pass/fail. */
#define _XOPEN_SOURCE 700
#include <ftw.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "sessile/sds/sds_builtin.h"
#include "sessile/sds/sds.h"
#include "sessile/sds/sds_batch.h"
#include "sessile/bench/bench.h"
#include "sessile/sds/sds_run.h"

#define REPS 5 /* medians over this many repeats */

/* The process's CPU time: lavapipe's threads are the process's, so on a
 * shared machine the work of two variants compares where the wall does not. */
static double cpu_seconds(void) {
  struct timespec t;
  return clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) ? 0 : (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double median(double *v, int n) {
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
      double t = v[j];
      v[j] = v[j - 1], v[j - 1] = t;
    }
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct bench_size {
  int level; /* icosphere level */
  int rock;  /* 1: the rock model's body (radius 1) with its rock (radius 2.4, below) */
  int host_steps, gpu_steps;
} bench_size;

/* `steps` accepted steps through device batches (sessile_sds_gpu_batch),
 * from the asked step *dt (then the next one); the batches they took.  The
 * dispatches recorded after a batch's event still cost their launch (about
 * 0.1 ms each on lavapipe), so a batch asks about as many steps as the
 * batches before ran: twice the last when it ran them all, one more than
 * the steps an event let it run when one stopped it. */
static sessile_status device_steps(sessile_sds_gpu *s, uint32_t steps, double *dt, uint32_t *batches) {
  sessile_sds_batch b = {.t_stop = INFINITY, .dt = *dt};
  uint32_t ask = 16;
  for (uint32_t n = 0; n < steps; n += b.done, ++*batches) {
    b.steps = steps - n < ask ? steps - n : ask;
    SESSILE_CALL(sessile_sds_gpu_batch(s, &b));
    ask = b.events ? b.done + 1 : 2 * b.steps;
    if (ask > SESSILE_SDS_BATCH_MAX) ask = SESSILE_SDS_BATCH_MAX;
  }
  *dt = b.dt;
  return SESSILE_OK;
}

static sessile_status bench_one(sessile_gpu *g, const bench_size *b, FILE *out) {
  const double ctr[3] = {0, 0, 0}, rc[3] = {0, 0, -3.45}; /* as host/sds/models/rock.sds */
  sessile_sds o = {0};
  sessile_surface rock = {0};
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_sds_from_icosphere(b->level, 1.0, ctr, 0, 0, 0, 1.0, &o));
  double t_import = sessile_wall_seconds() - t0;
  /* a small perturbation so that every force term is non-trivial */
  for (size_t k = 0; k < 3 * (size_t)o.ncells; k++) o.v[k] = 0.01 * (double)((k * 2654435761u) % 1000) / 1000.0;
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.gravity = 0.05; /* as the shipped models with a floor or a rock (the default 10 crushes the body) */
  p.box = 1;
  for (int i = 0; i < 3; i++) p.box_lo[i] = -2, p.box_hi[i] = 2;
  sessile_status st = SESSILE_OK;
  if (b->rock) {
    st = sessile_surface_icosphere(4, 2.4, rc, &rock); /* as host/sds/models/rock.sds */
    p.box = 0;
    p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
  }
  double dt = 0.5 * sessile_sds_stable_dt(&o, &p);
  if (st == SESSILE_OK && !(dt > 0)) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the stable step's bound");
  sessile_sds_gpu *s = NULL;
  if (st == SESSILE_OK) st = sessile_sds_gpu_create(g, &o, &p, &s);
  double tg[REPS], tl[REPS], td[REPS], tb[REPS], th[REPS], fa[REPS], fn[REPS], fl[REPS], cr[REPS];
  uint32_t nbatch = 0;
  if (st == SESSILE_OK) st = sessile_sds_gpu_step(s, dt, NULL); /* warm-up */
  int per = b->gpu_steps / REPS > 0 ? b->gpu_steps / REPS : 1;
  for (int r = 0; r < REPS && st == SESSILE_OK; r++) {
    t0 = sessile_wall_seconds();
    for (int k = 0; k < per && st == SESSILE_OK; k++) st = sessile_sds_gpu_step(s, dt, NULL);
    tg[r] = (sessile_wall_seconds() - t0) / per;
    t0 = sessile_wall_seconds(); /* the loop's step: the stable bound in the submission, the step read back */
    double h = dt, c0 = cpu_seconds(); /* the step control's chain, as the loop's */
    for (int k = 0; k < per && st == SESSILE_OK; k++) st = sessile_sds_gpu_advance(s, 1, &h, NULL);
    tl[r] = (sessile_wall_seconds() - t0) / per;
    double cl = cpu_seconds() - c0;
    t0 = sessile_wall_seconds(), c0 = cpu_seconds(); /* the same steps with the control on the device, in batches */
    h = dt;
    if (st == SESSILE_OK) st = device_steps(s, (uint32_t)per, &h, &nbatch);
    td[r] = (sessile_wall_seconds() - t0) / per;
    double cd = cpu_seconds() - c0;
    cr[r] = cd > 0 ? cl / cd : 0;
    t0 = sessile_wall_seconds();
    if (st == SESSILE_OK) st = sessile_sds_gpu_steps(s, (uint32_t)per, dt);
    tb[r] = (sessile_wall_seconds() - t0) / per;
    if (st == SESSILE_OK) st = sessile_sds_gpu_time_contacts(s, per, &fa[r], &fn[r], &fl[r]);
  }
  int hper = b->host_steps / REPS > 0 ? b->host_steps / REPS : 1;
  for (int r = 0; r < REPS && st == SESSILE_OK; r++) {
    t0 = sessile_wall_seconds();
    for (int k = 0; k < hper; k++) sessile_sds_step_ref(&o, &p, dt);
    th[r] = (sessile_wall_seconds() - t0) / hper;
  }
  if (st == SESSILE_OK) {
    double mh = median(th, REPS), mg = median(tg, REPS), mb = median(tb, REPS), ma = median(fa, REPS),
           mn = median(fn, REPS), ml = median(fl, REPS), mlp = median(tl, REPS), md = median(td, REPS);
    fprintf(out, "%8u %9u %7u %5s %9.2f %10.3f %10.3f %10.3f %10.3f %8.2f %8.2f %8.2f %8.2f %7.1f %10.3f %8.2f %9.3f %8.0f%% %8.3f\n",
            o.ncells, o.ntets, o.nfaces, b->rock ? "yes" : "no", t_import, 1e3 * mh, 1e3 * mg, 1e3 * mlp, 1e3 * md,
            1e6 * mlp / o.ncells, 1e6 * md / o.ncells, mlp / md, median(cr, REPS), (double)REPS * per / nbatch, 1e3 * mb, mh / mb, ma,
            ma > 0 ? 100 * fmax(0, ma - mn) / ma : 0, ml);
    fflush(out);
  }
  sessile_sds_gpu_destroy(s);
  sessile_sds_free(&o);
  sessile_surface_free(&rock);
  return st;
}

sessile_status sessile_sds_bench_physics(sessile_gpu *g, FILE *out) {
  static const bench_size sizes[] = {
      {2, 0, 200, 400}, {2, 1, 200, 400}, {3, 0, 100, 200}, {3, 1, 100, 200}, {4, 0, 20, 60}, {5, 0, 5, 20}};
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  fprintf(out,
          "sds physics: force + integrate step (edge, tet, gather kernels; contact lists rebuilt when stale), "
          "device %s, fp%d; "
          "medians of %d repeats\n",
          i->name, i->precision, REPS);
  fprintf(out, "%8s %9s %7s %5s %9s %10s %10s %10s %10s %8s %8s %8s %8s %7s %10s %8s %9s %9s %8s\n", "cells", "tets",
          "faces", "rock", "import_s", "C_ms/step", "GPU_ms", "GPU_loop", "GPU_dev", "loop_us", "dev_us", "loop/dev",
          "cpu_l/d", "st/bat", "GPU_batch", "C/batch", "force_ms", "contacts", "list_ms");
  for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) SESSILE_CALL(bench_one(g, &sizes[k], out));
  fprintf(out,
          "(C: the host reference step, one thread; GPU_ms: one submission per step with the move check; "
          "GPU_loop: the loop's step, sessile_sds_gpu_advance: the same with the stable bound computed in the "
          "submission and the step read back (a step max_move undid counts); GPU_dev: the same steps with the step "
          "control on the device, batches of up to %d steps in one submission each (sessile_sds_gpu_batch), "
          "stopping at an undone step, an inverted tet or stale contact lists; loop_us, dev_us: microseconds "
          "per cell-step of the two, loop/dev their ratio (wall) and cpu_l/d that of the process's CPU time, "
          "which a shared machine disturbs less; st/bat: steps per batch; "
          "GPU_batch: all steps in one submission, the contact lists built before each; force_ms: one force "
          "evaluation in its own submission; contacts: its share spent on the contact lists' triangles; list_ms: "
          "one build of the contact lists, surface hash included, in its own submission)\n",
          SESSILE_SDS_BATCH_MAX);
  return SESSILE_OK;
}

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)sb, (void)flag, (void)ftw;
  return remove(path);
}

#define PAPER_S (5.7 * 60) /* Porter & McCormack: the rock model of Figure 9, dual-core 2 GHz PC */
#define ROCK_T_END 400.0   /* the model's t_end (host/sds/models/rock.sds) */

/* The cell-steps of a run: its step log's cells summed over the steps. */
static double cell_steps_of(const char *dir) {
  char path[600];
  snprintf(path, sizeof path, "%s/sds/steps.csv", dir);
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  double sum = 0;
  char line[256];
  unsigned long long step;
  double t, dt;
  unsigned cells;
  while (fgets(line, sizeof line, f))
    if (sscanf(line, "%llu,%lf,%lf,%u,", &step, &t, &dt, &cells) == 4) sum += cells;
  fclose(f);
  return sum;
}

/* One run of the rock model to t_end through the loop (device_loop: the
 * loop on the device), frames on, in a temporary run directory; mass_dt > 0
 * sets mass_scaling_dt (docs/sds.md, "Mass scaling"). */
static sessile_status rock_run(sessile_gpu *g, const embedded_text *m, double t_end, int device_loop, double mass_dt,
                               const char *scratch, const volatile sig_atomic_t *stop, FILE *out, double *wall_out,
                               sessile_sds_run_stats *rs) {
  char dir[512];
  snprintf(dir, sizeof dir, "%s/sessile-bench-sds-XXXXXX", scratch);
  SESSILE_CHECK(mkdtemp(dir), SESSILE_ERR_IO, "bench sds: cannot create a temporary run directory under %s",
                scratch);
  sessile_run_options ro = {.dir = dir, .generator = "bench-sds", .version = "bench", .mode = SESSILE_RUN_NEW,
                            .stop = stop};
  sessile_run *run = NULL;
  sessile_status st = sessile_run_open(&ro, &run);
  memset(rs, 0, sizeof *rs);
  sessile_sds_run_params p;
  if (st == SESSILE_OK) st = sessile_sds_run_params_of_model(m->text, "rock", &p);
  p.device_loop = device_loop;
  if (mass_dt > 0) p.mass_scaling_dt = mass_dt;
  char what[160];
  snprintf(what, sizeof what, "%s%s", device_loop ? "the loop on the device (device_loop)" : "the host-driven loop",
           mass_dt > 0 ? " with mass scaling" : "");
  if (mass_dt > 0) snprintf(what + strlen(what), sizeof what - strlen(what), " (mass_scaling_dt %g)", mass_dt);
  double load0[3], load1[3];
  sessile_load_average(load0);
  uint64_t q0 = sessile_gpu_submissions(g);
  double t0 = sessile_wall_seconds();
  if (st == SESSILE_OK) {
    sessile_sds_run_options o = {.run = run, .gpu = g, .seed = 1, .model_text = m->text, .model_name = "rock",
                                 .params = &p, .t_end = t_end, .frames = -1, .max_cells = 200000};
    st = sessile_sds_run(&o, rs);
    st = sessile_run_close(run, st);
  } else if (run)
    st = sessile_run_close(run, st);
  double wall = sessile_wall_seconds() - t0;
  uint64_t nq = sessile_gpu_submissions(g) - q0; /* each waits: about 0.1 ms on a discrete GPU */
  sessile_load_average(load1);
  double cell_steps = st == SESSILE_OK ? cell_steps_of(dir) : 0;
  nftw(dir, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
  SESSILE_CALL(st);
  fprintf(out,
          "sds rock (Figure 9), %s, frames on, to t = %g of %g: wall %.1f s (loop %.1f s), %u cells, "
          "%u tets, %llu steps (%.2f ms/step, %.1f us per cell-step), %llu divisions, %llu inversions, "
          "%llu submissions (%.2f a step)",
          what, rs->time, ROCK_T_END, wall,
          rs->wall_s, rs->cells, rs->tets, (unsigned long long)rs->steps,
          rs->steps ? 1e3 * rs->wall_s / (double)rs->steps : 0.0, cell_steps > 0 ? 1e6 * rs->wall_s / cell_steps : 0.0,
          (unsigned long long)rs->divisions, (unsigned long long)rs->inversions, (unsigned long long)nq,
          rs->steps ? (double)nq / (double)rs->steps : 0.0);
  if (device_loop)
    fprintf(out, ", %llu batches (%.1f steps a batch), %llu steps completed by the host",
            (unsigned long long)rs->batches, rs->batches ? (double)rs->steps / (double)rs->batches : 0.0,
            (unsigned long long)rs->host_steps);
  fprintf(out, "; load %.2f -> %.2f\n", load0[0], load1[0]);
  if (rs->time >= ROCK_T_END * (1 - 1e-9))
    fprintf(out, "  paper: %.0f s; ours %.1f s: %.2fx the paper's speed (target >= 5)\n", PAPER_S, wall,
            PAPER_S / wall);
  else {
    double ext = wall * ROCK_T_END / (rs->time > 0 ? rs->time : 1e-9);
    fprintf(out,
            "  EXTRAPOLATION (linear in simulated time from t = %g; growth and divisions later make steps "
            "dearer, so a lower bound): %.0f s to t = %g; paper %.0f s: %.3fx the paper's speed "
            "(target >= 5)\n",
            rs->time, ext, ROCK_T_END, PAPER_S, PAPER_S / ext);
  }
  fflush(out); /* a line a run, as it ends: the whole bench takes minutes */
  *wall_out = wall;
  return SESSILE_OK;
}

#define ROCK_RUNS 3 /* the host-driven loop, the loop on the device, the host-driven loop with mass scaling */

/* Each variant's median and minimum wall over the repeats, its paper's speed
 * at both, and the median of the ratios measured in the same repeat: the
 * machine is shared, so one run's wall is one draw of its noise. */
static void rock_summary(double wall[][ROCK_RUNS], unsigned reps, int nvar, const double *t_reached, FILE *out) {
  static const char *name[ROCK_RUNS] = {"the host-driven loop", "the loop on the device",
                                        "the host-driven loop with mass scaling"};
  double v[SESSILE_SDS_BENCH_REPEAT_MAX];
  fprintf(out, "over %u repeats (the loops alternating):\n", reps);
  for (int k = 0; k < nvar; k++) {
    /* short of the model's t_end the paper's speed is rock_run's linear extrapolation's */
    int whole = t_reached[k] >= ROCK_T_END * (1 - 1e-9);
    double scale = whole ? 1 : ROCK_T_END / (t_reached[k] > 0 ? t_reached[k] : 1e-9);
    for (unsigned r = 0; r < reps; r++) v[r] = wall[r][k];
    double med = median(v, (int)reps), lo = v[0]; /* median() sorts v */
    fprintf(out, "  %s, to t = %g: median %.1f s (%.2fx the paper's speed%s), minimum %.1f s (%.2fx), maximum %.1f s\n",
            name[k], t_reached[k], med, PAPER_S / (scale * med), whole ? "" : ", EXTRAPOLATED to t = 400", lo,
            PAPER_S / (scale * lo), v[reps - 1]);
  }
  for (unsigned r = 0; r < reps; r++) v[r] = wall[r][0] / wall[r][1];
  fprintf(out, "  the loop on the device against the host-driven loop: median ratio %.2fx\n", median(v, (int)reps));
}

sessile_status sessile_sds_bench_rock(sessile_gpu *g, double t_end, double mass_dt, unsigned repeats,
                                      const char *scratch, const volatile sig_atomic_t *stop, FILE *out) {
  const embedded_text *m = embedded_text_find(sds_builtins, "rock");
  SESSILE_CHECK(m, SESSILE_ERR_INTERNAL, "bench sds: the rock model is not embedded");
  SESSILE_CHECK(repeats >= 1 && repeats <= SESSILE_SDS_BENCH_REPEAT_MAX, SESSILE_ERR_USAGE,
                "bench sds: repeats must be 1..%d (got %u)", SESSILE_SDS_BENCH_REPEAT_MAX, repeats);
  double wall[SESSILE_SDS_BENCH_REPEAT_MAX][ROCK_RUNS];
  sessile_sds_run_stats rs[ROCK_RUNS] = {0}, first[ROCK_RUNS]; /* rs[2] unused without mass scaling */
  int nvar = mass_dt > 0 ? 3 : 2, same = 1;
  for (unsigned rep = 0; rep < repeats; rep++) {
    if (repeats > 1) fprintf(out, "repeat %u of %u\n", rep + 1, repeats);
    for (int dev = 0; dev < 2; dev++)
      SESSILE_CALL(rock_run(g, m, t_end, dev, 0, scratch, stop, out, &wall[rep][dev], &rs[dev]));
    fprintf(out,
            "the loop on the device against the host-driven loop, the same run (%s): %.2fx (wall %.1f s against "
            "%.1f s)\n",
            rs[0].steps == rs[1].steps && rs[0].cells == rs[1].cells ? "the same steps and cells" : "THE STEPS DIFFER",
            wall[rep][0] / wall[rep][1], wall[rep][1], wall[rep][0]);
    if (mass_dt > 0) { /* a third run: another trajectory (its statistics: docs/sds.md, "Mass scaling") */
      SESSILE_CALL(rock_run(g, m, t_end, 0, mass_dt, scratch, stop, out, &wall[rep][2], &rs[2]));
      fprintf(out,
              "the host-driven loop with mass scaling against without, the same run: %.2fx (wall %.1f s against "
              "%.1f s; %llu steps against %llu, %u cells against %u: another trajectory)\n",
              wall[rep][0] / wall[rep][2], wall[rep][2], wall[rep][0], (unsigned long long)rs[2].steps,
              (unsigned long long)rs[0].steps, rs[2].cells, rs[0].cells);
    }
    if (rep == 0) memcpy(first, rs, sizeof rs);
    for (int k = 0; k < nvar; k++) same &= rs[k].steps == first[k].steps && rs[k].cells == first[k].cells;
  }
  if (repeats > 1) {
    double t_reached[ROCK_RUNS];
    for (int k = 0; k < nvar; k++) t_reached[k] = first[k].time;
    rock_summary(wall, repeats, nvar, t_reached, out);
    /* the runs are deterministic: a repeat that took other steps is a bug, not noise */
    fprintf(out, "  %s\n", same ? "every repeat took the same steps to the same cells"
                                : "THE REPEATS' STEPS OR CELLS DIFFER");
  }
  return SESSILE_OK;
}
