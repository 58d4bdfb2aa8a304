// One tetrahedron per invocation: the forces of the volume spring
// E = k/2 ((V - R')/R')^2, R' = s_m R (Appendix A), k = k_vol (sum r/2)(sum m/2)
// (k = k_vol alone with uniform stiffness, sp[SP_UNIFORM] = 1, the damping's
// scale 1 too), times the surface multiplier on surface tets, on its 4 cells, and with
// damping the volume-rate term -c (sum r/2)(sum m/2) (dV/dt)/R'^2 grad V.
// In mode 2 it also writes each corner's terms of the stable bound
// (stable.glsl), k s/R'^2 |grad_k V| sum_j |grad_j V| with k = k_vol (times
// the surface multiplier) and with k = damp_vol, operation by operation as
// sessile_sds_stable_dt, so that the bound has the host's bits where the
// device rounds as the host does (precise: no fused multiply-adds).
// In a batch it also flags the tet when its input state is inverted
// (inverted.glsl's flag, one dispatch fewer a step).
// Mirrors tet_force in host/sds/sds_physics.c.
#include "sds_common.glsl"
#include "sds_load.glsl"

void tet_force_at(uint t) {
  if (t >= pc.ntets || (pc.batch != 0u && ev[0] != 0u)) return; // a batch that stopped
  uint q[4] = uint[4](LD_TOPO(4u * t), LD_TOPO(4u * t + 1u), LD_TOPO(4u * t + 2u), LD_TOPO(4u * t + 3u));
  REAL a[3], b[3], c[3], g[4][3];
  for (int i = 0; i < 3; i++) {
    a[i] = LD_X(3u * q[1] + i) - LD_X(3u * q[0] + i);
    b[i] = LD_X(3u * q[2] + i) - LD_X(3u * q[0] + i);
    c[i] = LD_X(3u * q[3] + i) - LD_X(3u * q[0] + i);
  }
  if (pc.batch != 0u && (pc.batch & SDS_BATCH_SPLIT) == 0u) { // a batch: the flags of this state, the last step's result (stable_min checks them)
    uint inv = tet_inverted(a, b, c);
    flag[t] = inv;
    if (inv != 0u) atomicOr(ev[2], 1u);
  }
  g[1][0] = b[1] * c[2] - b[2] * c[1], g[1][1] = b[2] * c[0] - b[0] * c[2], g[1][2] = b[0] * c[1] - b[1] * c[0];
  g[2][0] = c[1] * a[2] - c[2] * a[1], g[2][1] = c[2] * a[0] - c[0] * a[2], g[2][2] = c[0] * a[1] - c[1] * a[0];
  g[3][0] = a[1] * b[2] - a[2] * b[1], g[3][1] = a[2] * b[0] - a[0] * b[2], g[3][2] = a[0] * b[1] - a[1] * b[0];
  precise REAL gl[4];
  if (pc.mode == 2u) { // |grad_k V| from the unscaled cross products, as the host
    precise REAL g0[3];
    for (int i = 0; i < 3; i++) g0[i] = -(g[1][i] + g[2][i] + g[3][i]);
    gl[0] = sqrt(g0[0] * g0[0] + g0[1] * g0[1] + g0[2] * g0[2]) / REAL(6);
    for (int k = 1; k < 4; k++) gl[k] = sqrt(g[k][0] * g[k][0] + g[k][1] * g[k][1] + g[k][2] * g[k][2]) / REAL(6);
  }
  for (int i = 0; i < 3; i++) {
    g[1][i] /= REAL(6), g[2][i] /= REAL(6), g[3][i] /= REAL(6);
    g[0][i] = -(g[1][i] + g[2][i] + g[3][i]);
  }
  REAL V = a[0] * g[1][0] + a[1] * g[1][1] + a[2] * g[1][2];
  REAL R = LD_SM(t) * tet_rest(R_OF(q[0]), R_OF(q[1]), R_OF(q[2]), R_OF(q[3]));
  REAL rs = REAL(0), ms = REAL(0);
  for (int i = 0; i < 4; i++) rs += R_OF(q[i]), ms += M_OF(q[i]);
  REAL sc = sp[SP_UNIFORM] != REAL(0) ? REAL(1) : REAL(0.5) * rs * REAL(0.5) * ms;
  REAL coef = sp[SP_K_VOL] * (LD_TOPO(o_tsurf() + t) != 0u ? sp[SP_SURF] : REAL(1)) * sc * (V - R) / (R * R);
  if (pc.damping != 0u && sp[SP_DAMP_VOL] > REAL(0)) {
    REAL vdot = REAL(0);
    for (int k = 0; k < 4; k++)
      vdot += g[k][0] * LD_V(3u * q[k]) + g[k][1] * LD_V(3u * q[k] + 1u) + g[k][2] * LD_V(3u * q[k] + 2u);
    coef += sp[SP_DAMP_VOL] * sc * vdot / (R * R);
  }
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) elf[12u * t + 3u * k + i] = -coef * g[k][i];
  if (pc.mode == 2u) { // Gershgorin's row of the volume spring (sessile_sds_stable_dt)
    precise REAL gs = REAL(0);
    for (int k = 0; k < 4; k++) gs += gl[k];
    precise REAL s = sc / (R * R);
    precise REAL ks = sp[SP_K_VOL] * (LD_TOPO(o_tsurf() + t) != 0u ? sp[SP_SURF] : REAL(1)) * s, ds = sp[SP_DAMP_VOL] * s;
    uint o = 12u * pc.ntets + 3u * pc.nedges + 8u * t;
    for (int k = 0; k < 4; k++) {
      precise REAL wk = ks * gl[k] * gs, dk = ds * gl[k] * gs;
      elf[o + 2u * uint(k)] = wk, elf[o + 2u * uint(k) + 1u] = dk;
    }
  }
}

#ifndef SDS_ELEM_FUSED
void main() { tet_force_at(sessile_gid()); }
#endif
