// One cell per invocation: its bound h_c on the stable step of semi-implicit
// Euler (docs/sds.md, "Integrator"), the positive root of
// w2 h^2 + 2 gam h = 4, where Gershgorin's theorem on M^-1 H bounds w2 by
// the cell's edges (2 k_e (m_a + m_b)/R' each) and tets
// (k_vol s/R'^2 |grad_c V| sum_j |grad_j V|) over its mass, plus the wall
// and contact terms, and gam likewise with damp_vol, plus the viscous c.
// The terms are edge_force's and tet_force's in mode 2; the sums run in CSR
// order (ascending element index, edges first), the order in which
// sessile_sds_stable_dt (host/sds/sds_integrate.c) adds them to each cell:
// the same bits where the device rounds as the host does (precise: no fused
// multiply-adds).  The same loop also sums the elements' forces on the cell
// (the gather's sum, in its order), which the gather of mode 2 then reads
// instead of looping over the elements again.  With mass scaling a cell
// whose bound falls below sp[SP_MASS_DT] gets the inertia that lifts it there
// (docs/sds.md, "Mass scaling"), its factor after the sums.
#include "sds_common.glsl"
#include "sds_load.glsl"

// Cell c's bound (c < ncells, the batch not stopped).
void stable_cell(uint c) {
  uint ce = o_ce(), ct = o_ct(), ceo = o_ceo(), cto = o_cto();
  uint tw = 12u * pc.ntets + 3u * pc.nedges, ew = 20u * pc.ntets + 3u * pc.nedges;
  precise REAL w2 = REAL(0), gam = REAL(0);
  REAL s[3] = REAL[3](REAL(0), REAL(0), REAL(0));
  for (uint k = LD_TOPO(ceo + c); k < LD_TOPO(ceo + c + 1u); k++) {
    uint v = LD_TOPO(ce + k), e = v >> 1u; // 2 e + 1 where c is the edge's second cell
    REAL sg = (v & 1u) != 0u ? REAL(1) : REAL(-1);
    for (int i = 0; i < 3; i++) s[i] += sg * LD_ELF(12u * pc.ntets + 3u * e + i);
    w2 += LD_ELF(ew + e);
  }
  for (uint k = LD_TOPO(cto + c); k < LD_TOPO(cto + c + 1u); k++) {
    uint v = LD_TOPO(ct + k); // 4 t + c's corner
    for (int i = 0; i < 3; i++) s[i] += LD_ELF(3u * v + i);
    uint o = tw + 2u * v; // 8 t + 2 j: the corner's pair
    w2 += LD_ELF(o), gam += LD_ELF(o + 1u);
  }
  for (int i = 0; i < 3; i++) stab[pc.ncells + 3u + 3u * c + i] = s[i];
  REAL m = M_OF(c);
  precise REAL wa = sp[SP_STAB_ADH] / R_OF(c); // the adhesion's slope 2 A / delta, where it exceeds the wall's
  precise REAL w = w2 / m + (wa > sp[SP_STAB_WALL] ? wa : sp[SP_STAB_WALL]) +
                   (LD_TOPO(o_csurf() + c) != 0u ? sp[SP_STAB_CONTACT] : REAL(0));
  precise REAL g = gam / m + sp[SP_DAMP_VISC];
  precise REAL h;
  if (w > REAL(0)) h = REAL(4) / (g + sqrt(g * g + REAL(4) * w));
  else h = g > REAL(0) ? REAL(2) / g : sp[SP_DT_MAX];
  // selective mass scaling: below H the cell moves with the inertia alpha m
  // whose bound is H, (w H^2 + 2 g H) / 4 (> 1 there), read by the gather
  precise REAL H = sp[SP_MASS_DT], alpha = REAL(1);
  if (H > REAL(0) && h < H) alpha = (w * H * H + REAL(2) * g * H) / REAL(4), h = H;
  stab[4u * pc.ncells + 3u + c] = alpha;
  stab[c] = h;
}

#ifndef STABLE_NO_MAIN
void main() {
  uint c = sessile_gid();
  if (c < pc.ncells && !(pc.batch != 0u && ev[0] != 0u)) stable_cell(c); // else a batch that stopped
}
#endif
