#version 450
#extension GL_GOOGLE_include_directive : require
// The axis morphogen's gradient at each cell for the oriented growth of a
// batch step (kernels.def, SDS_AXIAL_GRAD): sessile_morph_gradient, as the
// rules compute it (gradient.glsl).
#include "sds_kernels.glsl"
#define RV_X(i) x[i]
#define RV_PHI(i) phi[i]
#define RV_OFF(i) nbr_off[i]
#define RV_NBR(i) nbr[i]
#include "gradient.glsl"

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  REAL g0, g1, g2;
  gradient(c, pc.axis, g0, g1, g2);
  grad[3u * c] = g0, grad[3u * c + 1u] = g1, grad[3u * c + 2u] = g2;
}
