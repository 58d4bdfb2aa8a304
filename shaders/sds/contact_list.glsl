// One cell per invocation: its contact candidates (docs/sds.md,
// "Collisions"), a Verlet list: every obstacle triangle, and for a surface
// cell every boundary face not at the cell or a neighbour of it, within
// delta + skin of the cell (delta = contact_scale r).  Until a cell or a
// face corner has moved skin / 2 (or the radii have grown by as much) no
// other triangle can come within delta, so the gather finds each step's
// nearest triangle in the list alone: the same triangle, the same bytes, as
// a query of the whole surface every step.  The list's order is the hash's
// visit order; the gather's choice does not depend on it (ties go to the
// lower index).  Also keeps the positions the list was built at (xb).
// Mirrors nothing on the host: the reference is the brute force.
#include "sds_common.glsl"
#include "sds_load.glsl"
#include "sds_contact.glsl"

// Is cell v the cell c or one of its neighbours (an edge of the complex)?
bool near_cell(uint c, uint v) {
  if (v == c) return true;
  uint oe = o_edge(), ce = o_ce();
  for (uint k = LD_TOPO(o_ceo() + c); k < LD_TOPO(o_ceo() + c + 1u); k++) {
    uint e = LD_TOPO(ce + k);
    if (LD_TOPO(oe + 2u * e) == v || LD_TOPO(oe + 2u * e + 1u) == v) return true;
  }
  return false;
}

void corner(uint q, out REAL a[3]) { a = REAL[3](LD_X(3u * q), LD_X(3u * q + 1u), LD_X(3u * q + 2u)); }
void obs_corner(uint q, out REAL a[3]) {
  uint w = 3u * pc.nattract + 3u * q;
  a = REAL[3](LD_WORLD(w), LD_WORLD(w + 1u), LD_WORLD(w + 2u));
}

uint n_in = 0u; // candidates found (may exceed the list's capacity: the host grows it and builds again)
void keep(uint c, uint entry) {
  if (n_in < pc.lcap) list[pc.ncells + c * pc.lcap + n_in] = entry;
  n_in++;
}

// Boundary faces within reach of p through the surface hash: the buckets of
// the grid cells within reach + rho (rho: the largest face radius).
void self_candidates(uint c, REAL p[3], REAL reach) {
  uint T = pc.tsize, e0 = 3u * T + 1u;
  REAL h = sp[SP_H_SELF], rho = REAL(uintBitsToFloat(LD_HASH(e0 + pc.nfaces)));
  REAL far = (reach + rho) * REAL(1.000000001);
  int lo[3], hi[3];
  for (int i = 0; i < 3; i++) lo[i] = grid_coord(p[i] - far, h), hi[i] = grid_coord(p[i] + far, h);
  for (int gi = lo[0]; gi <= hi[0]; gi++)
    for (int gj = lo[1]; gj <= hi[1]; gj++)
      for (int gk = lo[2]; gk <= hi[2]; gk++) {
        uint b = grid_hash(gi, gj, gk, T);
        for (uint k = LD_HASH(T + b); k < LD_HASH(T + b + 1u); k++) {
          uint t = LD_HASH(e0 + k), of = o_face() + 3u * t;
          uint v0 = LD_TOPO(of), v1 = LD_TOPO(of + 1u), v2 = LD_TOPO(of + 2u);
          if (v0 == c || v1 == c || v2 == c) continue; // its own faces
          REAL g0 = p[0] - LD_FSPH(4u * t), g1 = p[1] - LD_FSPH(4u * t + 1u), g2 = p[2] - LD_FSPH(4u * t + 2u);
          REAL rr = (reach + LD_FSPH(4u * t + 3u)) * REAL(1.000000001);
          if (g0 * g0 + g1 * g1 + g2 * g2 > rr * rr) continue;
          REAL a0[3], a1[3], a2[3];
          corner(v0, a0), corner(v1, a1), corner(v2, a2);
          if (tri_dist2(p, a0, a1, a2) <= reach * reach && !near_cell(c, v0) && !near_cell(c, v1) &&
              !near_cell(c, v2))
            keep(c, t);
        }
      }
}

// Obstacle triangles within reach of p through the obstacle's table.
void obstacle_candidates(uint c, REAL p[3], REAL reach) {
  uint T = pc.tsize_obs, o0 = 3u * pc.nobs, e0 = o0 + T + 1u;
  REAL h = sp[SP_H_OBS], far = (reach + sp[SP_RHO_OBS]) * REAL(1.000000001);
  int lo[3], hi[3];
  for (int i = 0; i < 3; i++) lo[i] = grid_coord(p[i] - far, h), hi[i] = grid_coord(p[i] + far, h);
  for (int gi = lo[0]; gi <= hi[0]; gi++)
    for (int gj = lo[1]; gj <= hi[1]; gj++)
      for (int gk = lo[2]; gk <= hi[2]; gk++) {
        uint b = grid_hash(gi, gj, gk, T);
        for (uint k = LD_OBS(o0 + b); k < LD_OBS(o0 + b + 1u); k++) {
          uint t = LD_OBS(e0 + k), sq = 3u * pc.nattract + 3u * pc.nobs_v + 21u * pc.nobs + 4u * t;
          REAL g0 = p[0] - LD_WORLD(sq), g1 = p[1] - LD_WORLD(sq + 1u), g2 = p[2] - LD_WORLD(sq + 2u);
          REAL rr = (reach + LD_WORLD(sq + 3u)) * REAL(1.000000001);
          if (g0 * g0 + g1 * g1 + g2 * g2 > rr * rr) continue;
          REAL a0[3], a1[3], a2[3];
          obs_corner(LD_OBS(3u * t), a0), obs_corner(LD_OBS(3u * t + 1u), a1), obs_corner(LD_OBS(3u * t + 2u), a2);
          if (tri_dist2(p, a0, a1, a2) <= reach * reach) keep(c, t | SDS_LIST_OBS);
        }
      }
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  REAL p[3] = REAL[3](LD_X(3u * c), LD_X(3u * c + 1u), LD_X(3u * c + 2u));
  for (int i = 0; i < 3; i++) xb[3u * c + uint(i)] = p[i];
  REAL reach = sp[SP_CONTACT] * R_OF(c) + sp[SP_SKIN];
  if (pc.nobs > 0u) obstacle_candidates(c, p, reach);
  if (pc.tsize > 0u && LD_TOPO(o_csurf() + c) != 0u) self_candidates(c, p, reach);
  list[c] = n_in;
  atomicMax(lmax[0], n_in); // the largest count (a maximum: order-free)
}
