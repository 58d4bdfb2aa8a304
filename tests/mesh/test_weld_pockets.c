/* The welded surface's last pass (host/mesh/weld_clean.c): from a surface of
 * three components - an outer sphere (outward), a pocket inside it (an
 * inward-facing sphere, as marching tetrahedra draws enclosed water) and a
 * speck (a tiny outward sphere) - only the outer sphere survives, with its
 * vertices and triangles in their original order, and still a closed
 * oriented 2-manifold. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/weld_internal.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"

static void append(sessile_surface *all, const sessile_surface *s, int flip) {
  t_must("reserve", sessile_surface_reserve(all, all->nv + s->nv, all->nf + s->nf));
  memcpy(all->pos + 3 * (size_t)all->nv, s->pos, 3 * (size_t)s->nv * sizeof *s->pos);
  for (uint32_t f = 0; f < s->nf; f++) {
    uint32_t *t = all->tri + 3 * (size_t)(all->nf + f);
    t[0] = all->nv + s->tri[3 * f], t[1] = all->nv + s->tri[3 * f + (flip ? 2 : 1)];
    t[2] = all->nv + s->tri[3 * f + (flip ? 1 : 2)];
  }
  all->nv += s->nv, all->nf += s->nf;
}

int main(void) {
  sessile_surface outer = {0}, pocket = {0}, speck = {0}, all = {0};
  t_must("outer", sessile_surface_icosphere(3, 2.0, (double[3]){0, 0, 0}, &outer));
  t_must("pocket", sessile_surface_icosphere(2, 0.5, (double[3]){0.3, 0, 0}, &pocket));
  t_must("speck", sessile_surface_icosphere(1, 0.01, (double[3]){5, 0, 0}, &speck));
  append(&all, &pocket, 1); /* first, so the kept vertices must move down */
  append(&all, &outer, 0);
  append(&all, &speck, 0);
  uint32_t nv = all.nv, nf = all.nf;
  uint32_t *nearest = t_xalloc((size_t)nv * sizeof *nearest);
  for (uint32_t v = 0; v < nv; v++) nearest[v] = v;
  /* one cell of 0.05 cm: the speck (about 4e-6 cm^3) is below it, the outer sphere far above */
  t_must("drop", weld_drop_pockets(all.pos, &nv, all.tri, &nf, nearest, 0.05 * 0.05 * 0.05));
  t_true("only the outer sphere's vertices and triangles are left", nv == outer.nv && nf == outer.nf);
  int same = !memcmp(all.pos, outer.pos, 3 * (size_t)outer.nv * sizeof *all.pos);
  for (uint32_t f = 0; f < outer.nf && same; f++)
    for (int k = 0; k < 3; k++) same &= all.tri[3 * f + k] == outer.tri[3 * f + k];
  t_true("in their original order, renumbered", same);
  int near_ok = 1;
  for (uint32_t v = 0; v < nv; v++) near_ok &= nearest[v] == pocket.nv + v;
  t_true("the per-vertex data moved with the vertices", near_ok);
  all.nv = nv, all.nf = nf;
  t_true("the result is a closed oriented 2-manifold", sessile_surface_check(&all, 2, 0) == SESSILE_OK);
  free(nearest);
  sessile_surface_free(&outer), sessile_surface_free(&pocket), sessile_surface_free(&speck), sessile_surface_free(&all);
  return t_finish(NULL);
}
