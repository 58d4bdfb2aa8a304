// The body of bmg_prolong.comp and bmg_prolong_tex.comp (BMG_TEXEL 0 or 1):
// x += P xc on the free unknowns of the fine grid (n0 x n1 x n2; coarse grid
// f0 x f1 x f2): fine node 2C + o (o in {0,1}^3) is coarse node C when o = 0,
// else the midpoint of the coarse Kuhn edge from C to C + o (P1 interpolation
// on the coarse tets, which the fine Kuhn tets refine).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#include "bmg_common.glsl"
#if BMG_TEXEL
#define BMG_FMASK(i) texelFetch(fmask_t, int(i)).x
#define BMG_XC(i) bmg_tex4(xc_t, i)
#else
#define BMG_FMASK(i) fmask[i]
#define BMG_XC(i) xc[i]
#endif
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint m = BMG_FMASK(node);
  if (m == 0u) return;
  uvec3 f = grid_ijk(node), c0 = f >> 1u, c1 = c0 + (f & 1u);
  uint i0 = c0.x + pc.f0 * (c0.y + pc.f1 * c0.z), i1 = c1.x + pc.f0 * (c1.y + pc.f1 * c1.z);
  REAL4 v = i0 == i1 ? BMG_XC(i0) : REAL(0.5) * (BMG_XC(i0) + BMG_XC(i1));
  x[node] += bmg_free(m) * v;
}
