#version 450
#extension GL_GOOGLE_include_directive : require
// One cell per invocation: the sum of the forces of its incident edges and
// tets (in CSR order, ascending element index: the same bytes every run),
// gravity, the box penalty, attraction, the obstacle and self contacts
// (docs/sds.md, "Collisions") and viscous damping;
// in mode 1 one semi-implicit Euler step (v += dt f/m, x += dt v) into
// x_out, v_out and the move |dt v| / r.  Mirrors sessile_sds_forces_ref and
// sessile_sds_step_ref (host/sds).
#include "sds_common.glsl"
#include "sds_contact.glsl"

// Is cell v the cell c or one of its neighbours (an edge of the complex)?
bool near_cell(uint c, uint v) {
  if (v == c) return true;
  uint oe = o_edge(), ce = o_ce();
  for (uint k = topo[o_ceo() + c]; k < topo[o_ceo() + c + 1u]; k++) {
    uint e = topo[ce + k];
    if (topo[oe + 2u * e] == v || topo[oe + 2u * e + 1u] == v) return true;
  }
  return false;
}

void corner(uint q, out REAL a[3]) { a = REAL[3](x[3u * q], x[3u * q + 1u], x[3u * q + 2u]); }
void obs_corner(uint q, out REAL a[3]) {
  uint w = 3u * pc.nattract + 3u * q;
  a = REAL[3](world[w], world[w + 1u], world[w + 2u]);
}

// The cell c at p against its nearest boundary face (not containing c or a
// neighbour of c) closer than delta, found through the surface hash: the
// buckets of the grid cells within delta + rho of p (rho: the largest face
// radius; a face within delta has its centroid within delta + rho).  Ties
// go to the lower face index, so the result does not depend on the order
// of the visit (the brute-force reference gets the same face).
void self_contact(uint c, REAL p[3], REAL delta, inout REAL acc[3]) {
  uint T = pc.tsize, e0 = 3u * T + 1u;
  REAL h = sp[SP_H_SELF], rho = REAL(uintBitsToFloat(hash[e0 + pc.nfaces]));
  REAL reach = (delta + rho) * REAL(1.000000001);
  int lo[3], hi[3];
  for (int i = 0; i < 3; i++) lo[i] = grid_coord(p[i] - reach, h), hi[i] = grid_coord(p[i] + reach, h);
  REAL best = delta * delta;
  uint bt = 0xffffffffu;
  // one flat loop over the (bucket, entry) pairs of the query box (measured
  // on lavapipe: 24 % less CPU in a limb run than three nested loops)
  uint nx = uint(hi[0] - lo[0] + 1), ny = uint(hi[1] - lo[1] + 1), nz = uint(hi[2] - lo[2] + 1);
  uint cellq = 0u, ncq = nx * ny * nz, k = 0u, kend = 0u;
  while (true) {
    if (k >= kend) {
      if (cellq >= ncq) break;
      int gi = lo[0] + int(cellq % nx), gj = lo[1] + int((cellq / nx) % ny), gk = lo[2] + int(cellq / (nx * ny));
      cellq++;
      uint b = grid_hash(gi, gj, gk, T);
      k = hash[T + b], kend = hash[T + b + 1u];
      continue;
    }
    {
      {
        { // (braces of the former nested loops kept: the body below is the obstacle's twin)
          uint t = hash[e0 + k], of = o_face() + 3u * t;
          k++;
          uint v0 = topo[of], v1 = topo[of + 1u], v2 = topo[of + 2u];
          if (v0 == c || v1 == c || v2 == c) continue; // its own faces: excluded, cheaply
          // quick rejection by the face's bounding sphere (conservative)
          REAL g0 = p[0] - fsph[4u * t], g1 = p[1] - fsph[4u * t + 1u], g2 = p[2] - fsph[4u * t + 2u];
          REAL rr = (delta + fsph[4u * t + 3u]) * REAL(1.000000001);
          if (g0 * g0 + g1 * g1 + g2 * g2 > rr * rr) continue;
          REAL a0[3], a1[3], a2[3];
          corner(v0, a0), corner(v1, a1), corner(v2, a2);
          REAL dd = tri_dist2(p, a0, a1, a2);
          if ((dd < best || (dd == best && t < bt && bt != 0xffffffffu)) && !near_cell(c, v0) && !near_cell(c, v1) &&
              !near_cell(c, v2))
            best = dd, bt = t;
        }
      }
    }
  }
  if (bt == 0xffffffffu) return;
  uint of = o_face() + 3u * bt;
  REAL a0[3], a1[3], a2[3];
  corner(topo[of], a0), corner(topo[of + 1u], a1), corner(topo[of + 2u], a2);
  REAL none[21];
  contact_add(p, a0, a1, a2, delta, sp[SP_K_CONTACT], false, none, acc);
}

// The cell at p against its nearest obstacle triangle closer than delta,
// through the obstacle's table (built once on the host: same layout),
// signed by the pseudo-normals (world, after the obstacle's vertices).
void obstacle_contact(REAL p[3], REAL delta, inout REAL acc[3]) {
  uint T = pc.tsize_obs, o0 = 3u * pc.nobs, e0 = o0 + T + 1u;
  REAL h = sp[SP_H_OBS], reach = (delta + sp[SP_RHO_OBS]) * REAL(1.000000001);
  int lo[3], hi[3];
  for (int i = 0; i < 3; i++) lo[i] = grid_coord(p[i] - reach, h), hi[i] = grid_coord(p[i] + reach, h);
  REAL best = delta * delta;
  uint bt = 0xffffffffu;
  for (int gi = lo[0]; gi <= hi[0]; gi++)
    for (int gj = lo[1]; gj <= hi[1]; gj++)
      for (int gk = lo[2]; gk <= hi[2]; gk++) {
        uint b = grid_hash(gi, gj, gk, T);
        for (uint k = obs_tri[o0 + b]; k < obs_tri[o0 + b + 1u]; k++) {
          uint t = obs_tri[e0 + k], sq = 3u * pc.nattract + 3u * pc.nobs_v + 21u * pc.nobs + 4u * t;
          REAL g0 = p[0] - world[sq], g1 = p[1] - world[sq + 1u], g2 = p[2] - world[sq + 2u];
          REAL rr = (delta + world[sq + 3u]) * REAL(1.000000001);
          if (g0 * g0 + g1 * g1 + g2 * g2 > rr * rr) continue;
          REAL a0[3], a1[3], a2[3];
          obs_corner(obs_tri[3u * t], a0), obs_corner(obs_tri[3u * t + 1u], a1), obs_corner(obs_tri[3u * t + 2u], a2);
          REAL dd = tri_dist2(p, a0, a1, a2);
          if (dd < best || (dd == best && t < bt && bt != 0xffffffffu)) best = dd, bt = t;
        }
      }
  if (bt == 0xffffffffu) return;
  REAL a0[3], a1[3], a2[3];
  obs_corner(obs_tri[3u * bt], a0), obs_corner(obs_tri[3u * bt + 1u], a1), obs_corner(obs_tri[3u * bt + 2u], a2);
  REAL nrm[21];
  uint n0 = 3u * pc.nattract + 3u * pc.nobs_v + 21u * bt;
  for (int i = 0; i < 21; i++) nrm[i] = world[n0 + uint(i)];
  contact_add(p, a0, a1, a2, delta, sp[SP_K_WALL], true, nrm, acc);
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
  int at = attract[c];
  if (at >= 0 && uint(at) < pc.nattract) {
    REAL d[3];
    for (int i = 0; i < 3; i++) d[i] = world[3u * uint(at) + i] - p[i];
    REAL l = sqrt(dot3(d, d));
    if (l > REAL(0))
      for (int i = 0; i < 3; i++) acc[i] += sp[SP_K_ATTRACT] * d[i] / l;
  }
  REAL delta = sp[SP_CONTACT] * R_OF(c);
  if (pc.nobs > 0u) obstacle_contact(p, delta, acc);
  if (pc.tsize > 0u && topo[o_csurf() + c] != 0u) self_contact(c, p, delta, acc);
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
