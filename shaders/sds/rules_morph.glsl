// A batch step's rules (mode 0) and its first morphogen sub-step in one
// dispatch (kernels.def, SDS_RULES_MORPH): the invocation of cell c
// evaluates c's rules, then steps c's amounts.  Nothing crosses between
// invocations: the sub-step reads c's own sources (just written, through the
// storage buffer src) and, of c's neighbours, only what no invocation of
// this dispatch writes (positions, radii, the amounts at the step's start).
// So it gives the bytes of rules_vm mode 0 followed by morph_step_batch, one
// thread-pool round trip fewer a step on lavapipe.  Apply (mode 1) stays a
// dispatch of its own: it changes the radii the sub-steps of every cell
// read.  With SDS_RULES_GEN the generated evaluate_gen (host/sds/rules_glsl.c),
// else the interpreter (rules_morph.comp).
#define RULES_TEXEL 1
#define RULES_EVAL_ONLY 1
#define RULES_NO_MAIN 1
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
  if (event[SDS_EV_STOP] != 0u) { // a topology event earlier in the batch (as rules_vm mode 0)
    event[SDS_EV_SKIP] = 1u;
    return;
  }
  if (event[SDS_EV_SKIP] != 0u) return; // morph_bound: the host's step
#ifdef SDS_RULES_GEN
  evaluate_gen(c);
#else
  evaluate(c);
#endif
  morph_cell(c);
}
