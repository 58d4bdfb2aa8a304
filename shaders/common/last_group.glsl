// The subgroup that finishes a dispatch last, which may then read what every
// other invocation wrote in it (a single-pass reduction: the work of a
// one-workgroup kernel that would otherwise be a dispatch of its own, each a
// thread-pool round trip on lavapipe).  Every subgroup makes its writes
// visible, then counts itself in word `i` of the coherent uint buffer CNT
// (zero before the dispatch); the one that counts last sets it back to zero
// for the next and returns true on all its lanes, which then run the
// one-workgroup code with GRP_SUBGROUP (group.glsl).  The includer enables
// GL_KHR_shader_subgroup_basic and _arithmetic (the device check requires both).  Subgroups, not
// workgroups: counting a workgroup needs a workgroup barrier, which on
// lavapipe suspends and resumes every vector of lanes of every workgroup
// (llvmpipe runs them as coroutines) and cost more than the dispatch it
// saved.  Call it from every invocation, the subgroup converged.  What the
// last subgroup reads of the others' writes must be coherent (kernels.def:
// rwc).  Which subgroup is last varies from run to run; what it computes must
// not depend on it (a min, a check over all cells).
#ifndef LAST_GROUP_GLSL
#define LAST_GROUP_GLSL
#define LAST_GROUP(CNT, i) last_group_of_##CNT(i)
#define DECLARE_LAST_GROUP(CNT)                                                              \
  bool last_group_of_##CNT(uint i) {                                                         \
    memoryBarrierBuffer();                                                                   \
    subgroupMemoryBarrierBuffer();                                                           \
    subgroupBarrier();                                                                       \
    uint before = 0u;                                                                        \
    if (subgroupElect()) before = atomicAdd(CNT[i], 1u);                                     \
    before = subgroupMax(before); /* the elected lane's: arithmetic, which sessile requires */ \
    uint n = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z * gl_NumSubgroups; \
    bool last = before == n - 1u;                                                            \
    if (last && subgroupElect()) CNT[i] = 0u;                                                \
    memoryBarrierBuffer();                                                                   \
    return last;                                                                             \
  }
#endif
