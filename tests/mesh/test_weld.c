/* The welded surface (sessile_skeleton_weld, docs/weld.md): the GPU mesh
 * equals the host reference's (connectivity identical, positions to 1e-9
 * relative on fp64 contexts), is a closed consistently oriented 2-manifold
 * with the shape's Euler characteristic and no self-intersection, outward
 * (positive volume), also on a lattice-aligned frame with round cells,
 * deterministic to the byte; an empty skeleton gives an
 * empty surface; an oversized grid is refused with its estimate.  Vertex
 * values are compared bit for bit: capsule distances within 2^-30 h count as
 * ties on both sides (docs/weld.md, "Vertex value"), since an H100, whose
 * compiler contracts a*b+c into FMA, flipped exact ties at a ring's joints;
 * with the host reference built -mfma -ffp-contract=fast this test passes. */
#include <stdlib.h>
#include <string.h>
#include "mesh/weld_internal.h"
#include "sessile/mesh/intersect.h"
#include "test_weld_shapes.h"

static int fp64;

/* GPU and reference on s; the checks; returns the GPU mesh in out. */
static void weld_both(sessile_gpu *g, const char *name, const sessile_skeleton *s, const sessile_weld_params *p,
                      int euler, sessile_surface *out) {
  char what[160];
  sessile_surface ref = {0};
  double *vg = NULL, *vr = NULL;
  snprintf(what, sizeof what, "%s: GPU weld", name);
  t_must(what, sessile_skeleton_weld(g, s, p, out, &vg));
  snprintf(what, sizeof what, "%s: reference weld", name);
  t_must(what, sessile_skeleton_weld_ref(s, p, &ref, &vr));
  printf("%s: %u vertices, %u triangles (reference %u, %u)\n", name, out->nv, out->nf, ref.nv, ref.nf);
  if (fp64) {
    snprintf(what, sizeof what, "%s: same vertex and triangle counts", name);
    t_true(what, out->nv == ref.nv && out->nf == ref.nf);
    if (out->nv == ref.nv && out->nf == ref.nf) {
      snprintf(what, sizeof what, "%s: identical triangles (connectivity)", name);
      t_true(what, memcmp(out->tri, ref.tri, (size_t)out->nf * 12) == 0);
      snprintf(what, sizeof what, "%s: positions, max relative difference to the reference", name);
      t_check(what, t_relerr(out->pos, ref.pos, (size_t)out->nv * 3), 1e-9);
      snprintf(what, sizeof what, "%s: vertex values equal the reference's", name);
      t_true(what, memcmp(vg, vr, (size_t)out->nv * sizeof *vg) == 0);
    }
  }
  snprintf(what, sizeof what, "%s: closed oriented 2-manifold, Euler %d (GPU)", name, euler);
  sessile_status st = sessile_surface_check(out, euler, 0);
  if (st != SESSILE_OK) printf("  %s\n", sessile_error_message());
  t_true(what, st == SESSILE_OK);
  snprintf(what, sizeof what, "%s: closed oriented 2-manifold, Euler %d (reference)", name, euler);
  t_true(what, sessile_surface_check(&ref, euler, 0) == SESSILE_OK);
  uint64_t nx = 1;
  t_must("self-intersections", sessile_surface_self_intersections(out, 0, NULL, &nx));
  snprintf(what, sizeof what, "%s: self-intersecting triangle pairs", name);
  t_check(what, (double)nx, 0);
  sessile_surface_stats st2;
  sessile_surface_stats_of(out, &st2);
  snprintf(what, sizeof what, "%s: outward orientation (volume %.4g > 0)", name, st2.volume);
  t_true(what, st2.volume > 0);
  /* each vertex carries the value of a capsule of s */
  int ok = 1;
  for (uint32_t v = 0; v < out->nv && ok; v++) {
    ok = 0;
    for (uint32_t i = 0; i < s->n; i++) ok |= vg[v] == s->value[i];
  }
  snprintf(what, sizeof what, "%s: every vertex value is a capsule's", name);
  t_true(what, ok);
  free(vg), free(vr);
  sessile_surface_free(&ref);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  if (!fp64) printf("fp32 context: the GPU mesh is compared by its invariants only\n");
  sessile_weld_params p = {.cell = 0, .max_cells = 48, .blend = 0};
  sessile_surface m = {0};

  sessile_skeleton one = {0};
  shape_capsule(&one, 1.0, 5.0);
  weld_both(g, "one capsule", &one, &p, 2, &m);
  int all7 = m.nv > 0;
  for (uint32_t v = 0; v < m.nv; v++) all7 &= 1; /* values checked in weld_both */
  t_true("one capsule: a non-empty surface", all7);

  sessile_skeleton y = {0};
  shape_y(&y);
  weld_both(g, "Y junction, blend 0", &y, &p, 2, &m);
  p.blend = 0.6;
  weld_both(g, "Y junction, blend 0.6", &y, &p, 2, &m);
  p.blend = 0;

  sessile_skeleton ring = {0};
  shape_ring(&ring, 16, 4.0, 0.9);
  p.max_cells = 64;
  weld_both(g, "ring of 16 capsules", &ring, &p, 0, &m);

  sessile_skeleton frame = {0};
  shape_frame(&frame);
  sessile_weld_params pf = {.cell = 0.1, .max_cells = 0, .blend = 0};
  weld_both(g, "lattice frame, cell 0.1", &frame, &pf, 6, &m);
  pf.cell = 0.125, pf.blend = 0.25;
  weld_both(g, "lattice frame, cell 0.125, blend 0.25", &frame, &pf, 6, &m);
  sessile_skeleton_free(&frame);

  sessile_skeleton tree = {0};
  t_must("tree", weld_random_tree(5, 40, 0.6, &tree));
  p.max_cells = 80, p.blend = 0.3;
  /* branches may touch and close loops: its Euler characteristic is V - E + F
   * of the mesh (E = 3F/2), the check is of the rest */
  sessile_surface tm = {0};
  t_must("tree weld", sessile_skeleton_weld_ref(&tree, &p, &tm, NULL));
  int chi = (int)tm.nv - (int)(3 * tm.nf / 2) + (int)tm.nf;
  printf("tree: Euler characteristic %d\n", chi);
  sessile_surface_free(&tm);
  weld_both(g, "tree of 40 segments, blend 0.3", &tree, &p, chi, &m);

  /* determinism: a second GPU run gives the same bytes */
  sessile_surface m2 = {0};
  double *v1 = NULL, *v2 = NULL;
  t_must("weld 1", sessile_skeleton_weld(g, &tree, &p, &m, &v1));
  t_must("weld 2", sessile_skeleton_weld(g, &tree, &p, &m2, &v2));
  t_true("two GPU runs: identical bytes (positions, triangles, values)",
         m.nv == m2.nv && m.nf == m2.nf && !memcmp(m.pos, m2.pos, (size_t)m.nv * 24) &&
             !memcmp(m.tri, m2.tri, (size_t)m.nf * 12) && !memcmp(v1, v2, (size_t)m.nv * 8));
  free(v1), free(v2);

  /* an empty skeleton: an empty surface, no values */
  sessile_skeleton none = {0};
  double *ve = (double *)&ve;
  t_ok("empty skeleton welds", sessile_skeleton_weld(g, &none, &p, &m2, &ve));
  t_true("empty skeleton: empty surface, NULL values", m2.nv == 0 && m2.nf == 0 && ve == NULL);

  /* an oversized grid is refused with its estimate, before any work */
  sessile_weld_params big = {.cell = 0, .max_cells = 100000, .blend = 0};
  sessile_status st = sessile_skeleton_weld(g, &one, &big, &m2, NULL);
  printf("refusal: %s\n", sessile_error_message());
  t_true("oversized grid: SESSILE_ERR_NO_MEMORY with 'MB' in the message",
         st == SESSILE_ERR_NO_MEMORY && strstr(sessile_error_message(), " MB") != NULL);
  st = sessile_skeleton_weld_ref(&one, &big, &m2, NULL);
  t_true("oversized grid refused by the reference too", st == SESSILE_ERR_NO_MEMORY);
  sessile_weld_params bad = {.cell = -1};
  t_true("negative cell: usage error", sessile_skeleton_weld(g, &one, &bad, &m2, NULL) == SESSILE_ERR_USAGE);

  sessile_surface_free(&m), sessile_surface_free(&m2);
  sessile_skeleton_free(&one), sessile_skeleton_free(&y), sessile_skeleton_free(&ring);
  sessile_skeleton_free(&tree);
  return t_finish(g);
}
