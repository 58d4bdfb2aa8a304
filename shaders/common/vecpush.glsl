// Helpers of the element-wise vector kernels: their push block VecPush and
// scalar buffer s (binding 0) are declared in shaders/la/kernels.def.
bool guarded() { return pc.guard >= 0 && s[pc.guard] != REAL(0); }

REAL coef() {
  REAL a = pc.a_slot >= 0 ? s[pc.a_slot] : REAL(1);
  if ((pc.flags & COEF_INV) != 0u) a = REAL(1) / a;
  return (pc.flags & COEF_NEG) != 0u ? -a : a;
}
