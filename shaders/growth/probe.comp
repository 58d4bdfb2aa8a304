#version 450
#extension GL_GOOGLE_include_directive : require
// What a vertex takes up (docs/model.md, "Probe"):
//  flux (default): the nutrient's normal derivative at the surface, where
//    c = 0, from two samples on the water side at fixed distances delta and
//    2 delta along the unit normal: dc/dn = (4 c(delta) - c(2 delta)) / (2 delta)
//    (second order), divided by the bare substratum's flux so that C is of
//    order 1; never negative (a vertex does not give nutrient back).  The
//    field is the cut-cell solution extended across the surface (ghost.comp),
//    so P1 interpolation stays second order in cut cells.
//  paper (eq 6): probed = (1/S) sum_k w(d_k) c(x + d_k offset N), d_k = k/(S-1),
//    w(d) = 1/(20 d + 1).
// c is the P1 interpolant on the box (point location mirrors sessile_box_locate).
#include "growth_common.glsl"

REAL field_at(uint v, REAL s) {
  REAL p[3];
  for (uint a = 0u; a < 3u; a++) {
    precise REAL t = s * nrm[3u * v + a];
    p[a] = pos[3u * v + a] + t;
  }
  uint nd[4];
  REAL w[4];
  box_locate(p, nd, w);
  precise REAL c = w[0] * field[nd[0]] + w[1] * field[nd[1]];
  c = c + w[2] * field[nd[2]];
  c = c + w[3] * field[nd[3]];
  return c;
}

void main() {
  uint v = sessile_gid();
  if (v >= pc.nv) return;
  if (pc.probe_flux != 0u) {
    REAL d = gp[P_DELTA];
    REAL c1 = field_at(v, d);
    REAL c2 = field_at(v, REAL(2) * d);
    precise REAL num = REAL(4) * c1 - c2;
    precise REAL flux = num / (REAL(2) * d);
    probed[v] = max(flux / gp[P_FLUXREF], REAL(0));
    return;
  }
  precise REAL sum = REAL(0);
  for (uint k = 0u; k < pc.samples; k++) {
    precise REAL d = REAL(k) / REAL(pc.samples - 1u);
    precise REAL s = d * gp[P_OFFSET];
    REAL c = field_at(v, s);
    precise REAL att = REAL(1) / (REAL(20) * d + REAL(1));
    sum += att * c;
  }
  probed[v] = sum / REAL(pc.samples);
}
