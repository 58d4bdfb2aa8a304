// Workgroup tree reduction of a REAL2 accumulator (power-of-two local size).
shared REAL2 red_sh[gl_WorkGroupSize.x];

REAL2 group_reduce(REAL2 v) {
  uint l = gl_LocalInvocationID.x;
  barrier(); // a previous call's readers of red_sh[0] must be done
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
}
