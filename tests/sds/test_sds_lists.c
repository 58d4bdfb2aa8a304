/* The contact lists' partial build (docs/sds.md, "Collisions"): after a
 * division that keeps the boundary (an interior cell's, or a surface cell's
 * inward), the device lists only the cells the division touched, and the
 * forces are bit for bit those of a device that built every list of the
 * divided body from scratch.  A division that changes the boundary (a
 * tangential split of a surface cell) builds every list.  Not exercised
 * here: a division that changes which surface cells neighbour a surface
 * cell (an edge through the body between two of them), whose self list the
 * partial build also redoes; the test prints how many it met (0 so far).  The scene: two spheres in one complex, 0.05 apart (self
 * contacts active), resting on a rock (obstacle contacts). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "collide_scenes.h"
#include "sessile/sds/sds_topo.h"

/* Divides cell c of o toward d as the loop does (sds_divide.c): the complex
 * through TetGen, daughter b appended with c's radius, mass and velocity,
 * new tets and edges at unit multipliers.  Returns 0 when TetGen declines. */
static int divide(sessile_sds *o, uint32_t c, const double d[3]) {
  sessile_sds_topo_complex cx = {0};
  cx.nv = o->ncells, cx.nt = o->ntets;
  cx.x = t_dalloc(3 * (size_t)o->ncells);
  cx.tet = t_xalloc(4 * (size_t)o->ntets * sizeof *cx.tet);
  memcpy(cx.x, o->x, 3 * (size_t)o->ncells * sizeof *cx.x);
  memcpy(cx.tet, o->tet, 4 * (size_t)o->ntets * sizeof *cx.tet);
  sessile_sds_topo_division dv;
  memset(&dv, 0, sizeof dv);
  sessile_status st = sessile_sds_topo_divide(&cx, c, d, 0.5 * o->r[c], &dv);
  if (st != SESSILE_OK) {
    free(dv.tet_from);
    sessile_sds_topo_complex_free(&cx);
    return 0;
  }
  t_must("reserve", sessile_sds_reserve(o, cx.nv, cx.nt));
  double *sm = t_dalloc((size_t)cx.nt + 1);
  for (uint32_t t = 0; t < cx.nt; t++) sm[t] = dv.tet_from[t] == SESSILE_SDS_TOPO_NEW_TET ? 0 : o->tet_sm[dv.tet_from[t]];
  memcpy(o->tet_sm, sm, (size_t)cx.nt * sizeof *sm);
  memcpy(o->x, cx.x, 3 * (size_t)cx.nv * sizeof *o->x);
  memcpy(o->tet, cx.tet, 4 * (size_t)cx.nt * sizeof *o->tet);
  uint32_t a = dv.a, b = dv.b;
  o->ncells = cx.nv, o->ntets = cx.nt;
  o->r[b] = o->r[a], o->m[b] = o->m[a], o->attract[b] = -1;
  for (int k = 0; k < 3; k++) o->v[3 * b + k] = o->v[3 * a + k];
  free(sm), free(dv.tet_from);
  sessile_sds_topo_complex_free(&cx);
  t_must("rebuild", sessile_sds_rebuild_oriented(o, SESSILE_SDS_NEW_UNIT));
  return 1;
}

/* Surface cells among the first n0 whose surface neighbours among the first
 * n0 differ between a (before a division) and b (after): the cells whose
 * self lists a partial build must redo. */
static uint32_t surface_rewired(const sessile_sds *a, const sessile_sds *b, uint32_t n0) {
  uint32_t count = 0;
  for (uint32_t c = 0; c < n0; c++) {
    if (!a->surface[c]) continue;
    int diff = 0;
    for (int pass = 0; pass < 2 && !diff; pass++) {
      const sessile_sds *p = pass ? b : a, *q = pass ? a : b;
      for (uint32_t k = p->cell_edge_off[c]; k < p->cell_edge_off[c + 1] && !diff; k++) {
        const uint32_t *e = p->edge + 2 * (size_t)p->cell_edge[k];
        uint32_t v = e[0] == c ? e[1] : e[0], found = 0;
        if (v >= n0 || !a->surface[v]) continue; /* a list leaves out faces at surface neighbours */
        for (uint32_t j = q->cell_edge_off[c]; j < q->cell_edge_off[c + 1]; j++) {
          const uint32_t *f = q->edge + 2 * (size_t)q->cell_edge[j];
          found |= (f[0] == c ? f[1] : f[0]) == v;
        }
        diff = !found;
      }
    }
    count += diff;
  }
  return count;
}

/* Forces of o on a fresh device (every list built from scratch). */
static void fresh_forces(sessile_gpu *g, const sessile_sds *o, const sessile_sds_params *p, double *f) {
  sessile_sds_gpu *s = NULL;
  t_must("gpu", sessile_sds_gpu_create(g, o, p, &s));
  t_must("forces", sessile_sds_gpu_forces(s, 1, f));
  uint64_t all = 0, part = 0;
  sessile_sds_gpu_list_builds(s, &all, &part);
  t_true("a fresh device builds every list (again if a list overflowed), none in part", all >= 1 && part == 0);
  sessile_sds_gpu_destroy(s);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  sessile_sds o = {0};
  sessile_surface rock = {0};
  const double c0[3] = {0, 0, 0}, c1[3] = {2.05, 0, 0}, rc[3] = {1.0, 0, -6.95};
  two_bodies(3, c0, c1, &o);
  t_must("rock", sessile_surface_icosphere(3, 6.0, rc, &rock));
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.gravity = 0.05;
  p.contact_scale = 2.5; /* contacts reach 2.5 radii: interior cells touch the rock, surface cells faces
                            near their neighbours' (which a list leaves out): what a stale list would miss */
  p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
  sessile_sds_gpu *s = NULL;
  t_must("gpu", sessile_sds_gpu_create(g, &o, &p, &s));
  size_t cap = 3 * ((size_t)o.ncells + 8);
  double *f = t_dalloc(cap), *ref = t_dalloc(cap);
  unsigned char *tried = calloc(cap, 1);
  t_must("forces", sessile_sds_gpu_forces(s, 1, f));
  uint32_t nself = 0, nobs = 0;
  {
    sessile_sds_contact *ct = calloc(o.ncells, sizeof *ct);
    t_must("contacts", sessile_sds_contacts(&o, &p, ct));
    for (uint32_t c = 0; c < o.ncells; c++) nself += ct[c].tri >= 0, nobs += ct[c].obs >= 0;
    free(ct);
  }
  printf("two spheres on a rock: %u cells, %u in self contact, %u on the rock\n", o.ncells, nself, nobs);
  uint32_t nin = 0; /* interior cells on the rock */
  {
    sessile_sds_contact *ct = calloc(o.ncells, sizeof *ct);
    t_must("contacts", sessile_sds_contacts(&o, &p, ct));
    for (uint32_t c = 0; c < o.ncells; c++) nin += !o.surface[c] && ct[c].obs >= 0;
    free(ct);
  }
  printf("interior cells on the rock: %u\n", nin);
  t_true("the scene has self and obstacle contacts, interior cells' too", nself > 0 && nobs > 0 && nin > 0);

  /* interior divisions, one after another, lowest cell first (beside the
   * rock and below the surface cells whose neighbours they change): each
   * upload keeps the boundary */
  const double dir_in[3] = {0.3, 1, 0.2};
  int done = 0;
  uint32_t rewired = 0; /* surface cells whose old neighbours changed */
  for (int tries = 0; tries < 80 && done < 6; tries++) {
    /* three interior cells, then three surface cells of the first sphere
     * divided inward (along -x: the daughter goes inside, the boundary stays) */
    int surf = done >= 3;
    uint32_t c = UINT32_MAX;
    for (uint32_t k = 0; k < o.ncells; k++)
      if (o.surface[k] == surf && !tried[k] && (!surf || o.x[3 * k] < 1.0) &&
          (c == UINT32_MAX || o.x[3 * k + 2] < o.x[3 * c + 2]))
        c = k;
    if (c == UINT32_MAX) break;
    tried[c] = 1;
    double in[3] = {-o.x[3 * c], -o.x[3 * c + 1], -o.x[3 * c + 2]};
    const double *dir = surf ? in : dir_in;
    uint32_t nf = o.nfaces, n0 = o.ncells;
    uint32_t *faces = t_xalloc(3 * (size_t)nf * sizeof *faces);
    memcpy(faces, o.face, 3 * (size_t)nf * sizeof *faces);
    sessile_sds before = {0};
    t_must("copy", sessile_sds_copy(&o, &before));
    if (!divide(&o, c, dir)) {
      printf("cell %u: TetGen declined\n", c);
      free(faces);
      sessile_sds_free(&before);
      continue;
    }
    rewired += surface_rewired(&before, &o, n0);
    sessile_sds_free(&before);
    int kept = o.nfaces == nf && !memcmp(faces, o.face, 3 * (size_t)nf * sizeof *faces);
    free(faces);
    uint64_t all0 = 0, part0 = 0, all1 = 0, part1 = 0;
    sessile_sds_gpu_list_builds(s, &all0, &part0);
    t_must("upload", sessile_sds_gpu_upload(s, &o));
    t_must("forces after the division", sessile_sds_gpu_forces(s, 1, f));
    sessile_sds_gpu_list_builds(s, &all1, &part1);
    fresh_forces(g, &o, &p, ref);
    double err = t_relerr(f, ref, 3 * (size_t)o.ncells);
    printf("cell %u divided (%u cells): boundary kept %d, builds +%llu (partial +%llu), forces against a fresh "
           "build %.3g\n",
           c, o.ncells, kept, (unsigned long long)(all1 - all0), (unsigned long long)(part1 - part0), err);
    t_true("an interior or inward division keeps the boundary", kept);
    t_true("and its lists are built again in part, once", all1 - all0 == 1 && part1 - part0 == 1);
    t_check("the forces equal a full build's, bit for bit", err, 0);
    done++;
  }
  printf("surface cells with other neighbours after the divisions: %u\n", rewired);
  t_true("three interior and three surface cells divided", done == 6);

  /* a change of the boundary (its faces moved to other cells) builds every list */
  {
    uint64_t all0 = 0, part0 = 0, all1 = 0, part1 = 0;
    uint32_t c = 0;
    while (c < o.ncells && !o.surface[c]) c++;
    t_true("a surface cell", c < o.ncells);
    const double tangent[3] = {1, 0, 0};
    uint32_t nf = o.nfaces;
    if (divide(&o, c, tangent)) {
      sessile_sds_gpu_list_builds(s, &all0, &part0);
      t_must("upload", sessile_sds_gpu_upload(s, &o));
      t_must("forces", sessile_sds_gpu_forces(s, 1, f));
      sessile_sds_gpu_list_builds(s, &all1, &part1);
      fresh_forces(g, &o, &p, ref);
      printf("surface cell %u divided: faces %u -> %u, builds +%llu (partial +%llu)\n", c, nf, o.nfaces,
             (unsigned long long)(all1 - all0), (unsigned long long)(part1 - part0));
      if (o.nfaces != nf) t_true("a changed boundary builds every list", all1 - all0 == 1 && part1 == part0);
      t_check("the forces equal a full build's", t_relerr(f, ref, 3 * (size_t)o.ncells), 0);
    }
  }
  free(f), free(ref), free(tried);
  sessile_sds_gpu_destroy(s);
  sessile_sds_free(&o);
  sessile_surface_free(&rock);
  return t_finish(g);
}
