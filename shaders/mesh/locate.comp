#version 450
#extension GL_GOOGLE_include_directive : require
// Point location in an unstructured tet mesh and P1 interpolation of a nodal
// field: the bin holding the point, then the first tet of the bin (ascending
// index) whose barycentric weights are all >= -eps.  Operation by operation
// as sessile_locator_find / locate_weights (host/mesh/locate.c), so the fp64
// build returns the host's tet.
#include "mesh_kernels.glsl"

const uint OUTSIDE = 0xFFFFFFFFu;

void weights(uvec4 v, REAL p[3], out REAL w[4]) {
  REAL d1[3], d2[3], d3[3], q[3];
  for (int k = 0; k < 3; k++) {
    REAL x0 = xyz[3u * v.x + uint(k)];
    d1[k] = xyz[3u * v.y + uint(k)] - x0;
    d2[k] = xyz[3u * v.z + uint(k)] - x0;
    d3[k] = xyz[3u * v.w + uint(k)] - x0;
    q[k] = p[k] - x0;
  }
  precise REAL c23x = d2[1] * d3[2] - d2[2] * d3[1], c23y = d2[2] * d3[0] - d2[0] * d3[2],
               c23z = d2[0] * d3[1] - d2[1] * d3[0];
  precise REAL cq3x = q[1] * d3[2] - q[2] * d3[1], cq3y = q[2] * d3[0] - q[0] * d3[2],
               cq3z = q[0] * d3[1] - q[1] * d3[0];
  precise REAL c2qx = d2[1] * q[2] - d2[2] * q[1], c2qy = d2[2] * q[0] - d2[0] * q[2],
               c2qz = d2[0] * q[1] - d2[1] * q[0];
  precise REAL det = d1[0] * c23x + d1[1] * c23y + d1[2] * c23z;
  precise REAL a1 = q[0] * c23x + q[1] * c23y + q[2] * c23z;
  precise REAL a2 = d1[0] * cq3x + d1[1] * cq3y + d1[2] * cq3z;
  precise REAL a3 = d1[0] * c2qx + d1[1] * c2qy + d1[2] * c2qz;
  w[1] = a1 / det;
  w[2] = a2 / det;
  w[3] = a3 / det;
  precise REAL w0 = REAL(1) - w[1] - w[2] - w[3];
  w[0] = w0;
}

void main() {
  uint i = sessile_gid();
  if (i >= pc.n) return;
  REAL p[3] = REAL[3](pts[3u * i], pts[3u * i + 1u], pts[3u * i + 2u]);
  uint dims[3] = uint[3](pc.d0, pc.d1, pc.d2);
  uint c[3];
  bool inside = true;
  for (int k = 0; k < 3; k++) {
    precise REAL x = (p[k] - gp[LOC_LO + k]) * gp[LOC_INV_H + k];
    if (!(x >= REAL(-1e-3) && x <= REAL(dims[k]) + REAL(1e-3))) inside = false;
    REAL top = REAL(dims[k] - 1u);
    c[k] = !inside || x <= REAL(0) ? 0u : x >= top ? dims[k] - 1u : uint(x);
  }
  uint hit = OUTSIDE;
  REAL value = gp[LOC_OUTSIDE];
  if (inside) {
    REAL eps = gp[LOC_EPS];
    uint b = c[0] + pc.d0 * (c[1] + pc.d1 * c[2]);
    uint e1 = cell_off[b + 1u];
    for (uint e = cell_off[b]; e < e1; e++) {
      uint t = cell_tet[e];
      uvec4 v = tet[t];
      REAL w[4];
      weights(v, p, w);
      if (w[0] >= -eps && w[1] >= -eps && w[2] >= -eps && w[3] >= -eps) {
        hit = t;
        precise REAL s = w[0] * field[v.x] + w[1] * field[v.y];
        s = s + w[2] * field[v.z];
        s = s + w[3] * field[v.w];
        value = s;
        break;
      }
    }
  }
  val[i] = value;
  found[i] = hit;
}
