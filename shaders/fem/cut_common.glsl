// Shared by cutcell.comp and ghost.comp: node coordinates and the boundary
// classification of the cut-cell nutrient (docs/nutrient.md).  Mirrored by
// host/fem/nutrient_cut_ref.c.
#ifndef CUT_COMMON_GLSL
#define CUT_COMMON_GLSL
#include "fem_kernels.glsl"

void cut_ijk(uint node, out uint c[3]) {
  c[0] = node % pc.n0;
  uint t = node / pc.n0;
  c[1] = t % pc.n1;
  c[2] = t / pc.n1;
}

// Height of node layer k above the substratum.
REAL cut_z(uint k) { return pc.h * REAL(k); }

// The Dirichlet nodes that are not the sponge: the substratum (c = 0), and
// the far field (c = 1): the layers at or above the far-field height, or
// every other wall; FAR_PROFILE's inflow wall x = 0 carries the bare
// substratum's profile z / height (the water the current brings, undisturbed
// by the sponge).  Returns 1 and the value for them.
bool cut_node_dirichlet(uint c[3], out REAL value) {
  value = REAL(0);
  if (c[2] == 0u) return true;
  if (pc.far_field == FAR_WALLS) {
    bool wall = c[0] == 0u || c[1] == 0u || c[0] == pc.n0 - 1u || c[1] == pc.n1 - 1u ||
                c[2] == pc.n2 - 1u;
    value = REAL(1);
    return wall;
  }
  value = REAL(1);
  if (pc.far_field == FAR_INLET && c[0] == 0u) return true; // fresh water through the inlet
  if (pc.far_field == FAR_PROFILE && c[0] == 0u) {
    value = min(cut_z(c[2]) / pc.height, REAL(1));
    return true;
  }
  // a layer within 1e-9 h of the plane is on it (28.8 is not 24 x 1.2 in binary)
  return !(cut_z(c[2]) < pc.height - REAL(1e-9) * pc.h);
}

// The face fraction of an edge along axis a at node c: 1/2 for each other
// axis on which c lies on the grid's boundary (zero-flux walls, docs/nutrient.md).
REAL cut_face(uint c[3], uint a) {
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
  REAL f = REAL(1);
  for (uint b = 0u; b < 3u; b++)
    if (b != a && (c[b] == 0u || c[b] == n[b] - 1u)) f *= REAL(0.5);
  return f;
}

// The cut fraction of node c towards direction d (axis d/2, side d%2),
// raised to theta_min; 1 when the surface does not cross the edge.
REAL cut_theta(uint node, uint d) {
  REAL t = theta[6u * node + d];
  if (!(t < REAL(1))) t = REAL(1);
  return max(t, pc.theta_min);
}

uint cut_stride(uint a) { return a == 0u ? 1u : (a == 1u ? pc.n0 : pc.n0 * pc.n1); }
#endif
