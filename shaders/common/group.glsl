// The lanes that run a one-workgroup kernel's work: the whole workgroup
// (GRP_LANE of GRP_SIZE, synchronised by barrier()), or with GRP_SUBGROUP
// one subgroup (the last_group.glsl tail of a wider dispatch, synchronised
// by subgroup barriers; the includer enables GL_KHR_shader_subgroup_basic).
// On lavapipe a workgroup barrier suspends and resumes every vector of lanes
// of every workgroup of the dispatch (llvmpipe runs them as coroutines); a
// subgroup is one vector, and its barrier costs nothing of the kind.
#ifndef GROUP_GLSL
#define GROUP_GLSL
#if GRP_SUBGROUP
#define GRP_LANE gl_SubgroupInvocationID
#define GRP_SIZE gl_SubgroupSize
#define GRP_BARRIER()              \
  subgroupMemoryBarrierShared();   \
  subgroupMemoryBarrierBuffer();   \
  subgroupBarrier()
#else
#define GRP_LANE gl_LocalInvocationID.x
#define GRP_SIZE gl_WorkGroupSize.x
#define GRP_BARRIER() barrier()
#endif
#endif
