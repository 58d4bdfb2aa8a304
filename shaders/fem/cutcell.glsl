// The cut-cell boundary of the nutrient on one box level (Gibou et al. 2002,
// the symmetric Shortley-Weller variant; docs/nutrient.md):
//   mask: CUT_SOLID inside the sponge, CUT_NODE on the substratum and the far
//         field, CUT_FREE elsewhere;
//   diag: for a free node, the sum over its existing neighbours of f w, f the
//         face fraction, w = 1/theta across the sponge surface (c = 0 there),
//         1/theta' across the far-field plane (theta' its fraction), else 1;
//   lift (finest level): h sum of f w g over the Dirichlet neighbours (the
//         right-hand side of the free rows), value: c on Dirichlet nodes.
// Mirrored by sessile_cut_ref_setup (host/fem/nutrient_cut_ref.c).
// The includer sets CUT_ADV: 1 for the advected nutrient (cutcell_adv.comp),
// where every weight w is multiplied by the exponentially fitted factor of
// its edge (cut_adv.glsl) and also written to coef (6 per node).
#include "cut_common.glsl"
#if CUT_ADV
#include "cut_adv.glsl"
#endif

void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint c[3];
  cut_ijk(node, c);
  REAL g;
  uint code = cut_node_dirichlet(c, g) ? CUT_NODE : (solid[node] != 0u ? CUT_SOLID : CUT_FREE);
  if (code == CUT_SOLID) g = REAL(0);
  mask[node] = code;
  if (code != CUT_FREE) {
    diag[node] = REAL(1);
    if (pc.want_lift != 0u) {
      lift[node] = REAL(0);
      value[node] = g;
    }
#if CUT_ADV
    for (uint dir = 0u; dir < 6u; dir++) coef[6u * node + dir] = REAL(0);
#endif
    return;
  }
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
#if CUT_ADV
  // a missing neighbour (a zero-flux wall) gives the existing one no weight
  for (uint dir = 0u; dir < 6u; dir++) coef[6u * node + dir] = REAL(0);
#endif
  precise REAL d = REAL(0);
  precise REAL b = REAL(0);
  for (uint dir = 0u; dir < 6u; dir++) {
    uint a = dir >> 1u;
    bool plus = (dir & 1u) != 0u;
    if (plus ? c[a] + 1u >= n[a] : c[a] == 0u) continue;
    uint m = plus ? node + cut_stride(a) : node - cut_stride(a);
    uint cm[3] = uint[3](c[0], c[1], c[2]);
    cm[a] = plus ? c[a] + 1u : c[a] - 1u;
    REAL gm;
    bool nodebc = cut_node_dirichlet(cm, gm);
    REAL f = cut_face(c, a);
    REAL w = REAL(1);
#if CUT_ADV
    REAL th = REAL(1);
#endif
    if (nodebc) {
      // The far-field plane between two layers: its own fraction.
      if (pc.far_field != FAR_WALLS && a == 2u && plus && cm[2] != 0u) {
        precise REAL t = (pc.height - cut_z(c[2])) / pc.h;
        w = REAL(1) / max(min(t, REAL(1)), pc.theta_min);
#if CUT_ADV
        th = max(min(t, REAL(1)), pc.theta_min);
#endif
      }
#if CUT_ADV
      w *= adv_factor(node, c, dir, th);
#endif
      b += f * w * gm;
    } else if (solid[m] != 0u) {
      w = REAL(1) / cut_theta(node, dir);
#if CUT_ADV
      w *= adv_factor(node, c, dir, cut_theta(node, dir));
    } else {
      w *= adv_factor(node, c, dir, REAL(1));
#endif
    }
#if CUT_ADV
    coef[6u * node + dir] = w;
#endif
    d += f * w;
  }
  diag[node] = d;
  if (pc.want_lift != 0u) {
    lift[node] = pc.h * b;
    value[node] = REAL(0);
  }
}
