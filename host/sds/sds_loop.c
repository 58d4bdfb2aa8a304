/* The SDS loop (sessile/sds/sds_run.h, docs/sds.md "The loop").  One step:
 *   1. physics: one integrator step on the GPU (step control inside);
 *   2. inversions: tets with volume <= 0 after the step are found on the GPU;
 *      the first inversion time among them (linear motion over the step,
 *      §3.1.2) rewinds every cell to that time, the tet's case-1 or case-2
 *      transformation is applied (host, TetGen) and the step goes on;
 *   3. morphogens: explicit Euler on the GPU, sub-stepped below its bound;
 *   4. rules: evaluated on the host in cell order, then sets, growth (r, m)
 *      and divisions (host, TetGen) in cell order.
 * Same model, seed and device: the same bytes. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sessile/rng.h"
#include "sessile/sds/sds_batch.h"
#include "sds/sds_checkpoint.h"
#include "sds/sds_sim.h"

/* The loop's scalars to and from the checkpoint (sds_checkpoint.h). */
static void loop_scalars(const sds_sim *s, sds_ckpt_loop *out) {
  const sessile_sds_run_stats *t = s->st;
  sds_ckpt_loop l = {.version = SDS_CKPT_VERSION, .key = s->key, .time = s->time, .dt = s->dt,
                     .stalled = s->stalled, .rng = s->rng, .frame = s->frame,
                     .steps_frame = s->steps_frame, .div_interval = s->div_interval,
                     .inv_interval = s->inv_interval, .steps = t->steps, .divisions = t->divisions,
                     .inversions = t->inversions, .resisted = t->resisted, .slivers = t->slivers,
                     .deferred = t->deferred, .repairs = t->repairs, .c0 = {s->c0[0], s->c0[1], s->c0[2]}, .size0 = s->size0,
                     .retry_cap = s->retry_at ? s->retry_cap : 0, .nsliver = s->nsliver};
  *out = l;
}

static sessile_status restore(sds_sim *s, const sessile_ckpt *ck) {
  sds_ckpt_loop l;
  SESSILE_CALL(sds_ckpt_read(ck, s->key, (uint32_t)sessile_sds_model_nmorph(s->model),
                             (uint32_t)sessile_sds_model_nstate(s->model), &s->o, &l, &s->retry_at, &s->sliver));
  sessile_sds_run_stats *t = s->st;
  s->time = l.time, s->dt = l.dt, s->stalled = (int)l.stalled, s->rng = l.rng;
  s->frame = (int)l.frame, s->steps_frame = l.steps_frame;
  s->div_interval = l.div_interval, s->inv_interval = l.inv_interval;
  t->steps = l.steps, t->divisions = l.divisions, t->inversions = l.inversions, t->resisted = l.resisted;
  t->slivers = l.slivers, t->deferred = l.deferred, t->repairs = l.repairs, t->frames = s->frame;
  memcpy(s->c0, l.c0, sizeof s->c0);
  s->size0 = l.size0, s->retry_cap = (uint32_t)l.retry_cap;
  s->nsliver = s->sliver_cap = (uint32_t)l.nsliver;
  if (!s->retry_cap) free(s->retry_at), s->retry_at = NULL;
  SESSILE_CHECK(s->frame >= 1 && s->frame <= s->frames + 1 && isfinite(s->time) && s->dt > 0 && s->size0 > 0,
                SESSILE_ERR_IO, "the checkpoint's loop section does not fit this run (damaged?)");
  /* the times of the frames written so far (the series lists them) */
  SESSILE_CALL(sessile_ckpt_take(ck, "frame_times", s->frame_time, (size_t)s->frame * sizeof *s->frame_time));
  s->resumed = 1;
  return SESSILE_OK;
}

/* The model, its key and the parameters; then a new run's organism (a
 * resume's comes from the checkpoint: gen_restore). */
static sessile_status setup(sds_gen_state *g, const sessile_sds_run_params *params) {
  sds_sim *s = &g->s;
  const sds_gen_args *a = g->su->extra;
  const char *where = a->name ? a->name : "model";
  int level;
  double radius;
  s->text = a->text;
  SESSILE_CALL(sds_check_model(s, where, params, &level, &radius));
  SESSILE_CALL(sds_run_length(s->model, a->have_t_end ? a->t_end : -1, a->frames, &s->t_end, &s->frames));
  s->key = sds_ckpt_key(s->text, g->su->seed, s->t_end, s->frames, a->max_cells);
  /* values apart from the model's own (--set, --config) belong to the key */
  sessile_sds_run_params own;
  SESSILE_CALL(sessile_sds_run_params_of_model(s->text, where, &own));
  s->key = sds_ckpt_key_params(s->key, &own, &s->prm);
  int nm = sessile_sds_model_nmorph(s->model), ns = sessile_sds_model_nstate(s->model);
  s->frame_time = calloc((size_t)s->frames + 1, sizeof *s->frame_time);
  SESSILE_CHECK(s->frame_time, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  s->tip_state = sessile_sds_model_state_index(s->model, "tip");
  s->birth_state = sessile_sds_model_state_index(s->model, "birth_radius");
  if (sessile_run_checkpoint_loaded(g->su->run)) return SESSILE_OK;
  SESSILE_CALL(sds_import_organism(s, where, level, radius));
  s->o.edge_k_defer = s->prm.axial_stiffness != 1; /* the springs of the start are isotropic */
  for (uint32_t c = 0; c < s->o.ncells; c++) {
    for (int k = 0; k < nm; k++) s->o.phi[(size_t)c * nm + k] = sessile_sds_model_morph_start(s->model, k);
    for (int k = 0; k < ns; k++) s->o.state[(size_t)c * ns + k] = sessile_sds_model_state_start(s->model, k);
  }
  if (s->birth_state >= 0)
    for (uint32_t c = 0; c < s->o.ncells; c++) s->o.state[(size_t)c * ns + (uint32_t)s->birth_state] = s->o.r[c];
  SESSILE_CALL(sds_mark_tips(s, where));
  SESSILE_CALL(sds_neighbours(s));
  if (s->prm.tips_below && s->tip_state >= 0) SESSILE_CALL(sds_cells_below_tips(s));
  SESSILE_CALL(sds_axial_assign(s));
  sds_measure_start(s);
  s->dt = s->p.dt;
  return sds_gpu_create(g);
}

void sds_teardown(sds_sim *s) {
  sds_device_loop_destroy(s); /* detaches from pg first */
  sessile_sds_model_destroy(s->model);
  sessile_sds_gpu_destroy(s->pg);
  sessile_morph_gpu_destroy(s->mg);
  s->pg = NULL, s->mg = NULL;
  sessile_sds_free(&s->o);
  sessile_surface_free(&s->rock);
  free(s->nbr_off), free(s->nbr), free(s->xprev), free(s->retry_at), free(s->sliver), free(s->steplog), free(s->divlog);
  free(s->frame_time);
}

/* --- the loop --------------------------------------------------------------- */
/* A blow-up (docs/sds.md, "Blow-ups"): the step from t = s->time (step
 * steps + 1) left no usable state.  Nothing of the step is written; the
 * message says what happened, when, and what to try. */
sessile_status sds_blowup(sds_sim *s, const char *fmt, ...) {
  sessile_sds_run_stats *t = s->st;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->blowup_cause, sizeof t->blowup_cause, fmt, ap);
  va_end(ap);
  t->blowup = 1, t->blowup_time = s->step_t0, t->blowup_step = t->steps + 1;
  return sessile_error_set(SESSILE_ERR_NUMERIC,
                           "sds: blow-up in step %llu from t = %.9g: %s; the last good frame is frame_%04d; try "
                           "weaker forces (gravity, attractor), more damping, stiffer volume springs "
                           "(volume_stiffness) or slower growth",
                           (unsigned long long)t->blowup_step, s->step_t0, t->blowup_cause, s->frame - 1);
}

/* The state after the physics: every position and velocity finite, every
 * cell within 1e6 starting sizes of the starting centroid. */
sessile_status sds_check_motion(sds_sim *s) {
  const sessile_sds *o = &s->o;
  double far2 = 1e12 * s->size0 * s->size0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    const double *x = o->x + 3 * (size_t)c, *v = o->v + 3 * (size_t)c;
    if (!isfinite(x[0] + x[1] + x[2]) || !isfinite(v[0] + v[1] + v[2]))
      return sds_blowup(s, "cell %u's position or velocity is not finite", c);
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (x[k] - s->c0[k]) * (x[k] - s->c0[k]);
    if (d2 > far2)
      return sds_blowup(s, "cell %u is %.3g u from the start's centre, more than 1e6 times the starting size %.3g u", c,
                    sqrt(d2), s->size0);
  }
  return SESSILE_OK;
}

/* The state after the rules: radii positive and finite, morphogens and
 * state variables finite (a runaway growth or production). */
sessile_status sds_check_cells(sds_sim *s) {
  const sessile_sds *o = &s->o;
  for (uint32_t c = 0; c < o->ncells; c++) {
    if (!(o->r[c] > 0 && isfinite(o->r[c]) && isfinite(o->m[c])))
      return sds_blowup(s, "cell %u's radius %g or mass %g is not positive and finite (a runaway growth rule?)", c,
                    o->r[c], o->m[c]);
    for (uint32_t k = 0; k < o->nmorph; k++)
      if (!isfinite(o->phi[(size_t)c * o->nmorph + k]))
        return sds_blowup(s, "cell %u's morphogen %s is not finite", c, sessile_sds_model_morph_name(s->model, (int)k));
    for (uint32_t k = 0; k < o->nstate; k++)
      if (!isfinite(o->state[(size_t)c * o->nstate + k]))
        return sds_blowup(s, "cell %u's state %s is not finite", c, sessile_sds_model_state_name(s->model, (int)k));
  }
  return SESSILE_OK;
}

/* The physics' verdict a blow-up: a non-finite state or a step below dt_min. */
sessile_status sds_physics_failed(sds_sim *s, sessile_status st) {
  if (st != SESSILE_ERR_NUMERIC) return st;
  char why[512];
  const char *m = sessile_error_message();
  snprintf(why, sizeof why, "%s", strncmp(m, "sds: ", 5) ? m : m + 5);
  return sds_blowup(s, "%s", why);
}

/* What follows a step's physics of `elapsed` s from s->time (step_t0),
 * the state downloaded and xprev the positions before it: the motion
 * checked, the inversions (a rewind shortens the step), the rules. */
sessile_status sds_finish_step(sds_sim *s, double elapsed) {
  SESSILE_CALL(sds_check_motion(s));
  int handled = 0;
  double frac = 1;
  SESSILE_CALL(sds_inversions(s, &handled, &frac));
  if (handled) {
    /* rewound to the inversion: the elapsed time shrinks with it */
    elapsed *= frac;
    SESSILE_CALL(sds_refresh(s));
  }
  if (elapsed > 0) {
    s->time += elapsed;
    SESSILE_CALL(sds_rules(s, elapsed));
    SESSILE_CALL(sds_check_cells(s));
    s->stalled = 0;
  } else if (++s->stalled >= 1000)
    return sds_blowup(s, "time stands still: tets keep inverting at the start of the step for 1000 steps");
  s->st->steps++, s->steps_frame++;
  return SESSILE_OK;
}

/* One step (docs/sds.md, "The loop"): of the step the control proposed,
 * never cut to land on a frame or t_end, so that the outputs asked for do
 * not change the trajectory. */
static sessile_status step(sds_sim *s) {
  free(s->xprev);
  s->xprev = malloc((size_t)s->o.ncells * 3 * sizeof *s->xprev);
  SESSILE_CHECK(s->xprev, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  memcpy(s->xprev, s->o.x, (size_t)s->o.ncells * 3 * sizeof *s->xprev);
  double try_dt = s->dt, elapsed = 0;
  s->step_t0 = s->time;
  SESSILE_CALL(sds_physics_failed(s, sessile_sds_gpu_advance(s->pg, 1, &try_dt, &elapsed)));
  /* step control across calls (one step per call, so that an inversion is
   * rewound over one step): the integrator proposes the next step */
  s->dt = try_dt;
  SESSILE_CALL(sessile_sds_gpu_download(s->pg, &s->o));
  return sds_finish_step(s, elapsed);
}

/* Frame k's time, t_end x (k / frames): k / frames first, so that frames
 * at the same fraction of t_end in runs of other --frames have the same
 * time to the bit (1/5 and 10/50 round alike); the last is t_end itself. */
double sds_frame_time(const sds_sim *s, int k) { return s->t_end * ((double)k / s->frames); }

/* Steps up to frame s->frame: the steps go on until the first whose end is
 * at or past the frame's time (none when an earlier step passed it), so the
 * step boundaries are those of one loop over the whole run, whatever the
 * frames; or SESSILE_ERR_INTERRUPTED after a step when a stop is asked; the
 * state after any step resumes exactly (every step ends with an upload). */
sessile_status sds_frame_steps(sds_gen_state *g) {
  sds_sim *s = &g->s;
  sessile_run *run = g->su->run;
  const sds_gen_args *a = g->su->extra;
  double next_frame = sds_frame_time(s, s->frame);
  while (s->time < next_frame) {
    SESSILE_CHECK(s->o.ncells <= a->max_cells, SESSILE_ERR_NO_MEMORY,
                  "sds: %u cells at t = %g, more than the limit %u (--max-cells)", s->o.ncells, s->time, a->max_cells);
    if (s->prm.device_loop) /* a batch of steps on the device (sds_loop_device.c) */
      SESSILE_CALL(sds_device_batch(s, run, next_frame));
    else {
      double t0 = s->time, w0 = sessile_wall_seconds();
      uint64_t d0 = s->st->divisions, i0 = s->st->inversions;
      SESSILE_CALL(step(s));
      SESSILE_CALL(sds_steplog_row(s, run, s->time - t0, 1e3 * (sessile_wall_seconds() - w0), s->st->divisions - d0,
                                   s->st->inversions - i0));
    }
    if (s->time >= next_frame) break;
    sessile_gen_progress(g->su, "steps", 1 - (next_frame - s->time) / (s->t_end / s->frames), NULL);
    int stop = sessile_run_stop_requested(run);
    if (stop) return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d at t = %g", stop, s->time);
  }
  return SESSILE_OK;
}

/* The checkpoint's sections: the step log appended first (the checkpoint
 * keeps its length). */
sessile_status sds_sections(sds_gen_state *g, sessile_ckpt_section *sec, int *n) {
  sds_sim *s = &g->s;
  SESSILE_CALL(sds_steplog_flush(s, g->su->run));
  loop_scalars(s, &g->loop);
  *n = sds_ckpt_sections(&s->o, &g->loop, s->retry_at, s->sliver, s->frame_time, g->counts, sec);
  return SESSILE_OK;
}

sessile_status sds_gen_setup(sds_gen_state *g, const sessile_sds_run_params *params) {
  sds_sim *s = &g->s;
  s->st = &g->st;
  s->rng = sessile_rng_stream(g->su->seed, 1);
  s->seed = g->su->seed;
  g->t0 = g->tf = sessile_wall_seconds();
  return setup(g, params);
}

sessile_status sds_gen_restore(sds_gen_state *g, const sessile_ckpt *ck) {
  sds_sim *s = &g->s;
  SESSILE_CALL(restore(s, ck));
  SESSILE_CHECK(s->frame == sessile_ckpt_iteration(ck) + 1, SESSILE_ERR_IO,
                "the checkpoint's loop section does not fit this run (damaged?)");
  s->o.edge_k_defer = s->prm.axial_stiffness != 1;
  SESSILE_CALL(sds_neighbours(s));
  return sds_gpu_create(g);
}

sessile_status sds_gpu_create(sds_gen_state *g) {
  SESSILE_CALL(sessile_sds_gpu_create(g->su->gpu, &g->s.o, &g->s.p, &g->s.pg));
  sessile_sds_gpu_fuse(g->s.pg, (sessile_sds_fuse)g->s.prm.device_fuse);
  SESSILE_CALL(sessile_morph_gpu_create(g->su->gpu, &g->s.mg));
  return g->s.prm.device_loop ? sds_device_loop_create(&g->s, g->su->gpu) : SESSILE_OK;
}
