// Workgroup reduction of a REAL2 accumulator; every invocation gets the sum.
// fp64: subgroup sums, then one pass over the per-subgroup sums (3 barriers:
// lavapipe implements barrier() by switching coroutines, so a log2(n) tree of
// barriers cost more than the memory pass).  fp32: a shared-memory tree of
// two-sums keeps the compensation exact.  Power-of-two local size.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
shared REAL2 red_sh[gl_WorkGroupSize.x];

REAL2 group_reduce(REAL2 v) {
  uint l = gl_LocalInvocationID.x;
  barrier(); // a previous call's readers of red_sh must be done
#if SESSILE_F64
  REAL t = subgroupAdd(v.x);
  if (subgroupElect()) red_sh[gl_SubgroupID] = REAL2(t, 0);
  barrier();
  if (gl_SubgroupID == 0u) {
    REAL r = REAL(0);
    for (uint i = gl_SubgroupInvocationID; i < gl_NumSubgroups; i += gl_SubgroupSize) r += red_sh[i].x;
    r = subgroupAdd(r);
    if (subgroupElect()) red_sh[0] = REAL2(r, 0);
  }
  barrier();
  return red_sh[0];
#else
  red_sh[l] = v;
  barrier();
  for (uint h = gl_WorkGroupSize.x / 2u; h > 0u; h >>= 1u) {
    if (l < h) {
      REAL2 a = red_sh[l];
      acc_merge(a, red_sh[l + h]);
      red_sh[l] = a;
    }
    barrier();
  }
  return red_sh[0];
#endif
}
