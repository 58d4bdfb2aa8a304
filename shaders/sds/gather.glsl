// One cell per invocation: the sum of the forces of its incident edges and
// tets (in CSR order, ascending element index: the same bytes every run),
// gravity, the box penalty, attraction, the obstacle (its penalty and
// adhesion) and self contacts among the cell's contact list (docs/sds.md,
// "Collisions") and viscous damping;
// in mode 1 one semi-implicit Euler step (v += dt f/m, x += dt v) into
// x_out, v_out and the move |dt v| / r (the obstacle's friction implicit
// in it); in mode 2 the same step with the dt
// that stable_min capped (stab[n]).  Mirrors sessile_sds_forces_ref and
// sessile_sds_step_ref (host/sds).
#include "sds_common.glsl"
#include "sds_load.glsl"
#include "sds_contact.glsl"

void corner(uint q, out REAL a[3]) { a = REAL[3](LD_X(3u * q), LD_X(3u * q + 1u), LD_X(3u * q + 2u)); }
void obs_corner(uint q, out REAL a[3]) {
  uint w = 3u * pc.nattract + 3u * q;
  a = REAL[3](LD_WORLD(w), LD_WORLD(w + 1u), LD_WORLD(w + 2u));
}

// The cell c at p against its nearest triangles closer than delta among its
// contact candidates (contact_list.comp: every triangle that can be within
// delta until the list is rebuilt): the obstacle's, signed by its
// pseudo-normals, within 2 delta with adhesion, and the surface's (not at c
// or a neighbour).  The nearest wins, ties to the lower index: the triangle
// a query of every triangle finds (sessile_sds_contact_brute).  fr: the
// obstacle's friction acts on the cell, along its unit normal fn.
void contacts(uint c, REAL p[3], REAL delta, inout REAL acc[3], out bool fr, out REAL fn[3]) {
  REAL ro = sp[SP_ADHESION] > REAL(0) ? REAL(2) * delta : delta; // sessile_sds_obstacle_reach
  REAL best = delta * delta, best_o = ro * ro;
  fr = false;
  uint bt = 0xffffffffu, bo = 0xffffffffu, base = pc.lbase + c * pc.lcap, n = LD_LIST(c);
  for (uint k = 0u; k < n; k++) {
    uint e = LD_LIST(base + k), t = e & ~SDS_LIST_OBS;
    bool obs = (e & SDS_LIST_OBS) != 0u;
    REAL a0[3], a1[3], a2[3];
    if (obs) {
      obs_corner(LD_OBS(3u * t), a0), obs_corner(LD_OBS(3u * t + 1u), a1), obs_corner(LD_OBS(3u * t + 2u), a2);
    } else {
      uint of = o_face() + 3u * t;
      corner(LD_TOPO(of), a0), corner(LD_TOPO(of + 1u), a1), corner(LD_TOPO(of + 2u), a2);
    }
    REAL dd = tri_dist2(p, a0, a1, a2);
    if (obs) {
      if (dd < best_o || (dd == best_o && t < bo && bo != 0xffffffffu)) best_o = dd, bo = t;
    } else if (dd < best || (dd == best && t < bt && bt != 0xffffffffu))
      best = dd, bt = t;
  }
  REAL a0[3], a1[3], a2[3];
  if (bo != 0xffffffffu) {
    obs_corner(LD_OBS(3u * bo), a0), obs_corner(LD_OBS(3u * bo + 1u), a1), obs_corner(LD_OBS(3u * bo + 2u), a2);
    REAL nrm[21];
    uint n0 = 3u * pc.nattract + 3u * pc.nobs_v + 21u * bo;
    for (int i = 0; i < 21; i++) nrm[i] = LD_WORLD(n0 + uint(i));
    REAL w[3];
    REAL s = contact_geom(p, a0, a1, a2, true, nrm, w);
    if (s < delta)
      for (int i = 0; i < 3; i++) acc[i] += sp[SP_K_WALL] * (delta - s) * w[i];
    else if (sp[SP_ADHESION] > REAL(0)) { // a tent of height A over delta <= s <= 2 delta
      REAL e = s - delta, a = sp[SP_ADHESION], pull;
      if (e < REAL(0.5) * delta) pull = REAL(2) * a * e / delta;
      else {
        REAL g = delta - e > REAL(0) ? delta - e : REAL(0);
        pull = REAL(2) * a * g / delta;
      }
      for (int i = 0; i < 3; i++) acc[i] -= pull * w[i];
    }
    if (sp[SP_FRICTION] > REAL(0)) fr = true, fn = w;
  }
  if (bt != 0xffffffffu) {
    uint of = o_face() + 3u * bt;
    corner(LD_TOPO(of), a0), corner(LD_TOPO(of + 1u), a1), corner(LD_TOPO(of + 2u), a2);
    REAL none[21];
    contact_add(p, a0, a1, a2, delta, sp[SP_K_CONTACT], false, none, acc);
  }
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  if (pc.batch != 0u && !(stab[pc.ncells] > REAL(0))) return; // a batch that stopped (stable_min)
  REAL s[3] = REAL[3](REAL(0), REAL(0), REAL(0));
  uint ce = o_ce(), ct = o_ct(), ceo = o_ceo(), cto = o_cto(), efo = 12u * pc.ntets;
  if (pc.mode == 2u) // stable.glsl summed the elements already, in this order
    for (int i = 0; i < 3; i++) s[i] = stab[pc.ncells + 3u + 3u * c + i];
  else for (uint k = LD_TOPO(ceo + c); k < LD_TOPO(ceo + c + 1u); k++) {
    uint w = LD_TOPO(ce + k), e = w >> 1u; // 2 e + 1 where c is the edge's second cell
    REAL sg = (w & 1u) != 0u ? REAL(1) : REAL(-1);
    for (int i = 0; i < 3; i++) s[i] += sg * LD_ELF(efo + 3u * e + i);
  }
  if (pc.mode != 2u) for (uint k = LD_TOPO(cto + c); k < LD_TOPO(cto + c + 1u); k++) {
    uint w = LD_TOPO(ct + k), t = w >> 2u, j = w & 3u; // 4 t + c's corner
    for (int i = 0; i < 3; i++) s[i] += LD_ELF(12u * t + 3u * j + i);
  }
  REAL p[3] = REAL[3](LD_X(3u * c), LD_X(3u * c + 1u), LD_X(3u * c + 2u));
  REAL acc[3] = REAL[3](REAL(0), REAL(0), -sp[SP_GRAVITY]);
  if (pc.box != 0u)
    for (int i = 0; i < 3; i++) {
      if (p[i] < sp[SP_LO + i]) acc[i] += sp[SP_K_WALL] * (sp[SP_LO + i] - p[i]);
      if (p[i] > sp[SP_HI + i]) acc[i] -= sp[SP_K_WALL] * (p[i] - sp[SP_HI + i]);
    }
  int at = attract[c];
  if (at >= 0 && uint(at) < pc.nattract) {
    REAL d[3];
    for (int i = 0; i < 3; i++) d[i] = LD_WORLD(3u * uint(at) + i) - p[i];
    REAL l = sqrt(dot3(d, d));
    if (l > REAL(0))
      for (int i = 0; i < 3; i++) acc[i] += sp[SP_K_ATTRACT] * d[i] / l;
  }
  REAL delta = sp[SP_CONTACT] * R_OF(c);
  bool fr = false;
  REAL fn[3];
  if (pc.lcap > 0u) contacts(c, p, delta, acc, fr, fn);
  REAL mc = M_OF(c);
  for (int i = 0; i < 3; i++) {
    s[i] += mc * acc[i];
    if (pc.damping != 0u) s[i] -= sp[SP_DAMP_VISC] * mc * LD_V(3u * c + i);
    f[3u * c + i] = s[i];
  }
  if (pc.mode != 0u) {
    REAL dt = pc.mode == 2u ? stab[pc.ncells] : pc.dt;
    REAL d2 = REAL(0), vq[3];
    // mode 2: the inertia of mass scaling (stable.glsl; exactly mc where it is 1)
    REAL mi = pc.mode == 2u ? mc * stab[4u * pc.ncells + 3u + c] : mc;
    for (int i = 0; i < 3; i++) vq[i] = LD_V(3u * c + i) + dt * s[i] / mi;
    if (fr) { // the obstacle's friction, backward Euler on -friction v_t (as sessile_sds_step_ref)
      REAL vn = vq[0] * fn[0] + vq[1] * fn[1] + vq[2] * fn[2];
      for (int i = 0; i < 3; i++) vq[i] = vn * fn[i] + (vq[i] - vn * fn[i]) / (REAL(1) + dt * sp[SP_FRICTION]);
    }
    for (int i = 0; i < 3; i++) {
      REAL vn = vq[i];
      REAL dx = dt * vn;
      v_out[3u * c + i] = vn;
      x_out[3u * c + i] = p[i] + dx;
      d2 += dx * dx;
    }
    move[c] = sqrt(d2) / R_OF(c);
    if (pc.lcap > 0u) { // how far the cell is from where its contact list was built
      REAL e2 = REAL(0);
      for (int i = 0; i < 3; i++) {
        REAL d = p[i] + dt * vq[i] - xb[3u * c + i]; // x_out, as above
        e2 += d * d;
      }
      move[pc.ncells + c] = sqrt(e2);
    }
  }
}
