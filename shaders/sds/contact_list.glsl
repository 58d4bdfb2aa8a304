// One cell per invocation: the first part of its contact candidates
// (docs/sds.md, "Collisions"), a Verlet list: every obstacle triangle within
// delta + skin of the cell (delta = contact_scale r); contact_self.glsl then
// appends, for a surface cell, every boundary face not at the cell or a
// neighbour of it within the same reach.  Until a cell or a
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
#include "contact_keep.glsl"

void obs_corner(uint q, out REAL a[3]) {
  uint w = 3u * pc.nattract + 3u * q;
  a = REAL[3](LD_WORLD(w), LD_WORLD(w + 1u), LD_WORLD(w + 2u));
}

// Obstacle triangles within reach of p through the obstacle's table.
void obstacle_candidates(uint c, REAL p[3], REAL reach) {
  uint T = pc.tsize_obs, o0 = 3u * pc.nobs, e0 = o0 + T + 1u;
  REAL h = sp[SP_H_OBS], far = (reach + sp[SP_RHO_OBS]) * REAL(1.000000001);
  int lo[3], hi[3];
  // clipped to the grid cells of the obstacle's centroids (the other
  // buckets of the box hold nothing of the obstacle but hash collisions):
  // a cell away from the rock visits no bucket
  for (int i = 0; i < 3; i++)
    lo[i] = max(grid_coord(p[i] - far, h), int(sp[SP_OBS_GLO + i])),
    hi[i] = min(grid_coord(p[i] + far, h), int(sp[SP_OBS_GHI + i]));
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
  if (pc.lsub > 0u) { // a partial build: the cells the host listed
    if (c >= pc.lsub) return;
    c = lmax[2u + c];
  } else if (c >= pc.ncells)
    return;
  REAL p[3] = REAL[3](LD_X(3u * c), LD_X(3u * c + 1u), LD_X(3u * c + 2u));
  for (int i = 0; i < 3; i++) xb[3u * c + uint(i)] = p[i];
  REAL delta = sp[SP_CONTACT] * R_OF(c);
  // the obstacle's force reaches 2 delta with adhesion (sessile_sds_obstacle_reach)
  REAL reach = (sp[SP_ADHESION] > REAL(0) ? REAL(2) * delta : delta) + sp[SP_SKIN];
  if (pc.nobs > 0u) obstacle_candidates(c, p, reach);
  list[c] = n_in;
  atomicMax(lmax[0], n_in); // the largest count (a maximum: order-free)
}
