/* Rule evaluation on hand-made cells (the limb bud rules r1-r3 of §3.4):
 *  - cell 0 (tip) gets r1: set phi = its volume, and nothing else;
 *  - cell 1 (phi above K vol, small) gets r2: grow at Delta;
 *  - cell 2 (phi above K vol, radius above R) gets r2 and r3: grow and a
 *    division whose direction equals the least-squares gradient of phi;
 *  - cell 3 (phi below threshold) gets nothing;
 *  - conditions read the state at the start of the step (synchronous): a
 *    rule setting tip in cell 1 does not make r1 fire there the same step;
 *  - apply: r += dt Delta exactly; set values clamped to [0, vol];
 *  - the gradient of a linear field on a jittered lattice equals the field's
 *    gradient (1e-12 relative: least squares is exact for linear fields),
 *    and a divide rule's direction is its unit vector (1e-12);
 *  - §3.6 tip check: a tip with an interior cell straight below passes, one
 *    whose only interior neighbour is sideways is reported with it to split. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "morph_lattice.h"
#include "testutil.h"

static const char *limb =
    "const K = 0.1\n"
    "const Delta = 0.01\n"
    "const R = 0.5\n"
    "morphogen phi diffusion=0.1 decay=0\n"
    "state tip\n"
    "rule r1: tip == 1 -> set phi = volume\n"
    "rule r2: tip == 0 && phi > K * volume -> grow Delta\n"
    "rule r3: tip == 0 && radius > R -> divide toward grad(phi)\n"
    "rule r9: tip == 0 && phi > 0.9 * volume -> set tip = 1\n";

int main(void) {
  sessile_sds_model *m = NULL;
  t_must("parse", sessile_sds_model_parse(limb, "limb-test", &m));
  /* four cells on a tetrahedron-like star around the origin */
  double pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  double radius[4] = {0.3, 0.3, 0.6, 0.3};
  uint32_t off[5] = {0, 3, 6, 9, 12};
  uint32_t nbr[12] = {1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2};
  sessile_morph_cells cells = {4, pos, radius, off, nbr, NULL};
  double v[4];
  for (int c = 0; c < 4; c++) v[c] = sessile_morph_vol(radius[c]);
  double phi[4] = {0.5 * v[0], 0.95 * v[1], 0.5 * v[2], 0.01 * v[3]};
  double state[4] = {1, 0, 0, 0};
  sessile_sds_actions a = {0};
  t_must("eval", sessile_sds_rules_eval(m, &cells, phi, state, 0.0, &a));
  t_true("r1: one set phi = vol on the tip, one set tip = 1 on cell 1 (r9), in cell order", a.nsets == 2 &&
         a.sets[0].cell == 0 && a.sets[0].kind == SESSILE_SDS_SET_MORPH && a.sets[0].value == v[0] &&
         a.sets[1].cell == 1 && a.sets[1].kind == SESSILE_SDS_SET_STATE && a.sets[1].value == 1);
  t_true("r2: grow Delta on cells 1 and 2, none on 0 and 3",
         a.grow[0] == 0 && a.grow[1] == 0.01 && a.grow[2] == 0.01 && a.grow[3] == 0);
  t_true("r3: one division, cell 2, rule r3", a.ndivides == 1 && a.divides[0].cell == 2 && a.divides[0].rule == 2);
  double g[3];
  sessile_morph_gradient(&cells, 1, phi, 2, 0, g);
  double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), de = 0;
  for (int k = 0; k < 3; k++) de = fmax(de, fabs(a.divides[0].dir[k] - g[k] / gl));
  t_check("r3: direction = unit LS gradient of phi at cell 2", de, 1e-15);
  t_true("firings: r1 on 0, r2 and r9 on 1, r2 and r3 on 2", a.fired == 5);
  t_true("synchronous: r1 did not fire on cell 1 though r9 sets its tip", a.nsets == 2);

  double r1[4], p1[4], s1[4];
  memcpy(r1, radius, sizeof r1), memcpy(p1, phi, sizeof p1), memcpy(s1, state, sizeof s1);
  sessile_sds_actions_apply(m, &a, 0.5, r1, p1, s1);
  t_true("apply: r += dt * Delta", r1[1] == radius[1] + 0.5 * 0.01 && r1[0] == radius[0] && r1[3] == radius[3]);
  t_true("apply: tip full, cell 1 becomes a tip", fabs(p1[0] - sessile_morph_vol(r1[0])) <= 1e-15 && s1[1] == 1);
  sessile_sds_actions_free(&a);

  /* gradient of a linear field */
  lattice L = lattice_make(6, 6, 6, 0.3, 0.25, 0.1, 9);
  int n = L.cells.ncells;
  double G[3] = {0.3, -1.2, 0.7};
  double *f = t_dalloc(n);
  for (int c = 0; c < n; c++) f[c] = 2 + G[0] * L.pos[3 * c] + G[1] * L.pos[3 * c + 1] + G[2] * L.pos[3 * c + 2];
  double worst = 0, Gl = sqrt(G[0] * G[0] + G[1] * G[1] + G[2] * G[2]);
  for (int c = 0; c < n; c++) {
    double q[3];
    sessile_morph_gradient(&L.cells, 1, f, c, 0, q);
    for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(q[k] - G[k]) / Gl);
  }
  t_check("LS gradient of a linear field, every cell (relative, corners included)", worst, 1e-12);
  sessile_sds_model *dm = NULL;
  t_must("parse", sessile_sds_model_parse("morphogen f diffusion=0 decay=0\nrule d: 1 -> divide grad(f)\n"
                                          "rule e: 1 -> divide away grad(f)\n", "div-test", &dm));
  t_must("eval", sessile_sds_rules_eval(dm, &L.cells, f, NULL, 0.0, &a));
  double dworst = 0;
  for (size_t i = 0; i < a.ndivides; i++)
    for (int k = 0; k < 3; k++) dworst = fmax(dworst, fabs(a.divides[i].dir[k] - G[k] / Gl));
  t_true("one division per cell (the first divide rule)", a.ndivides == (size_t)n);
  t_check("divide direction = the field's unit gradient", dworst, 1e-12);
  sessile_sds_actions_free(&a);
  sessile_sds_model_destroy(dm);
  t_must("parse", sessile_sds_model_parse("morphogen f diffusion=0 decay=0\nrule e: 1 -> divide away grad(f)\n",
                                          "div-test", &dm));
  t_must("eval", sessile_sds_rules_eval(dm, &L.cells, f, NULL, 0.0, &a));
  t_true("divide away: the opposite direction", a.ndivides == (size_t)n && fabs(a.divides[0].dir[1] + G[1] / Gl) < 1e-12);
  sessile_sds_actions_free(&a);
  sessile_sds_model_destroy(dm);

  /* §3.6: tips on the surface of a 3x3x3 lattice (the centre is interior) */
  lattice T = lattice_make(3, 3, 3, 1.0, 0, 0, 1);
  uint8_t surf[27];
  double st[27];
  for (int c = 0; c < 27; c++) surf[c] = c != 13, st[c] = 0;
  st[4] = 1;  /* face centre z = 0: the centre cell 13 lies straight above it, toward the centroid */
  st[0] = 1;  /* a corner: its neighbours are surface cells only */
  sessile_sds_tip_check *tc = NULL;
  int nt = 0;
  t_must("tips below", sessile_sds_tips_below(&T.cells, surf, NULL, st, 1, 0, 0.9, &tc, &nt));
  t_true("two tips checked, in cell order", nt == 2 && tc[0].tip == 0 && tc[1].tip == 4);
  t_true("face-centre tip: the interior cell 13 below (cos 1)", nt == 2 && tc[1].below == 13 && tc[1].split == -1 &&
                                                                fabs(tc[1].cosine - 1) < 1e-15);
  t_true("corner tip: no interior neighbour, the tip itself to split inward", nt == 2 && tc[0].below == -1 &&
                                                                              tc[0].split == 0);
  free(tc);
  t_true("tips below: bad state index refused",
         sessile_sds_tips_below(&T.cells, surf, NULL, st, 1, 3, 0.9, &tc, &nt) == SESSILE_ERR_USAGE);
  lattice_free(&T);
  free(f);
  lattice_free(&L);
  sessile_sds_model_destroy(m);
  return t_finish(NULL);
}
