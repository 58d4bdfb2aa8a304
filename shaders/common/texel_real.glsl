// One real from a texel buffer of raw bits: RG32UI per double (fp64), R32UI
// per float (fp32); the `texel NAME real` bindings of kernels.def.
#ifndef TEXEL_REAL_GLSL
#define TEXEL_REAL_GLSL
REAL texel_real(usamplerBuffer t, uint i) {
#if SESSILE_F64
  return packDouble2x32(texelFetch(t, int(i)).xy);
#else
  return uintBitsToFloat(texelFetch(t, int(i)).x);
#endif
}
#endif
