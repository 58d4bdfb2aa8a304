/* The reef's glTF scene (sessile_reef_gltf_make; docs/reef.md, "Output"):
 * node count = placements + the seabed, one mesh per standard entry and per
 * automatic placement, a material per entry, node matrices that put the
 * base on the placement, +z on its up axis and the footprint at its size. */
#include <math.h>
#include <stdio.h>
#include "reef_test_scene.h"

static int calls, fail_at = -1;

/* A stand-in organism: an icosphere of radius 5 cm whose centre sits 3 cm off
 * in x, so the base-at-origin shift is seen, with one scalar "t.k" = the
 * vertex's index (as a PLY's vertex property). */
static sessile_status organism(void *ctx, const sessile_reef_entry *e, uint64_t seed, double exposure,
                               sessile_surface *out, sessile_reef_scalars *sc) {
  (void)ctx, (void)e, (void)seed, (void)exposure;
  if (calls++ == fail_at) return sessile_error_set(SESSILE_ERR_USAGE, "the stand-in fails");
  SESSILE_CALL(sessile_surface_icosphere(2, 5, (const double[3]){3, 0, 7}, out));
  sc->names = calloc(1, sizeof *sc->names), sc->values = calloc(1, sizeof *sc->values);
  if (sc->names && sc->values) sc->n = 1, sc->names[0] = malloc(4), sc->values[0] = malloc(out->nv * sizeof(float));
  if (!sc->names || !sc->values || !sc->names[0] || !sc->values[0]) return sessile_error_set(SESSILE_ERR_NO_MEMORY, "oom");
  memcpy(sc->names[0], "t.k", 4);
  for (uint32_t v = 0; v < out->nv; v++) sc->values[0][v] = (float)v;
  return SESSILE_OK;
}

static const char *json =
    "{\"seabed\": {\"noise\": {\"resolution\": [17, 9], \"extent\": [16, 8], \"height_scale\": 1, \"base\": -5}},"
    " \"pool\": [{\"name\": \"a\", \"generator\": \"g\", \"colour\": [1, 0, 0, 1], \"rotate\": [\"x\", \"z\"]},"
    "  {\"name\": \"b\", \"generator\": \"g\", \"colour\": [0, 0, 1, 1]}],"
    " \"brushes\": [{\"points\": [[4, 4]], \"size\": 3, \"density\": 12},"
    "  {\"points\": [[12, 4]], \"size\": 3, \"density\": 12, \"kind\": \"automatic\"}]}";

int main(void) {
  sessile_reef_scene s;
  sessile_reef_seabed b;
  sessile_reef_placements pl;
  sessile_reef_gltf g;
  rt_parse(json, &s);
  t_must("seabed", sessile_reef_seabed_make(&s, &b));
  t_must("place", sessile_reef_place(&s, &b, 9, &pl));
  t_must("the glTF scene", sessile_reef_gltf_make(&s, &b, &pl, organism, NULL, &g));
  uint32_t automatic = 0, entries_std[2] = {0};
  for (uint32_t k = 0; k < pl.n; k++) {
    automatic += pl.p[k].automatic;
    if (!pl.p[k].automatic) entries_std[pl.p[k].entry] = 1;
  }
  printf("%u placements, %u automatic, %u meshes\n", pl.n, automatic, g.scene.nmeshes);
  t_true("both brushes placed", automatic > 3 && automatic + 3 < pl.n);
  t_true("nodes = placements + the seabed", g.scene.nnodes == pl.n + 1);
  t_true("meshes = the seabed + one per standard entry + one per automatic placement",
         g.scene.nmeshes == 1 + entries_std[0] + entries_std[1] + automatic && (uint32_t)calls == g.scene.nmeshes - 1);
  t_true("materials = the seabed's + one per entry", g.scene.nmaterials == 3 && g.materials[1].rgba[0] == 1 &&
                                                         g.materials[2].rgba[2] == 1);
  t_true("the seabed mesh", g.meshes[0].nv == 17 * 9 && g.meshes[0].nt == 2 * 16 * 8 && g.scene.metres_per_unit == 0.01);
  int named = 1;
  for (uint32_t m = 0; m < g.scene.nmeshes; m++) named &= g.meshes[m].name && g.meshes[m].name[0];
  for (uint32_t k = 0; k < g.scene.nnodes; k++) named &= g.nodes[k].name && g.nodes[k].name[0];
  t_true("every mesh and node is named", named && !strncmp(g.nodes[1].name, s.entries[pl.p[0].entry].name, 1) &&
                                                g.nodes[1].name[1] == ' ');
  double base = 0, axis = 0, foot = 0, mat = 0;
  for (uint32_t k = 0; k < pl.n; k++) {
    const sessile_reef_placement *p = &pl.p[k];
    const double *m = g.nodes[k + 1].matrix;
    const sessile_gltf_mesh *me = &g.meshes[g.nodes[k + 1].mesh];
    mat += me->material != p->entry + 1;
    for (int i = 0; i < 3; i++) base = fmax(base, fabs(m[12 + i] - 100 * p->pos[i]));
    /* the mesh's lowest point lies at its origin, its footprint radius is 5 cm */
    double zmin = INFINITY, r = 0;
    for (uint32_t v = 0; v < me->nv; v++)
      zmin = fmin(zmin, me->pos[3 * v + 2]), r = fmax(r, hypot(me->pos[3 * v], me->pos[3 * v + 1]));
    base = fmax(base, fabs(zmin));
    double sc = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    foot = fmax(foot, fabs(sc * r - 100 * p->size));
    if (p->angle[0] == 0 && p->angle[1] == 0) /* z of the organism along its up axis */
      for (int i = 0; i < 3; i++) axis = fmax(axis, fabs(m[8 + i] / sc - p->up[i]));
  }
  t_check("node translation = base on the seabed (cm)", base, 1e-9);
  t_check("organism +z = the placement's up axis", axis, 1e-12);
  t_check("footprint radius = the placement's size (cm)", foot, 1e-9);
  t_check("meshes with another entry's material", mat, 0);
  int scal = g.meshes[0].nscalars == 0;
  for (uint32_t m = 1; m < g.scene.nmeshes; m++) {
    scal &= g.meshes[m].nscalars == 1 && !strcmp(g.meshes[m].scalar_names[0], "_T_K");
    for (uint32_t v = 0; scal && v < g.meshes[m].nv; v++) scal &= g.meshes[m].scalars[0][v] == (float)v;
  }
  t_true("each organism mesh carries its scalar as _T_K (io's attribute name), the seabed none", scal);
  sessile_reef_gltf_free(&g);
  calls = 0, fail_at = 2;
  sessile_status st = sessile_reef_gltf_make(&s, &b, &pl, organism, NULL, &g);
  t_true("an organism's failure names its pool entry",
         st == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "pool[") &&
             strstr(sessile_error_message(), "the stand-in fails"));
  sessile_reef_placements_free(&pl), sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);
  return t_finish(NULL);
}
