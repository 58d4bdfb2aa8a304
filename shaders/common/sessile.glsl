// Shared GLSL for sessile kernels: precision, workgroup size, indexing and
// compensated accumulation.  Kernels declared "real" in their kernels.def are
// built twice: SESSILE_F64=1 (REAL = double) and 0 (float).  Push blocks,
// bindings and constants shared with the host come from the generated
// <layer>_kernels.glsl (docs/design.md, "Declaring a kernel").
#ifndef SESSILE_GLSL
#ifndef SESSILE_F64
#define SESSILE_F64 1
#endif
#define SESSILE_GLSL

#if SESSILE_F64
#define REAL double
#define REAL2 dvec2
#define REAL4 dvec4
#else
#define REAL float
#define REAL2 vec2
#define REAL4 vec4
#endif

// Workgroup size is specialisation constant 0 (set by the host per device).
layout(local_size_x_id = 0) in;

// Linear invocation index; the host spreads large dispatches over y.
uint sessile_gid() {
  return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
}
uint sessile_group() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
// The dispatch's invocations: the stride of a loop over more items than them.
uint sessile_invocations() { return gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_WorkGroupSize.x; }

// Compensated accumulation: exact two-sum in fp32, plain sum in fp64.
void acc_add(inout REAL2 a, REAL x) {
#if SESSILE_F64
  a.x += x;
#else
  precise float s = a.x + x;
  precise float bp = s - a.x;
  precise float e = (a.x - (s - bp)) + (x - bp);
  a.x = s;
  a.y += e;
#endif
}
void acc_merge(inout REAL2 a, REAL2 b) {
  acc_add(a, b.x);
  a.y += b.y;
}
REAL acc_value(REAL2 a) { return a.x + a.y; }

// Finite test on the exponent bits: isnan/isinf may be folded away by a
// driver compiling with fast-math assumptions.
bool is_finite(REAL v) {
#if SESSILE_F64
  return (unpackDouble2x32(v).y & 0x7ff00000u) != 0x7ff00000u;
#else
  return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u;
#endif
}

#endif
