#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x, sliced ELL (SELL-8): slices of 8 consecutive rows; a slice stores
// its rows' entries in chunks of 4 (uvec4 columns, REAL4 values), chunk t of
// row j of the slice at slice_ptr[s] + 8 t + j, so the 8 lanes of a subgroup
// read one contiguous run per load (lavapipe scalarises per-lane loads; a
// single sequential stream is what its CPU prefetchers follow).  Rows shorter
// than the slice's widest are padded with column = the row's last column,
// value 0.  One row per invocation.
#include "../common/sessile.glsl"
layout(push_constant) uniform SpmvPush {
  uint nrows;
  uint xoff, yoff;   // in reals
  int guard;
  uint rows_per;     // unused (layout fixes one row per invocation)
} pc;
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer RP { uint slice_ptr[]; };  // in chunks of 4
layout(std430, binding = 2) readonly buffer C { uvec4 col[]; };
layout(std430, binding = 3) readonly buffer V { REAL4 val[]; };
layout(std430, binding = 4) readonly buffer X { REAL x[]; };
layout(std430, binding = 5) writeonly buffer Y { REAL y[]; };
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint row = sessile_gid();
  if (row >= pc.nrows) return;
  uint sl = row >> 3u;
  uint k = slice_ptr[sl] + (row & 7u), e = slice_ptr[sl + 1u];
  REAL sum = REAL(0);
  for (; k < e; k += 8u) {
    uvec4 c = col[k] + uvec4(pc.xoff);
    REAL4 v = val[k];
    sum += v.x * x[c.x] + v.y * x[c.y] + v.z * x[c.z] + v.w * x[c.w];
  }
  y[pc.yoff + row] = sum;
}
