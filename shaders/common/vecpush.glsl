// Push constants and scalar buffer shared by the element-wise vector kernels.
// Vectors are REAL4 arrays padded with zeros to a multiple of 4 reals;
// off0..off2 are offsets, in REAL4, of the vectors bound at 1..3 (GMRES keeps
// its whole basis in one buffer).
layout(push_constant) uniform VecPush {
  uint n4;      // REAL4 chunks to process
  uint n;       // reals (tail chunk is masked against n)
  uint off0, off1, off2;
  int a_slot;   // coefficient = s[a_slot] (or 1 when < 0)
  uint flags;   // bit 0: negate the coefficient; bit 1: use 1/coefficient
  int guard;    // skip everything when s[guard] != 0 (< 0: never)
} pc;

layout(std430, binding = 0) buffer Scalars { REAL s[]; };

bool guarded() { return pc.guard >= 0 && s[pc.guard] != REAL(0); }

REAL coef() {
  REAL a = pc.a_slot >= 0 ? s[pc.a_slot] : REAL(1);
  if ((pc.flags & 2u) != 0u) a = REAL(1) / a;
  return (pc.flags & 1u) != 0u ? -a : a;
}
