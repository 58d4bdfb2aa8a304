// The body of bmg_restrict.comp and bmg_restrict_tex.comp (BMG_TEXEL 0 or 1):
// b_C = R r = P^T r on the coarse grid (n0 x n1 x n2; fine grid f0 x f1 x f2):
// coarse node C gathers fine node 2C (weight 1) and the 14 fine nodes 2C +- e
// halfway along its Kuhn edges e (weight 1/2), on their free unknowns, and
// keeps its own free unknowns (a coarse Dirichlet unknown gets 0).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#include "bmg_common.glsl"
#if BMG_TEXEL
#define BMG_FMASK(i) texelFetch(fmask_t, int(i)).x
#define BMG_R(i) bmg_tex4(r_t, i)
#else
#define BMG_FMASK(i) fmask[i]
#define BMG_R(i) r[i]
#endif
const ivec3 EDGE[7] = ivec3[7](ivec3(1, 0, 0), ivec3(0, 1, 0), ivec3(0, 0, 1), ivec3(1, 1, 0),
                               ivec3(1, 0, 1), ivec3(0, 1, 1), ivec3(1, 1, 1));
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  ivec3 f = 2 * ivec3(grid_ijk(node)), fn = ivec3(pc.f0, pc.f1, pc.f2);
  uint c = uint(f.x) + pc.f0 * (uint(f.y) + pc.f1 * uint(f.z));
  REAL4 sum = bmg_free(BMG_FMASK(c)) * BMG_R(c), half_sum = REAL4(0);
  for (int e = 0; e < 7; e++)
    for (int sg = -1; sg <= 1; sg += 2) {
      ivec3 q = f + sg * EDGE[e];
      if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, fn))) continue;
      uint m = uint(q.x) + pc.f0 * (uint(q.y) + pc.f1 * uint(q.z));
      half_sum += bmg_free(BMG_FMASK(m)) * BMG_R(m);
    }
  b[node] = bmg_free(cmask[node]) * (sum + REAL(0.5) * half_sum);
}
