#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The stable bound per cell (stable.glsl, through texels) and its minimum
// (stable_min.glsl: in a batch first the step before's checks) in one
// dispatch (kernels.def, SDS_STABLE_ALL): the subgroup that finishes last
// (last_group.glsl) runs stable_min over every cell's bound, which reach it
// through stab (coherent).  The same bits as stable_tex then stable_min (a
// min is exact in any order; the checks read only what earlier dispatches
// wrote); one thread-pool round trip fewer a step on lavapipe.
#define SDS_TEXEL 1
#define GRP_SUBGROUP 1 // the one-workgroup code runs on the last subgroup
#define STABLE_NO_MAIN 1
#include "stable.glsl"
// no slivers' table reaches stable_all's check: it checks only in a batch
// without the rules (not split), and only the rules' batches get a table
// (sessile_sds_gpu_batch); the cubic's code left out of the tail
#define SDS_SLIVERS 0
#define STABLE_MIN_NO_MAIN 1
#include "stable_min.glsl"
#include "last_group.glsl"
DECLARE_LAST_GROUP(cnt)

void main() {
  // each invocation every sessile_invocations()-th cell: on a CPU device the
  // host launches few subgroups, each of which runs the tail masked
  // (sds_gpu_tail_groups); one cell each elsewhere
  for (uint c = sessile_gid(); c < pc.ncells; c += sessile_invocations())
    if (!(pc.batch != 0u && ev[0] != 0u)) stable_cell(c); // else a batch that stopped
  if (LAST_GROUP(cnt, 0u)) stable_min_run();
}
