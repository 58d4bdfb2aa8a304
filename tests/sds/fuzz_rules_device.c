/* The rules' kernels on fuzzed models (a target for tools/fuzz/driver.c,
 * which mutates tools/fuzz/corpus_sds deterministically): every model the
 * parser accepts and the device can run, up to the first 40 of a run, goes
 * through the generated kernel and the interpreter (docs/sds_rules.md,
 * "Generated kernel") on a seeded lattice of 60 cells: one step of
 * evaluation and actions in one submission, against the host's evaluator
 * and actions.  Both must give the host's sources, division requests,
 * amounts, states and radii bit for bit, or, where a value is not finite,
 * refuse as the host does (its SESSILE_ERR_NUMERIC, the kernel's flag).
 * Anything else aborts, and so does a validation message at the end. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_vm_cells.h"
#include "sds/sds_gpu_rules.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_MODELS = 40 };
static sessile_gpu *gpu;
static int checked;

static void fail(const char *what) {
  fprintf(stderr, "fuzz_rules_device: %s (model %d; last message: %s)\n", what, checked, sessile_error_message());
  abort();
}

static void at_end(void) {
  uint64_t v = gpu ? sessile_gpu_validation_count(gpu) : 0;
  printf("fuzz_rules_device: %d fuzzed models through both kernels on the device, %llu validation messages\n",
         checked, (unsigned long long)v);
  sessile_gpu_destroy(gpu);
  if (v) abort();
}

/* One step of kernel `kind` against the host's evaluation (status hs,
 * actions a, applied into the host's copy H). */
static void one_kernel(const sessile_sds_model *m, int kind, const rvm_cells *C, const rvm_cells *H, sessile_status hs,
                       const sessile_sds_actions *a) {
  const double density = 1.3, time = 1.5, dt = 0.125;
  sessile_morph_cells cl = rvm_morph_cells(C);
  sds_gpu_rules *r = NULL;
  sessile_cmd *cmd = NULL;
  if (sds_gpu_rules_create_kind(gpu, m, kind, &r) != SESSILE_OK) fail("the rules kernel was not made");
  if (sessile_cmd_create(gpu, &cmd) != SESSILE_OK) fail("no command buffer");
  sessile_status st = sds_gpu_rules_set_cells(r, &cl, C->phi, C->state, density);
  if (st == SESSILE_OK) st = sessile_cmd_begin(cmd);
  if (st == SESSILE_OK) st = sds_gpu_rules_record_clear(r, cmd);
  if (st == SESSILE_OK) st = sds_gpu_rules_record_eval(r, cmd, NULL, NULL, time);
  if (st == SESSILE_OK) st = sds_gpu_rules_record_apply(r, cmd, NULL, NULL, dt);
  if (st == SESSILE_OK) st = sessile_cmd_end(cmd);
  if (st == SESSILE_OK) st = sessile_cmd_submit_wait(cmd);
  if (st != SESSILE_OK) fail("the kernel's submission failed");
  size_t n = (size_t)C->n, nm = (size_t)C->nm, ns = (size_t)C->ns;
  double *src = malloc((n * nm + 1) * 8), *phi = malloc((n * nm + 1) * 8), *sv = malloc((n * ns + 1) * 8);
  double *rm = malloc(2 * n * 8), *req = malloc(SDS_REQ * n * 8);
  uint32_t ev[SDS_EV_COUNT], nreq = 0;
  if (!src || !phi || !sv || !rm || !req) fail("out of memory");
  st = sds_gpu_rules_read_events(r, ev, req, &nreq);
  if (st == SESSILE_OK && nm) st = sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_SRC), 0, src, n * nm);
  if (st == SESSILE_OK && nm) st = sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_PHI), 0, phi, n * nm);
  if (st == SESSILE_OK && ns) st = sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_STATE), 0, sv, n * ns);
  if (st == SESSILE_OK) st = sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_RM), 0, rm, 2 * n);
  if (st != SESSILE_OK) fail("the kernel's results did not come down");
  if (hs == SESSILE_ERR_NUMERIC) {
    if (!(ev[SDS_EV_FLAGS] & 2u)) fail("the host found a value not finite, the kernel did not");
  } else {
    if (ev[SDS_EV_FLAGS] & 2u) fail("the kernel found a value not finite, the host did not");
    int ok = nreq == a->ndivides && (!nm || !memcmp(src, a->produce, n * nm * 8));
    for (uint32_t i = 0; ok && i < nreq; i++)
      ok = req[SDS_REQ * i] == a->divides[i].cell && req[SDS_REQ * i + 1] == a->divides[i].rule &&
           !memcmp(&req[SDS_REQ * i + 2], a->divides[i].dir, 24);
    if (!ok) fail("the kernel's sources or division requests are not the host's bits");
    ok = (!nm || !memcmp(phi, H->phi, n * nm * 8)) && (!ns || !memcmp(sv, H->state, n * ns * 8));
    for (size_t c = 0; ok && c < n; c++) ok = !memcmp(&rm[2 * c], &H->r[c], 8);
    if (!ok) fail("the kernel's amounts, states or radii are not the host's bits");
  }
  free(src), free(phi), free(sv), free(rm), free(req);
  sessile_cmd_destroy(cmd);
  sds_gpu_rules_destroy(r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (checked >= MAX_MODELS) return 0;
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = 0;
  sessile_sds_model *m = NULL;
  if (sessile_sds_model_parse(text, "fuzz.sds", &m) == SESSILE_OK && !sessile_sds_model_bytecode_refusal(m, 1)) {
    if (!gpu) {
      gpu = t_gpu(64);
      atexit(at_end);
    }
    rvm_cells C = rvm_cells_make(m, 5, 4, 3, 1000 + (uint64_t)checked), H = rvm_cells_make(m, 5, 4, 3, 1000 + (uint64_t)checked);
    sessile_morph_cells cl = rvm_morph_cells(&C);
    sessile_sds_actions a = {0};
    sessile_status hs = sessile_sds_rules_eval(m, &cl, C.phi, C.state, 1.5, &a);
    if (hs != SESSILE_OK && hs != SESSILE_ERR_NUMERIC) fail("an unexpected status from the host's evaluation");
    if (hs == SESSILE_OK) sessile_sds_actions_apply(m, &a, 0.125, H.r, H.phi, H.state);
    for (int kind = 0; kind < 2; kind++) one_kernel(m, kind, &C, &H, hs, &a);
    checked++;
    sessile_sds_actions_free(&a);
    rvm_cells_free(&C), rvm_cells_free(&H);
  }
  sessile_sds_model_destroy(m);
  free(text);
  return 0;
}
