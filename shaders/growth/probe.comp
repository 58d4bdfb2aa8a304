#version 450
#extension GL_GOOGLE_include_directive : require
// What a vertex takes up (docs/model.md, "Probe"):
//  flux (default): the nutrient's normal derivative at the surface, where
//    c = 0, from two samples on the water side at fixed distances delta and
//    2 delta along the unit normal: dc/dn = (4 c(delta) - c(2 delta)) / (2 delta)
//    (second order), divided by the bare substratum's flux so that C is of
//    order 1; never negative (a vertex does not give nutrient back).  The
//    field is the cut-cell solution extended across the surface (ghost.comp),
//    read by trilinear interpolation (second order in cut cells too; the
//    Kuhn P1 interpolant's diagonal bias made vertices of one ring of the
//    symmetric dome read up to 17 % apart at resolution 2, trilinear 3 %).
//  paper (eq 6): probed = (1/S) sum_k w(d_k) c(x + d_k offset N), d_k = k/(S-1),
//    w(d) = 1/(20 d + 1).
// paper: c is the P1 interpolant on the box (location mirrors sessile_box_locate).
#include "growth_common.glsl"

// The trilinear interpolant of field at p, as sessile_box_trilinear (same
// order of operations).
REAL box_trilinear(REAL p[3]) {
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
  REAL o[3] = REAL[3](gp[P_OX], gp[P_OY], gp[P_OZ]);
  uint c[3];
  REAL u[3];
  for (int a = 0; a < 3; a++) {
    precise REAL x = (p[a] - o[a]) / gp[P_H];
    REAL cells = REAL(n[a] - 1u);
    if (!(x > REAL(0))) x = REAL(0);
    if (x > cells) x = cells;
    REAL f = floor(x);
    if (f > cells - REAL(1)) f = cells - REAL(1);
    c[a] = uint(f);
    u[a] = x - f;
  }
  precise REAL sum = REAL(0);
  for (uint k = 0u; k < 2u; k++)
    for (uint j = 0u; j < 2u; j++)
      for (uint i = 0u; i < 2u; i++) {
        precise REAL w = (i != 0u ? u[0] : REAL(1) - u[0]) * (j != 0u ? u[1] : REAL(1) - u[1]);
        w = w * (k != 0u ? u[2] : REAL(1) - u[2]);
        sum += w * field[(c[0] + i) + pc.n0 * ((c[1] + j) + pc.n1 * (c[2] + k))];
      }
  return sum;
}

REAL field_tri(uint v, REAL s) {
  REAL p[3];
  for (uint a = 0u; a < 3u; a++) {
    precise REAL t = s * nrm[3u * v + a];
    p[a] = pos[3u * v + a] + t;
  }
  return box_trilinear(p);
}

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
    REAL c1 = field_tri(v, d);
    REAL c2 = field_tri(v, REAL(2) * d);
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
