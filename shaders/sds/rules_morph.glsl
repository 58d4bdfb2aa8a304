// A batch step's rules (mode 0) and its first morphogen sub-step in one
// dispatch (kernels.def, SDS_RULES_MORPH): the invocation of cell c
// evaluates c's rules, then steps c's amounts.  Nothing crosses between
// invocations: the sub-step reads c's own sources (just written, through the
// storage buffer src) and, of c's neighbours, only what no invocation of
// this dispatch writes (positions, radii, the amounts at the step's start).
// So it gives the bytes of rules_vm mode 0 followed by morph_step_batch, one
// thread-pool round trip fewer a step on lavapipe.  Mode 2, when the step
// has one sub-step: the apply (rules_vm mode 1) too, its radii and masses
// into rm_next, which the host's recording copies into rm after the
// dispatch (sessile_cmd_copy: no round trip), because every cell's sub-step
// reads its neighbours' radii as they were; a cell whose step is the host's
// copies its own.  A division asked sets STOP to the step's index in the
// batch, not 1: the invocations of the same dispatch that read STOP after it
// was set must still make their step (the first version lost a step's
// growth there; sds_device_loop's byte comparison caught it).  With SDS_RULES_GEN the generated evaluate_gen
// (host/sds/rules_glsl.c), else the interpreter (rules_morph.comp).
#define RULES_TEXEL 1
#define RULES_NO_MAIN 1
#define AP_R_IN(c) RV_R(c)
#define AP_RM_OUT rm_next
#define AP_PHI_OUT phi_out
#include "rules_vm.glsl"

#define MORPH_FUSED 1
#define MORPH_BATCH 1
#define MORPH_NO_MAIN 1
#define MORPH_CTL(i) konst[pc.kctl + (i)]
#define MORPH_SKIPPED (event[SDS_EV_SKIP] != 0u)
#define MORPH_SUB 1u
#define LD_POS(i) RV_X(i)
#define LD_RADIUS(i) RV_R(i)
#define LD_OFF(i) RV_OFF(i)
#define LD_NBR(i) RV_NBR(i)
#define LD_PHI(i) RV_PHI(i)
#define LD_SRC(i) src[i]
#include "morph_step.glsl"

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  bool mine = true;
  // a division asked earlier in the batch (as rules_vm mode 0); in mode 2 this
  // dispatch's own invocations set STOP to its step, which must not stop the rest
  uint stop = event[SDS_EV_STOP];
  if (stop != 0u && stop != pc.batch) {
    event[SDS_EV_SKIP] = 1u;
    mine = false;
  } else if (event[SDS_EV_SKIP] != 0u) { // morph_bound: the host's step
    mine = false;
  }
  if (!mine) {
    if (pc.mode == 2u) rm_next[2u * c] = RV_R(c), rm_next[2u * c + 1u] = texel_real(rm_t, 2u * c + 1u);
    return;
  }
#ifdef SDS_RULES_GEN
  evaluate_gen(c);
#else
  evaluate(c);
#endif
  morph_cell(c);
  if (pc.mode == 2u) { // rules_vm mode 1 (the invocation that asked a division sees its own flag)
    apply(c);
    if (event[SDS_EV_FLAGS] != 0u) event[SDS_EV_STOP] = pc.batch;
    if (c == 0u) event[SDS_EV_LAST] = pc.batch;
  }
}
