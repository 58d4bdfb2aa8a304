#version 450
#extension GL_GOOGLE_include_directive : require
// One cell per invocation: the sum of the forces of its incident edges and
// tets (in CSR order, ascending element index: the same bytes every run),
// gravity, the box and obstacle penalties, attraction and viscous damping;
// in mode 1 one semi-implicit Euler step (v += dt f/m, x += dt v) into
// x_out, v_out and the move |dt v| / r.  Mirrors sessile_sds_forces_ref and
// sessile_sds_step_ref (host/sds).
#include "sds_common.glsl"

REAL dot3(REAL a[3], REAL b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Closest point to p on triangle (a, b, c) (Ericson §5.1.5), as closest_on_tri.
void closest_on_tri(REAL p[3], REAL a[3], REAL b[3], REAL c[3], out REAL q[3]) {
  REAL ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  REAL d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= REAL(0) && d2 <= REAL(0)) { q = a; return; }
  for (int i = 0; i < 3; i++) bp[i] = p[i] - b[i];
  REAL d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= REAL(0) && d4 <= d3) { q = b; return; }
  REAL vc = d1 * d4 - d3 * d2;
  if (vc <= REAL(0) && d1 >= REAL(0) && d3 <= REAL(0)) {
    REAL v = d1 / (d1 - d3);
    for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i];
    return;
  }
  for (int i = 0; i < 3; i++) cp[i] = p[i] - c[i];
  REAL d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= REAL(0) && d5 <= d6) { q = c; return; }
  REAL vb = d5 * d2 - d1 * d6;
  if (vb <= REAL(0) && d2 >= REAL(0) && d6 <= REAL(0)) {
    REAL w = d2 / (d2 - d6);
    for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i];
    return;
  }
  REAL va = d3 * d6 - d5 * d4;
  if (va <= REAL(0) && (d4 - d3) >= REAL(0) && (d5 - d6) >= REAL(0)) {
    REAL w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]);
    return;
  }
  REAL den = REAL(1) / (va + vb + vc), v = vb * den, w = vc * den;
  for (int i = 0; i < 3; i++) q[i] = a[i] + ab[i] * v + ac[i] * w;
}

// Inside the obstacle (winding number by solid angles, in float: GLSL has no
// double atan; only its sign at 1/2 matters)?  q: the nearest surface point.
bool obstacle_inside(REAL p[3], out REAL q[3]) {
  float wind = 0.0;
  REAL best = REAL(-1);
  q = p;
  for (uint f = 0u; f < pc.nobs; f++) {
    REAL p0[3], p1[3], p2[3], a[3], b[3], c[3], y[3];
    for (int i = 0; i < 3; i++) {
      p0[i] = world[3u * pc.nattract + 3u * obs_tri[3u * f] + i];
      p1[i] = world[3u * pc.nattract + 3u * obs_tri[3u * f + 1u] + i];
      p2[i] = world[3u * pc.nattract + 3u * obs_tri[3u * f + 2u] + i];
      a[i] = p0[i] - p[i], b[i] = p1[i] - p[i], c[i] = p2[i] - p[i];
    }
    REAL la = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b)), lc = sqrt(dot3(c, c));
    REAL n[3] = REAL[3](b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]);
    REAL num = dot3(a, n), den = la * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la;
    wind += 2.0 * atan(float(num), float(den));
    closest_on_tri(p, p0, p1, p2, y);
    REAL d[3] = REAL[3](p[0] - y[0], p[1] - y[1], p[2] - y[2]);
    REAL dd = dot3(d, d);
    if (best < REAL(0) || dd < best) best = dd, q = y;
  }
  return wind > 6.2831853;
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  REAL s[3] = REAL[3](REAL(0), REAL(0), REAL(0));
  uint ce = o_ce(), ct = o_ct(), oe = o_edge(), ceo = o_ceo(), cto = o_cto(), efo = 12u * pc.ntets;
  for (uint k = topo[ceo + c]; k < topo[ceo + c + 1u]; k++) {
    uint e = topo[ce + k];
    REAL sg = topo[oe + 2u * e + 1u] == c ? REAL(1) : REAL(-1);
    for (int i = 0; i < 3; i++) s[i] += sg * elf[efo + 3u * e + i];
  }
  for (uint k = topo[cto + c]; k < topo[cto + c + 1u]; k++) {
    uint t = topo[ct + k];
    uint j = 0u;
    while (topo[4u * t + j] != c) j++;
    for (int i = 0; i < 3; i++) s[i] += elf[12u * t + 3u * j + i];
  }
  REAL p[3] = REAL[3](x[3u * c], x[3u * c + 1u], x[3u * c + 2u]);
  REAL acc[3] = REAL[3](REAL(0), REAL(0), -sp[SP_GRAVITY]);
  if (pc.box != 0u)
    for (int i = 0; i < 3; i++) {
      if (p[i] < sp[SP_LO + i]) acc[i] += sp[SP_K_WALL] * (sp[SP_LO + i] - p[i]);
      if (p[i] > sp[SP_HI + i]) acc[i] -= sp[SP_K_WALL] * (p[i] - sp[SP_HI + i]);
    }
  REAL q[3];
  if (pc.nobs > 0u && obstacle_inside(p, q))
    for (int i = 0; i < 3; i++) acc[i] += sp[SP_K_WALL] * (q[i] - p[i]);
  int at = attract[c];
  if (at >= 0 && uint(at) < pc.nattract) {
    REAL d[3];
    for (int i = 0; i < 3; i++) d[i] = world[3u * uint(at) + i] - p[i];
    REAL l = sqrt(dot3(d, d));
    if (l > REAL(0))
      for (int i = 0; i < 3; i++) acc[i] += sp[SP_K_ATTRACT] * d[i] / l;
  }
  REAL mc = M_OF(c);
  for (int i = 0; i < 3; i++) {
    s[i] += mc * acc[i];
    if (pc.damping != 0u) s[i] -= sp[SP_DAMP_VISC] * mc * v[3u * c + i];
    f[3u * c + i] = s[i];
  }
  if (pc.mode == 1u) {
    REAL d2 = REAL(0);
    for (int i = 0; i < 3; i++) {
      REAL vn = v[3u * c + i] + pc.dt * s[i] / mc;
      REAL dx = pc.dt * vn;
      v_out[3u * c + i] = vn;
      x_out[3u * c + i] = p[i] + dx;
      d2 += dx * dx;
    }
    move[c] = sqrt(d2) / R_OF(c);
  }
}
