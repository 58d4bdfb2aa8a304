/* The rules' step inside a batch of physics steps (docs/sds.md, "The loop on
 * the device"; kernels.def, "The rules' step inside a batch"): the batch's
 * hook records, after each step's check, morph_bound (or step_check made it
 * with the check: sds_gpu_batch_rules_check), the rules' two modes around
 * the morphogens' sub-steps (mode 0 with the first in rules_morph where the
 * views fit, and with one sub-step the apply too), and stable_min mode 4 (the lists' staleness with the grown
 * radii; the stop at a division or a step the host must complete).  Every kernel reads the step's dt and time from the
 * device, so a batch of K steps needs the host only at its end. */
#include <string.h>
#include "sds/sds_gpu_internal.h"
#include "sds/sds_gpu_rules.h"

static sessile_status rules_hook(sessile_sds_gpu *s, void *ctx, uint32_t k, int c) {
  sds_gpu_rules *r = ctx;
  if (!s->check_fused) /* else step_check made the bound with the step's check */
    SESSILE_CALL(sds_gpu_rules_record_bound(r, s->cmd, s->b[B_X0 + c], s->b[B_STEP], s->b[B_EVENT], k + 1, s->nsub_max));
  /* the growth check after them (stable_min mode 4): folded into the next
   * step's stable_min by the batch (sds_gpu_batch.c, record_batch) */
  SESSILE_CALL(sds_gpu_rules_record_batch_step(r, s->cmd, s->b[B_X0 + c], s->b[B_RM], k + 1, s->nsub_max));
  return sds_gpu_rules_record_axial(r, s->cmd, s->b[B_TOPO], s->b[B_SM], s->b[B_X0 + c], s->b[B_RM], s->ntets,
                                    s->nedges, k + 1, s->nsub_max);
}

sessile_status sds_gpu_batch_rules_check(sessile_sds_gpu *s, uint32_t k, int c, int *done) {
  *done = 0;
  return s->rules && s->hook == rules_hook ? sds_gpu_rules_record_check(s, k, c, done) : SESSILE_OK;
}

sessile_status sds_gpu_batch_rules_start(sessile_sds_gpu *s) {
  if (!s->rules || s->hook != rules_hook) return SESSILE_OK;
  SESSILE_CALL(sds_gpu_rules_record_batch_start(s->rules, s->cmd, s->b[B_RM]));
  if (s->rb && sds_gpu_contacts_on(s)) SESSILE_CALL(sessile_cmd_upload_reals(s->cmd, s->b[B_RB], 0, s->rb, s->ncells));
  return SESSILE_OK;
}

void sds_gpu_batch_rules_groups(const sessile_sds_gpu *s, uint32_t out[3]) {
  out[0] = out[1] = out[2] = 0;
  if (s->rules && s->hook == rules_hook) sds_gpu_rules_groups(s->rules, s->ntets, out);
}

sessile_status sds_gpu_batch_rules_end(sessile_sds_gpu *s) {
  if (!s->rules || s->hook != rules_hook) return SESSILE_OK;
  SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_RM], 0, s->rm, 2 * (size_t)s->ncells));
  return sds_gpu_rules_record_results(s->rules, s->cmd);
}

void sds_gpu_batch_rules_ready(sessile_sds_gpu *s) {
  if (!s->rules || s->hook != rules_hook) return;
  s->rm_fresh = 1;
  sds_gpu_rules_results_ready(s->rules);
}

void sds_gpu_batch_rules(sessile_sds_gpu *s, sds_gpu_rules *r, uint32_t nsub_max) {
  sds_gpu_rules_attach(s, r);
  s->hook = r ? rules_hook : NULL, s->hook_ctx = r;
  s->nsub_max = nsub_max;
}

sessile_status sds_gpu_pull_radii(sessile_sds_gpu *s) {
  SESSILE_CHECK(!s->rm_pending, SESSILE_ERR_INTERNAL, "sds: radii pulled over an upload not yet made");
  if (s->rm_fresh) return SESSILE_OK; /* the batch's submission brought them */
  return sessile_buffer_download_reals(s->b[B_RM], 0, s->rm, 2 * (size_t)s->ncells);
}

sessile_status sds_gpu_download_prev_x(sessile_sds_gpu *s, double *x) {
  return sessile_buffer_download_reals(s->b[B_X0 + 1 - s->cur], 0, x, 3 * (size_t)s->ncells);
}
