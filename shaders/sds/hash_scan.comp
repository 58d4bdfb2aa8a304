#version 450
#extension GL_GOOGLE_include_directive : require
// One workgroup: bucket offsets off = exclusive prefix sum of the counts
// (each invocation a contiguous chunk, the chunk totals scanned in shared
// memory), and the fill cursors cur = off.  Sums only: fixed result.
#include "sds_common.glsl"

shared uint part[SDS_SCAN_MAX];

void main() {
  uint l = gl_LocalInvocationID.x, L = gl_WorkGroupSize.x, T = pc.tsize;
  uint chunk = (T + L - 1u) / L, lo = min(l * chunk, T), hi = min(lo + chunk, T);
  uint sum = 0u;
  for (uint i = lo; i < hi; i++) sum += hash[i];
  part[l] = sum;
  barrier();
  if (l == 0u) {
    uint run = 0u;
    for (uint k = 0u; k < L; k++) {
      uint t = part[k];
      part[k] = run;
      run += t;
    }
    hash[2u * T] = run; // off[T]: every face once
  }
  barrier();
  uint base = part[l];
  for (uint i = lo; i < hi; i++) {
    hash[T + i] = base;
    hash[2u * T + 1u + i] = base;
    base += hash[i];
  }
}
