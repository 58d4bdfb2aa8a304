// One workgroup, in a batch after step k's check (kernels.def,
// SDS_MORPH_BOUND): is the step's rules' work the device's?  Only for an
// accepted step that inverted no tet, with no division asked before in the
// batch (else SKIP: the host makes them).  Then the morphogens' explicit
// Euler bound min over cells and morphogens of 1 / (D sum_n 1/|c - n| + C),
// operation for operation as sessile_morph_dt_max (host/sds/morph.c: the
// sums in CSR order; a min is exact in any order), and the sub-step count of
// sds_rules (host/sds/sds_rules_step.c): n = ceil(dt / bound * (1 + 1e-9))
// when dt > bound, else 1.  Coinciding cells (the host's blow-up) or more
// sub-steps than the batch recorded: SKIP, and the host completes the step
// (the same bits: it is the host's own path).
#include "sds_kernels.glsl"
#include "group.glsl"
// Reads the positions and the neighbour lists through uniform texel buffers
// (MB_TEXEL = 1: vector loads on lavapipe, as sds_load.glsl) or storage
// buffers; the same bits.
#if MB_TEXEL
#include "texel_real.glsl"
#define LD_POS(i) texel_real(pos_t, (i))
#define LD_OFF(i) texelFetch(nbr_off_t, int(i)).x
#define LD_NBR(i) texelFetch(nbr_t, int(i)).x
#else
#define LD_POS(i) pos[i]
#define LD_OFF(i) nbr_off[i]
#define LD_NBR(i) nbr[i]
#endif

#ifndef SDS_PART_SHARED
#define SDS_PART_SHARED 1 // also stable_min.glsl's
shared REAL part[SDS_SCAN_MAX];
#endif
shared uint coincide;

// Cell c's smallest 1 / rate over the morphogens (-1: no positive rate);
// SDS_MB_COINCIDE when it coincides with a neighbour (the host's blow-up).
#define SDS_MB_COINCIDE REAL(-2)
REAL mb_cell(uint c) {
  REAL best = REAL(-1);
  bool co = false;
  precise REAL w = REAL(0);
  REAL cx = LD_POS(3u * c), cy = LD_POS(3u * c + 1u), cz = LD_POS(3u * c + 2u);
  for (uint q = LD_OFF(c); q < LD_OFF(c + 1u); q++) {
    uint n = LD_NBR(q);
    precise REAL dx = cx - LD_POS(3u * n), dy = cy - LD_POS(3u * n + 1u), dz = cz - LD_POS(3u * n + 2u);
    precise REAL d = sqrt(dx * dx + dy * dy + dz * dz);
    if (!(d > REAL(0))) co = true;
    w += REAL(1) / d;
  }
  for (uint m = 0u; m < pc.nmorph; m++) {
    precise REAL rate = coef[3u * m] * w + coef[3u * m + 1u];
    if (rate > REAL(0)) {
      precise REAL inv = REAL(1) / rate;
      if (best < REAL(0) || inv < best) best = inv;
    }
  }
  return co ? SDS_MB_COINCIDE : best;
}

// Lane l of L (one workgroup, every lane; or one subgroup) for the batch's
// step k.  With MB_RATES the cells' mb_cell values come from mrate (written
// by the wider dispatch before: step_check.comp), else they are made here.
void morph_bound_run(uint l, uint L, uint k) {
  bool mine = pev[1] == k + 1u && (pev[0] & SDS_EV_INVERTED) == 0u && rev[SDS_EV_STOP] == 0u;
  if (!mine) { // not accepted, or its inversions or an earlier division are the host's
    if (l == 0u) rev[SDS_EV_SKIP] = 1u;
    return;
  }
  if (l == 0u) coincide = 0u;
  GRP_BARRIER();
  // the smallest 1 / rate over this lane's cells (a min: exact in any
  // order); -1: no positive rate
  REAL best = REAL(-1);
  for (uint c = l; c < pc.ncells && pc.nmorph > 0u; c += L) {
#if MB_RATES
    REAL b = mrate[c];
#else
    REAL b = mb_cell(c);
#endif
    if (b == SDS_MB_COINCIDE) coincide = 1u; // any lane: the same value
    else if (b >= REAL(0) && (best < REAL(0) || b < best)) best = b;
  }
  part[l] = best;
  GRP_BARRIER();
  for (uint w = L / 2u; w > 0u; w /= 2u) {
    if (l < w && part[l + w] >= REAL(0) && (part[l] < REAL(0) || part[l + w] < part[l])) part[l] = part[l + w];
    GRP_BARRIER();
  }
  if (l != 0u) return;
  REAL dt = step[SDS_STEP_LOG + 2u * k], t = step[SDS_STEP_LOG + 2u * k + 1u], bound = part[0];
  REAL n = REAL(1);
  if (pc.nmorph == 0u) n = REAL(0); // no morphogens: no sub-steps
  else if (bound >= REAL(0) && dt > bound) {
    precise REAL q = dt / bound * pc.fudge;
    n = ceil(q);
  }
  if (coincide != 0u || (pc.nmorph > 0u && !(bound != REAL(0))) || n > REAL(pc.nsub_max)) {
    rev[SDS_EV_SKIP] = 1u;
    return;
  }
  rev[SDS_EV_SKIP] = 0u;
  precise REAL h = n > REAL(0) ? dt / n : dt;
  ctl[pc.ctl] = n, ctl[pc.ctl + 1u] = h, ctl[pc.ctl + 2u] = t, ctl[pc.ctl + 3u] = dt;
}

#ifndef MB_NO_MAIN
void main() { morph_bound_run(gl_LocalInvocationID.x, gl_WorkGroupSize.x, pc.batch - 1u); }
#endif
