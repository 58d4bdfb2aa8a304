/* The generators' skeletons welded (GPU): the three shipped L-system
 * grammars (their defaults, on a coarser grid to keep the test short) and
 * the default open, closed and 3-D venation corals become closed, consistently oriented 2-manifolds (Euler
 * characteristic V - E + F with E = 3F/2, which sessile_surface_check also
 * verifies edge by edge) with no self-intersecting triangle pair, in ONE
 * connected piece (the vein graph is connected; tips thinner than a cell
 * once broke off), of genus 0 for an open (tree) coral in the plane and of
 * positive genus for a closed one (its cycles are handles). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/intersect.h"
#include "sessile/coral/lsystem.h"
#include "sessile/mesh/skeleton.h"
#include "sessile/coral/venation.h"
#include "testutil.h"

static uint32_t find(uint32_t *u, uint32_t x) {
  while (u[x] != x) x = u[x] = u[u[x]];
  return x;
}

/* Connected pieces of the mesh (union-find over triangle edges). */
static uint32_t components(const sessile_surface *m) {
  uint32_t *u = t_xalloc((size_t)(m->nv ? m->nv : 1) * sizeof *u), n = m->nv;
  for (uint32_t v = 0; v < m->nv; v++) u[v] = v;
  for (uint32_t f = 0; f < m->nf; f++)
    for (int k = 0; k < 2; k++) {
      uint32_t a = find(u, m->tri[3 * f + k]), b = find(u, m->tri[3 * f + k + 1]);
      if (a != b) u[a] = b, n--;
    }
  free(u);
  return n;
}

/* want_euler: the expected Euler characteristic, 1 for "below 2" (handles), 99 for any. */
static void check_weld(sessile_gpu *g, const char *name, const sessile_skeleton *sk, const sessile_weld_params *wp,
                       int want_euler) {
  sessile_surface m = {0};
  double *val = NULL;
  char what[160];
  t_must(name, sessile_skeleton_weld(g, sk, wp, &m, &val));
  int chi = (int)m.nv - (int)(3 * m.nf / 2) + (int)m.nf;
  snprintf(what, sizeof what, "%s: %u segments welded to %u triangles, a closed oriented 2-manifold", name, sk->n, m.nf);
  t_true(what, m.nf > 0 && sessile_surface_check(&m, chi, 0) == SESSILE_OK);
  uint64_t nx = 0;
  t_must("self-intersections", sessile_surface_self_intersections(&m, 0, NULL, &nx));
  snprintf(what, sizeof what, "%s: no self-intersecting pair", name);
  t_check(what, (double)nx, 0);
  uint32_t pieces = components(&m);
  printf("%s: Euler characteristic %d, %u piece(s)\n", name, chi, pieces);
  snprintf(what, sizeof what, "%s: one connected piece", name);
  t_true(what, pieces == 1);
  if (want_euler == 1) {
    snprintf(what, sizeof what, "%s: handles from the vein cycles (Euler %d < 2)", name, chi);
    t_true(what, chi < 2);
  } else if (want_euler != 99) {
    snprintf(what, sizeof what, "%s: Euler characteristic %d (expected %d)", name, chi, want_euler);
    t_true(what, chi == want_euler);
  }
  free(val);
  sessile_surface_free(&m);
}

static void venation(sessile_gpu *g, const char *name, const char *const *sets, int nsets, int want_euler) {
  sessile_venation_params p;
  sessile_params_defaults(&sessile_venation_param_table, &p);
  for (int i = 0; i < nsets; i++) t_must(sets[i], sessile_params_set_kv(&sessile_venation_param_table, &p, sets[i]));
  sessile_venation v = {0};
  t_must("init", sessile_venation_init(&v, 1));
  for (int k = 0; k < 40; k++) t_must("step", sessile_venation_step(&v, &p, NULL));
  sessile_skeleton sk = {0};
  t_must("skeleton", sessile_venation_skeleton(&v, &p, &sk));
  sessile_weld_params wp = {.cell = p.weld_cell, .blend = p.weld_blend};
  check_weld(g, name, &sk, &wp, want_euler);
  sessile_skeleton_free(&sk);
  sessile_venation_free(&v);
}

static void lsystem(sessile_gpu *g, const char *grammar) {
  sessile_coral_lsystem_params p;
  sessile_params_defaults(&sessile_coral_lsystem_param_table, &p);
  char set[64];
  snprintf(set, sizeof set, "grammar=%s", grammar);
  t_must(set, sessile_params_set_kv(&sessile_coral_lsystem_param_table, &p, set));
  t_must("weld", sessile_params_set_kv(&sessile_coral_lsystem_param_table, &p, "geometry=weld"));
  t_must("cells", sessile_params_set_kv(&sessile_coral_lsystem_param_table, &p, "weld_cells=128"));
  size_t len = 0;
  const char *text = sessile_lsys_builtin_find(grammar, &len);
  t_true(grammar, text != NULL);
  sessile_lsys *gr = NULL;
  t_must("parse", sessile_lsys_parse(text, len, grammar, 0, NULL, NULL, &gr));
  sessile_coral_lsystem_result r;
  memset(&r, 0, sizeof r);
  t_must("build", sessile_coral_lsystem_build(&p, gr, -1, 1, g, NULL, &r));
  char name[64];
  snprintf(name, sizeof name, "lsystem %s", grammar);
  /* branches of a Lophelia colony touch and fuse (handles): connected, any genus */
  sessile_weld_params wp = {.cell = p.weld_cell, .max_cells = (uint32_t)p.weld_cells, .blend = p.weld_blend};
  check_weld(g, name, r.skel, &wp, 99);
  sessile_coral_lsystem_result_free(&r);
  sessile_lsys_destroy(gr);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  lsystem(g, "lophelia1");
  lsystem(g, "lophelia2");
  lsystem(g, "flat");
  venation(g, "venation open", NULL, 0, 2);
  const char *closed[] = {"open=false"};
  venation(g, "venation closed", closed, 1, 1);
  /* in the box, branches may touch and close loops: connected, any genus */
  const char *box[] = {"planar=false"};
  venation(g, "venation 3-D box", box, 1, 99);
  return t_finish(g);
}
