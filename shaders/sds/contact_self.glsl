// One surface cell per invocation (the surface cells' indices follow
// cell_surf in topo: their count, then the cells), after contact_list: the
// boundary faces not at the cell or a neighbour of it within delta + skin,
// appended to the cell's obstacle entries.  A dispatch of its own over the
// surface cells alone, so that no SIMD lane of an interior cell idles
// through the bucket loops (docs/sds.md, "Collisions").
#include "sds_common.glsl"
#include "sds_load.glsl"
#include "sds_contact.glsl"
#include "contact_keep.glsl"

// Is cell v the cell c or one of its neighbours (an edge of the complex)?
bool near_cell(uint c, uint v) {
  if (v == c) return true;
  uint oe = o_edge(), ce = o_ce();
  for (uint k = LD_TOPO(o_ceo() + c); k < LD_TOPO(o_ceo() + c + 1u); k++) {
    uint e = LD_TOPO(ce + k) >> 1u; // 2 e + side (kernels.def)
    if (LD_TOPO(oe + 2u * e) == v || LD_TOPO(oe + 2u * e + 1u) == v) return true;
  }
  return false;
}

void corner(uint q, out REAL a[3]) { a = REAL[3](LD_X(3u * q), LD_X(3u * q + 1u), LD_X(3u * q + 2u)); }
// Is p farther than d from grid cell (i, j, k)'s box (cell size h)?  The
// box is widened by 1e-9 h so that a centroid floor() put in the cell lies
// in it despite the rounding of g/h.
bool box_far(REAL p[3], int i, int j, int k, REAL h, REAL d) {
  int g[3] = int[3](i, j, k);
  REAL e = REAL(1e-9) * h, s = REAL(0);
  for (int a = 0; a < 3; a++) {
    REAL lo = REAL(g[a]) * h - e, hi = REAL(g[a] + 1) * h + e;
    REAL o = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : REAL(0));
    s += o * o;
  }
  return s > d * d;
}
// Boundary faces within reach of p through the surface hash: the buckets of
// the grid cells within reach + rho (rho: the largest face radius), each
// skipped when its grid cell lies farther from p than reach + the largest
// radius of the bucket's faces (brho; a bucket also holds the faces of the
// grid cells that collide with it, which the visit of their own cell finds:
// a face's centroid lies in its cell's box).
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
        REAL brho = REAL(uintBitsToFloat(LD_HASH(e0 + pc.nfaces + 1u + b)));
        if (box_far(p, gi, gj, gk, h, (reach + brho) * REAL(1.000000001))) continue;
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

void main() {
  uint i = sessile_gid(), s0 = o_csurf() + pc.ncells, c;
  if (pc.tsize == 0u) return;
  if (pc.lsub > 0u) { // a partial build: the surface cells among those the host listed
    if (i >= lmax[1]) return;
    c = lmax[2u + pc.lsub + i];
  } else {
    if (i >= LD_TOPO(s0)) return;
    c = LD_TOPO(s0 + 1u + i);
  }
  REAL p[3] = REAL[3](LD_X(3u * c), LD_X(3u * c + 1u), LD_X(3u * c + 2u));
  REAL reach = sp[SP_CONTACT] * R_OF(c) + sp[SP_SKIN];
  n_in = list[c]; // the obstacle's entries
  self_candidates(c, p, reach);
  list[c] = n_in;
  atomicMax(lmax[0], n_in);
}
