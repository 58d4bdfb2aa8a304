// A batch step's inverted flags, its check and its morphogens' bound in one
// dispatch (kernels.def, SDS_STEP_CHECK; step_check.comp, and
// step_check_nosl.comp with SDS_SLIVERS 0), for the loop with the rules on the
// device: one invocation per tet flags it (inverted.glsl, through texels)
// and per cell makes its rate for the bound (morph_bound.glsl's mb_cell);
// the subgroup that finishes last then checks the step (stable_min.glsl's
// mode 3) and, the step accepted or not, runs morph_bound.glsl for it.  The
// same bits as the three dispatches inverted, stable_min (mode 3) and
// morph_bound: the flags reach the check through ev[2] (atomics), the check
// reaches the bound through ev and step (coherent, after a barrier), and
// nothing else crosses.  Two thread-pool round trips fewer a step on lavapipe.
#define SDS_TEXEL 1
#define GRP_SUBGROUP 1 // the one-workgroup code runs on the last subgroup
#include "sds_common.glsl"
#include "sds_load.glsl"
#define STABLE_MIN_CHECK_ONLY 1
#include "stable_min.glsl"
#define MB_TEXEL 1
#define MB_RATES 1
#define MB_NO_MAIN 1
#define pos_t x_t
#define pev ev
#include "morph_bound.glsl"
#define INVERTED_NO_MAIN 1
#include "inverted.glsl"
#include "last_group.glsl"
DECLARE_LAST_GROUP(cnt)

void main() {
  uint l = GRP_LANE, L = GRP_SIZE, n = pc.ncells, m = pc.ntets > n ? pc.ntets : n;
  uint bk = pc.batch & ~SDS_BATCH_SPLIT; // 2 + the step's index, as stable_min's mode 3
  // each invocation every sessile_invocations()-th tet and cell: on a CPU
  // device the host launches few subgroups, each of which runs the tail
  // masked (sds_gpu_tail_groups); one each elsewhere
  for (uint t = sessile_gid(); t < m; t += sessile_invocations()) {
    inverted_at(t); // pc.batch != 0: the flag raises ev[2]
    // morph_bound's per-cell part (its cells' rates), here where every lane
    // runs, not in the last subgroup
    if (t < n && pc.nmorph > 0u && ev[0] == 0u) mrate[t] = mb_cell(t);
  }
  if (!LAST_GROUP(cnt, 0u)) return;
  // stable_min's mode 3 for step bk - 2 (stopped before: nothing)
  if (ev[0] == 0u) {
    check_step(l, L, n, bk - 2u);
    if (evs != 0u && l == 0u) stab[n] = REAL(-1);
  }
  memoryBarrierBuffer();
  GRP_BARRIER();
  morph_bound_run(l, L, bk - 2u);
}
