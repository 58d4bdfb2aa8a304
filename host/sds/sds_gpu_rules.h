/* The rules on the device (docs/sds_rules.md, "Bytecode"): the model's
 * bytecode run per cell by shaders/sds/rules_vm.comp, equal to the host's
 * evaluator and actions (tests/sds/test_rules_vm.c).
 *
 * A step records mode 0 (evaluate, reading the amounts before the morphogen
 * step: sources into SRC, pending sets and growth, division requests into
 * DIVREQ with their count in EVENT), then the morphogen step (amounts PHI,
 * sources SRC), then mode 1 (apply: r += dt grow, the sets clamped as
 * sessile_sds_actions_apply clamps them, m = density 4/3 pi r^3 into rm).
 * EVENT (uint, SDS_EV_COUNT words, sds_kernels.h): FLAGS bit 0 a division
 * requested, bit 1 a value not finite (BAD: the smallest such cell; the host
 * evaluator then gives the message); once FLAGS is set, mode 1 sets STOP and
 * every later step of the batch does nothing, so a batched loop wakes the
 * host at the first topology event.  Requests (SDS_REQ reals: cell, rule,
 * unit direction or 0) are in the order the atomics gave: sort by cell. */
#ifndef SESSILE_SDS_GPU_RULES_H
#define SESSILE_SDS_GPU_RULES_H
#include "sessile/gpu/gpu.h"
#include "sessile/sds/sds.h"
#include "sessile/sds/sds_process.h"
#include "sds_kernels.h"

typedef struct sds_gpu_rules sds_gpu_rules;
enum { SDS_RULES_PHI, SDS_RULES_STATE, SDS_RULES_SRC, SDS_RULES_EVENT, SDS_RULES_DIVREQ, SDS_RULES_POS, SDS_RULES_RM };

/* Refuses (SESSILE_ERR_USAGE, the rule named) a model whose bytecode has an
 * operation without a device version, and an fp32 context. */
sessile_status sds_gpu_rules_create(sessile_gpu *g, const sessile_sds_model *m, sds_gpu_rules **out);
/* The same with the kernel chosen (sessile_sds_rules_kernel): the rules
 * written out as GLSL and compiled at load (the default above), or the
 * bytecode interpreter (docs/sds_rules.md, "Generated kernel"). */
sessile_status sds_gpu_rules_create_kind(sessile_gpu *g, const sessile_sds_model *m, int kind, sds_gpu_rules **out);
void sds_gpu_rules_destroy(sds_gpu_rules *r);
/* Uploads cells (after a topology change): positions and radii into its own
 * POS and RM (for runs that do not bind the physics'), neighbours, surface
 * flags, amounts and states; density for the masses. */
sessile_status sds_gpu_rules_set_cells(sds_gpu_rules *r, const sessile_morph_cells *cells, const double *phi,
                                       const double *state, double density);
/* Records into cmd: the event words cleared (a batch's start), mode 0 at
 * `time`, mode 1 with step dt.  pos and rm NULL: its own POS and RM. */
sessile_status sds_gpu_rules_record_clear(sds_gpu_rules *r, sessile_cmd *cmd);
/* A batch's start: the event words cleared, and rm_next (rules_morph's
 * apply writes the step's radii there, then they are copied into rm) set to
 * rm, so that a copy whose dispatch the batch's stop skipped copies rm. */
sessile_status sds_gpu_rules_record_batch_start(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *rm);
sessile_status sds_gpu_rules_record_eval(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                                         double time);
sessile_status sds_gpu_rules_record_apply(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                                          double dt);
sessile_buffer *sds_gpu_rules_buffer(const sds_gpu_rules *r, int which);
/* The event words and the requests (sorted by cell; *nreq of them, at most
 * the cell count), read after the submission ran.  req: SDS_REQ per request
 * (NULL: the event words and the count only). */
sessile_status sds_gpu_rules_read_events(sds_gpu_rules *r, uint32_t ev[SDS_EV_COUNT], double *req, uint32_t *nreq);
/* Records into cmd, after its last dispatch, the downloads of the event
 * words, amounts and states, which read_events and get_cells then give
 * without a submission of their own once results_ready says the recording
 * ran (until the next recording or upload on r).  For a discrete GPU, where
 * each blocking read is a submission and a wait. */
sessile_status sds_gpu_rules_record_results(sds_gpu_rules *r, sessile_cmd *cmd);
void sds_gpu_rules_results_ready(sds_gpu_rules *r);

/* The batched loop's entry (issue 33): with r attached to s, record mode 0
 * into s's open recording, reading s's positions and r, m (which mode 1 then
 * writes: the device owns them between topology events), and keep dt for
 * sds_gpu_rules_record_apply_s, recorded after the morphogen step. */
void sds_gpu_rules_attach(sessile_sds_gpu *s, sds_gpu_rules *r);
sessile_status sds_gpu_rules_record(sessile_sds_gpu *s, double time, double dt);
sessile_status sds_gpu_rules_record_apply_s(sessile_sds_gpu *s);

/* Inside a batch of physics steps (sds_gpu_batch_rules.c; kernels.def,
 * "The rules' step inside a batch"): morph_bound for step batch - 1 (its
 * result at pos, the batch's log in step, the physics' events pev); then
 * rules mode 0, nsub morphogen sub-steps (the amounts ping-pong between
 * two buffers over the batch), mode 1, each reading the step's time and dt
 * from the control morph_bound left.  After the batch, batch_done with the
 * steps whose rules ran on the device: the amounts' buffer is R_PHI again. */
sessile_status sds_gpu_rules_record_bound(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *step,
                                          sessile_buffer *pev, uint32_t batch, uint32_t nsub_max);
sessile_status sds_gpu_rules_record_batch_step(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos,
                                               sessile_buffer *rm, uint32_t batch, uint32_t nsub);
void sds_gpu_rules_batch_done(sds_gpu_rules *r, uint32_t steps, uint32_t nsub);
/* The oriented growth and convergent extension in the batch (docs/sds.md,
 * "Oriented growth", "Convergent extension"): with A != 0 or C != 0 each
 * batch step's rules are followed by axial_grad over the cells, then
 * axial_grow (A) and axial_extend (C, between cells whose state sext is set)
 * over the edges (record_axial, after record_batch_step), along the gradient
 * of morphogen `axis`; set before the first set_cells.  record_axial reads
 * the radii at the step's start that record_batch_step keeps, and multiplies
 * the edges' s_m (sm at ntets, the physics' topology topo) as
 * sds_axial_grow_edges and sds_axial_extend_edges do. */
sessile_status sds_gpu_rules_set_axial(sds_gpu_rules *r, int axis, double A, double C, int sext);
sessile_status sds_gpu_rules_record_axial(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *topo, sessile_buffer *sm,
                                          sessile_buffer *pos, sessile_buffer *rm, uint32_t ntets, uint32_t nedges,
                                          uint32_t batch, uint32_t nsub);
/* A batch's rules (sds_gpu_batch_rules.c): with r (NULL: none) every
 * accepted step of s's batches makes its rules' step on the device, at most
 * nsub_max morphogen sub-steps (beyond, and for a step that inverted a tet,
 * the batch stops with the step's rules left to the host: SDS_EV_HOST, and
 * the rules' event word LAST tells the last step whose rules ran); the
 * radii the device grew into s's host copy (then sessile_sds_gpu_download
 * gives them); the positions before the last step (the other pair). */
void sds_gpu_batch_rules(sessile_sds_gpu *s, sds_gpu_rules *r, uint32_t nsub_max);
/* A batch's start (sessile_sds_gpu_batch, after the lists' build): the
 * rules' events cleared, the radii at the lists' build up. */
sessile_status sds_gpu_batch_rules_start(sessile_sds_gpu *s);
/* Its end, on unmapped buffers: the radii, events, amounts and states
 * downloaded in the batch's submission (recorded after its last dispatch);
 * ready after the submission ran. */
sessile_status sds_gpu_batch_rules_end(sessile_sds_gpu *s);
/* The workgroup counts of the rules' and the morphogens' dispatches (for
 * sessile_cmd_indirect); of a batch's hook, or 0 and 0 without one. */
void sds_gpu_rules_groups(const sds_gpu_rules *r, uint32_t ntets, uint32_t out[3]);
/* A batch step's inverted flags, check and morphogens' bound in one dispatch
 * (step_check.comp; k the step, c its result's pair) when the views fit;
 * *done 0 otherwise.  sds_gpu_batch_rules_check: the same when the batch
 * runs the rules (its hook), for sds_gpu_batch.c. */
sessile_status sds_gpu_rules_record_check(sessile_sds_gpu *s, uint32_t k, int c, int *done);
sessile_status sds_gpu_batch_rules_check(sessile_sds_gpu *s, uint32_t k, int c, int *done);
void sds_gpu_batch_rules_groups(const sessile_sds_gpu *s, uint32_t out[3]);
void sds_gpu_batch_rules_ready(sessile_sds_gpu *s);
sessile_status sds_gpu_pull_radii(sessile_sds_gpu *s);
sessile_status sds_gpu_download_prev_x(sessile_sds_gpu *s, double *x);
/* The amounts and states as the device holds them. */
sessile_status sds_gpu_rules_get_cells(sds_gpu_rules *r, double *phi, double *state);
#endif
