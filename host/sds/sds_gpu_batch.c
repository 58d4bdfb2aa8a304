/* A batch of SDS physics steps in one submission (sessile/sds/sds_batch.h,
 * docs/sds.md "The loop on the device"): per step the forces (elem_force,
 * or edge_force and tet_force for a large complex, the tets' kernel also
 * flagging the inverted tets of its input), the stable bound with
 * stable_min (stable_all where texels fit; it first checks the step before,
 * as sessile_sds_gpu_advance does on the host) and the gather; with the
 * rules, each step's check right after it (step_check: with the inverted
 * flags and the morphogens' bound) and the rules' hook.  The kernels honour
 * the event word, so the batch stops itself after the first step that
 * raises one.  The host reads the events, the count of accepted steps and
 * their log once, at the end. */
#include <math.h>
#include <string.h>
#include "sessile/sds/sds_batch.h"
#include "sds/sds_gpu_internal.h"
#include "sds/sds_gpu_rules.h"

_Static_assert((int)SESSILE_SDS_EV_DIVIDE == (int)SDS_EV_DIVIDE && (int)SESSILE_SDS_EV_REJECT == (int)SDS_EV_REJECT &&
                   (int)SESSILE_SDS_EV_NONFINITE == (int)SDS_EV_NONFINITE && (int)SESSILE_SDS_EV_INVERTED == (int)SDS_EV_INVERTED &&
                   (int)SESSILE_SDS_EV_LISTS == (int)SDS_EV_LISTS && (int)SESSILE_SDS_EV_TIME == (int)SDS_EV_TIME &&
                   (int)SESSILE_SDS_EV_DTMIN == (int)SDS_EV_DTMIN && (int)SESSILE_SDS_EV_HOST == (int)SDS_EV_HOST &&
                   (int)SESSILE_SDS_BATCH_MAX == (int)SDS_BATCH_MAX && (int)SESSILE_SDS_SLIVERS_MAX == (int)SDS_SL_MAX,
               "sds_batch.h's events are kernels.def's");

/* Records the check of step k (stable_min in mode 3) after its result's
 * inverted flags (pair c). */
static sessile_status record_check(sessile_sds_gpu *s, uint32_t k, int c, uint32_t split) {
  if (s->ntets) SESSILE_CALL(sds_gpu_record_inverted(s, c, (k + 1) | split));
  sds_push p = sds_gpu_push_of(s, 0.0, 1, 3);
  p.batch = (k + 2) | split;
  return sds_gpu_record_stable_min(s, &p, c);
}

/* Records the batch: step k reads pair (cur + k) & 1.  Folded (five
 * dispatches a step): its tet_force flags step k - 1's result and its
 * stable_min checks step k - 1; the last step is checked after the loop.
 * Split (a hook, or asked for): each step checked right after its gather,
 * then the hook (seven dispatches a step, and the hook's). */
static sessile_status record_batch(sessile_sds_gpu *s, uint32_t steps) {
  uint32_t split = s->batch_split || s->hook ? SDS_BATCH_SPLIT : 0;
  /* With the rules' hook, the growth check after a step's rules (stable_min
   * mode 4) is folded into the next step's stable_min (SDS_BATCH_RULES; the
   * push's dt carries the reach's scale, which no kernel of a batch's
   * forces reads otherwise), and made alone after the last step. */
  double reach = s->hook ? sds_gpu_reach_scale(s) : 0.0;
  for (uint32_t k = 0; k < steps; k++) {
    int c = (s->cur + (int)k) & 1;
    uint32_t fold = s->hook && k > 0 ? SDS_BATCH_RULES : 0;
    SESSILE_CALL(sds_gpu_record_forces(s, c, reach, 1, 2, (k + 1) | split | fold));
    s->check_fused = 0;
    if (split) SESSILE_CALL(sds_gpu_batch_rules_check(s, k, 1 - c, &s->check_fused));
    if (split && !s->check_fused) SESSILE_CALL(record_check(s, k, 1 - c, split));
    if (s->hook) SESSILE_CALL(s->hook(s, s->hook_ctx, k, 1 - c));
  }
  if (s->hook) {
    sds_push p = sds_gpu_push_of(s, reach, 1, 4);
    p.batch = (steps + 1) | SDS_BATCH_SPLIT;
    SESSILE_CALL(sds_gpu_record_stable_min(s, &p, s->cur));
  }
  return split ? SESSILE_OK : record_check(s, steps - 1, (s->cur + (int)steps) & 1, 0);
}

void sessile_sds_gpu_batch_split(sessile_sds_gpu *s, int split) { s->batch_split = split != 0; }

void sessile_sds_gpu_fuse(sessile_sds_gpu *s, sessile_sds_fuse fuse) { s->fuse = fuse; }

sessile_status sessile_sds_gpu_batch(sessile_sds_gpu *s, sessile_sds_batch *b) {
  const sessile_sds_params *p = &s->p;
  SESSILE_CHECK(b->steps >= 1 && b->steps <= SDS_BATCH_MAX, SESSILE_ERR_USAGE,
                "sds: steps per batch must be 1..%d (got %u)", SDS_BATCH_MAX, b->steps);
  SESSILE_CHECK(!b->slivers || b->nslivers <= SDS_SL_MAX, SESSILE_ERR_USAGE,
                "sds: a batch takes at most %d lasting slivers (got %u)", SDS_SL_MAX, b->nslivers);
  b->done = 0, b->events = 0, b->quiet = 0, b->quiet_last = 0;
  SESSILE_CALL(sds_gpu_lists_ensure(s));
  /* The batch's inputs and results ride in its own submission
   * (sessile_cmd_upload/download): on a discrete GPU each blocking transfer
   * is a submission and a wait of its own, seven a batch before (docs/sds.md,
   * "The loop on the device").  The control's scalars (kernels.def, step):
   * the step asked, the time, the stop time, the lists' growth term of
   * sds_gpu_lists_stale. */
  double ctl[5] = {b->dt, b->time, b->t_stop, sds_gpu_reach_scale(s) * s->grown, 0};
  const uint32_t zero[4] = {0, 0, 0, 0};
  uint32_t ev[4], quiet[2];
  double st[SDS_STEP_LOG];
  /* the slivers' table (kernels.def, SL_*): only a batch with the rules
   * checks its steps with the inverted tets listed (split) */
  uint32_t tab[SL_TAB + 2 * SDS_SL_MAX] = {0};
  uint32_t ntab = b->slivers && s->hook ? b->nslivers : 0;
  tab[SL_COUNT] = ntab;
  s->batch_slivers = ntab;
  if (ntab) memcpy(tab + SL_TAB, b->slivers, 2 * (size_t)ntab * sizeof *tab);
  SESSILE_CALL(sds_gpu_begin(s));
  SESSILE_CALL(sds_gpu_batch_rules_start(s));
  /* The dispatches after a stop launch nothing (stable_min zeroes their
   * counts): on lavapipe each launch, even of a kernel that returns at once,
   * is a round trip through its thread pool (docs/sds.md, "The loop on the
   * device"). */
  uint32_t groups[10] = {sds_gpu_elem_groups(s), sds_gpu_groups(s, SDS_TET, s->ntets),
                         sds_gpu_stable_groups(s), sds_gpu_groups(s, SDS_GATHER, s->ncells),
                         sds_gpu_groups(s, SDS_INVERTED, s->ntets), 1, 0, 0, 0,
                         sds_gpu_groups(s, SDS_EDGE, s->nedges)};
  if (s->hook) sds_gpu_batch_rules_groups(s, &groups[6]);
  SESSILE_CALL(sessile_cmd_indirect(s->cmd, s->b[B_DISP], groups, 10));
  SESSILE_CALL(sessile_cmd_upload_reals(s->cmd, s->b[B_STEP], 3, ctl, 5));
  SESSILE_CALL(sessile_cmd_upload(s->cmd, s->b[B_EVENT], 0, zero, sizeof zero));
  SESSILE_CALL(sessile_cmd_upload(s->cmd, s->b[B_SLIVER], 0, tab, (SL_TAB + 2 * (size_t)ntab) * sizeof *tab));
  SESSILE_CALL(record_batch(s, b->steps));
  SESSILE_CALL(sessile_cmd_download(s->cmd, s->b[B_EVENT], 0, ev, sizeof ev));
  SESSILE_CALL(sessile_cmd_download(s->cmd, s->b[B_SLIVER], SL_QUIET * sizeof *tab, quiet, sizeof quiet));
  SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_STEP], 0, st, SDS_STEP_LOG));
  /* every step's row; the accepted ones (done, below) are read */
  if (b->log) SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_STEP], SDS_STEP_LOG, b->log, 2 * (size_t)b->steps));
  /* Unmapped buffers (a discrete GPU): what the loop reads after a batch
   * comes down in it too: x, v of both pairs (the batch may end on either),
   * the radii its rules grew, the rules' events and cells. */
  int rec = !sessile_buffer_host_ptr(s->b[B_X0]);
  size_t n3 = 3 * (size_t)s->ncells;
  if (rec) {
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_X0], 0, s->hx, n3));
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_V0], 0, s->hv, n3));
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_X1], 0, s->hx2, n3));
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_V1], 0, s->hv2, n3));
    SESSILE_CALL(sds_gpu_batch_rules_end(s));
  }
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  s->flags_cur = -1, s->mirror = -1;
  SESSILE_CALL(sds_gpu_submit(s));
  uint32_t done = ev[1], e = ev[0];
  SESSILE_CHECK(done <= b->steps, SESSILE_ERR_INTERNAL, "sds: a batch of %u steps accepted %u", b->steps, done);
  if (rec) { /* hx, hv hold pair 0, hx2, hv2 pair 1: the current pair into hx, hv */
    if ((s->cur + (int)done) & 1) {
      double *t = s->hx;
      s->hx = s->hx2, s->hx2 = t;
      t = s->hv, s->hv = s->hv2, s->hv2 = t;
    }
    s->mirror = (s->cur + (int)done) & 1;
    sds_gpu_batch_rules_ready(s);
  }
  s->cur = (s->cur + (int)done) & 1; /* a rejected step wrote the other pair */
  b->done = done, b->events = e, b->quiet = quiet[0], b->quiet_last = quiet[1];
  if (done) b->time = st[4], b->dt = st[3];
  if (e & SDS_EV_LISTS) lists_invalidate(s);
  if (!(e & SDS_EV_REJECT) && !(e & SDS_EV_NONFINITE) && done) s->flags_cur = s->cur;
  if (e & SDS_EV_NONFINITE)
    return sessile_error_set(SESSILE_ERR_NUMERIC, "sds: the state is not finite after a step of %g s (blow-up)", st[0]);
  if (e & SDS_EV_REJECT) { /* undone: the next batch retries at half the step */
    double h = 0.5 * st[0];
    SESSILE_CHECK(h >= p->dt_min, SESSILE_ERR_NUMERIC,
                  "sds: the step fell below dt_min = %g s (a step of %g s moved a cell more than %g radii)", p->dt_min,
                  st[0], p->max_move);
    b->dt = h;
  }
  SESSILE_CHECK(!(e & SDS_EV_DTMIN), SESSILE_ERR_NUMERIC,
                "sds: the step fell below dt_min = %g s (a cell moved %g radii in a step of %g s)", p->dt_min, st[7],
                st[0]);
  return SESSILE_OK;
}
