// One explicit Euler step of the morphogens (Porter & McCormack §3.3):
//   lap = sum_n (min(n_phi, vol(c)) - min(c_phi, vol(n))) / |c_x - n_x|
//   out = clamp(phi + dt (D lap - C phi + src), 0, vol(c) or +inf)
// Operation for operation as sessile_morph_step (host/sds/morph.c); the
// neighbour sum runs in CSR order so every run gives the same bytes.
#include "sds_kernels.glsl"
// Reads through uniform texel buffers (MORPH_TEXEL = 1: vector loads on
// lavapipe, as shaders/sds/sds_load.glsl) or storage buffers; the same bits.
// MORPH_BATCH 1 (morph_step_batch.comp): the step and the sub-step count
// from a batch's control (ctl), the radii from the physics' rm (r, m).
// MORPH_FUSED (rules_morph.glsl): the first sub-step inside the rules'
// evaluation, which defines the loads, MORPH_CTL and MORPH_SKIPPED itself.
#ifndef MORPH_CTL
#define MORPH_CTL(i) ctl[pc.ctl + (i)]
#define MORPH_SKIPPED (rev[SDS_EV_SKIP] != 0u)
#define MORPH_SUB pc.sub
#endif
#if MORPH_BATCH
#define MORPH_DT MORPH_CTL(1u)
#else
#define MORPH_DT pc.dt
#endif
#if MORPH_FUSED
#elif MORPH_TEXEL
#include "texel_real.glsl"
#define LD_POS(i) texel_real(pos_t, (i))
#if MORPH_BATCH
#define LD_RADIUS(i) texel_real(radius_t, 2u * (i))
#else
#define LD_RADIUS(i) texel_real(radius_t, (i))
#endif
#define LD_OFF(i) texelFetch(nbr_off_t, int(i)).x
#define LD_NBR(i) texelFetch(nbr_t, int(i)).x
#define LD_PHI(i) texel_real(phi_in_t, (i))
#define LD_SRC(i) texel_real(src_t, (i))
#else
#define LD_POS(i) pos[i]
#if MORPH_BATCH
#define LD_RADIUS(i) radius[2u * (i)]
#else
#define LD_RADIUS(i) radius[i]
#endif
#define LD_OFF(i) nbr_off[i]
#define LD_NBR(i) nbr[i]
#define LD_PHI(i) phi_in[i]
#define LD_SRC(i) src[i]
#endif

#ifndef SDS_VOL_OF
#define SDS_VOL_OF 1 // also rules_vm.glsl's
REAL vol_of(REAL r) {
  precise REAL v = REAL(4.0lf / 3.0lf * 3.14159265358979311600lf) * r * r * r;
  return v;
}
#endif

// Morphogen k of cell c from its neighbour sum s.
void finish(uint c, uint k, REAL pk, REAL s, REAL vc) {
  uint i = c * pc.nmorph + k;
  precise REAL rate = coef[3u * k] * s - coef[3u * k + 1u] * pk;
  rate += LD_SRC(i);
  precise REAL v = pk + MORPH_DT * rate;
  v = max(v, REAL(0));
  if (coef[3u * k + 2u] != REAL(0)) v = min(v, vc);
  phi_out[i] = v;
}

// The sub-step at cell c (< ncells).
void morph_cell(uint c) {
  uint nm = pc.nmorph;
#if MORPH_BATCH
  if (MORPH_SKIPPED) return;                // the host makes this step's rules
  if (REAL(MORPH_SUB) > MORPH_CTL(0u)) {   // past the step's sub-steps: the amounts as they are
    for (uint k = 0u; k < nm; k++) phi_out[c * nm + k] = LD_PHI(c * nm + k);
    return;
  }
#endif
  REAL cx = LD_POS(3u * c), cy = LD_POS(3u * c + 1u), cz = LD_POS(3u * c + 2u);
  REAL vc = vol_of(LD_RADIUS(c));
  uint a = LD_OFF(c), b = LD_OFF(c + 1u);
  // two morphogens at a time, each its own sum over the neighbours in CSR
  // order (the host's order: the same bits), the distance and the
  // neighbour's volume read once for both; no per-morphogen arrays
  // (llvmpipe keeps a dynamically indexed local array in memory, lane by
  // lane)
  uint k = 0u;
  for (; k + 1u < nm; k += 2u) {
    REAL p0 = LD_PHI(c * nm + k), p1 = LD_PHI(c * nm + k + 1u);
    precise REAL s0 = REAL(0), s1 = REAL(0);
    for (uint q = a; q < b; q++) {
      uint n = LD_NBR(q);
      precise REAL dx = cx - LD_POS(3u * n), dy = cy - LD_POS(3u * n + 1u), dz = cz - LD_POS(3u * n + 2u);
      precise REAL d = sqrt(dx * dx + dy * dy + dz * dz);
      REAL vn = vol_of(LD_RADIUS(n));
      precise REAL t0 = min(LD_PHI(n * nm + k), vc) - min(p0, vn);
      precise REAL t1 = min(LD_PHI(n * nm + k + 1u), vc) - min(p1, vn);
      s0 += t0 / d;
      s1 += t1 / d;
    }
    finish(c, k, p0, s0, vc);
    finish(c, k + 1u, p1, s1, vc);
  }
  if (k < nm) {
    REAL pk = LD_PHI(c * nm + k);
    precise REAL s = REAL(0);
    for (uint q = a; q < b; q++) {
      uint n = LD_NBR(q);
      precise REAL dx = cx - LD_POS(3u * n), dy = cy - LD_POS(3u * n + 1u), dz = cz - LD_POS(3u * n + 2u);
      precise REAL d = sqrt(dx * dx + dy * dy + dz * dz);
      precise REAL t = min(LD_PHI(n * nm + k), vc) - min(pk, vol_of(LD_RADIUS(n)));
      s += t / d;
    }
    finish(c, k, pk, s, vc);
  }
}

#ifndef MORPH_NO_MAIN
void main() {
  uint c = sessile_gid();
  if (c < pc.ncells) morph_cell(c);
}
#endif
