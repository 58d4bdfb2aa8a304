#version 450
#extension GL_GOOGLE_include_directive : require
// The skeleton's signed distance at every grid node: the fold (in segment
// order) of the capsules listed in the node's brick, by min or the smooth
// union, clamped to at most clampv; boundary nodes are outside (clampv) so
// the surface is closed.  As weld_node_value (host/mesh/weld_grid.c).
#include "mesh_kernels.glsl"
#include "weld_common.glsl"

void main() {
  uint i = sessile_gid();
  uint nxy = pc.nx * pc.ny;
  if (i >= nxy * pc.nz) return;
  uint x = i % pc.nx, y = (i / pc.nx) % pc.ny, z = i / nxy;
  REAL v = pc.clampv;
  if (x > 0u && y > 0u && z > 0u && x + 1u < pc.nx && y + 1u < pc.ny && z + 1u < pc.nz) {
    precise REAL px = pc.lox + pc.h * REAL(x), py = pc.loy + pc.h * REAL(y), pz = pc.loz + pc.h * REAL(z);
    uint b = brick_of(x, y, z);
    uint e1 = boff[b + 1u];
    REAL f = REAL(1e30);
    for (uint e = boff[b]; e < e1; e++) {
      REAL d = capsule_sdf(blist[e], px, py, pz);
      f = pc.blend > REAL(0) ? weld_smin(f, d, pc.blend) : min(f, d);
    }
    v = min(f, pc.clampv);
  }
  field[i] = v;
}
