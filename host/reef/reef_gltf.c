/* The reef as a glTF scene (docs/reef.md, "Output"): the seabed as mesh 0,
 * one mesh per distinct organism (a standard brush's entry once, every
 * automatic or grown placement its own), one node per placement.  All in
 * centimetres, z up: the writer converts (metres_per_unit 0.01). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "reef/reef_internal.h"

#define CM 100.0

static sessile_status seabed_mesh(const sessile_reef_seabed *b, sessile_surface *s) {
  SESSILE_CHECK((uint64_t)b->nx * b->ny < UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "the seabed is too large a mesh");
  SESSILE_CALL(sessile_surface_reserve(s, b->nx * b->ny, 2 * (b->nx - 1) * (b->ny - 1)));
  double dx = b->extent[0] / (b->nx - 1), dy = b->extent[1] / (b->ny - 1);
  for (uint32_t j = 0; j < b->ny; j++)
    for (uint32_t i = 0; i < b->nx; i++) {
      double *p = s->pos + 3 * ((size_t)j * b->nx + i);
      p[0] = i * dx * CM, p[1] = j * dy * CM, p[2] = b->h[(size_t)j * b->nx + i] * CM;
    }
  for (uint32_t j = 0; j + 1 < b->ny; j++)
    for (uint32_t i = 0; i + 1 < b->nx; i++) {
      uint32_t a = j * b->nx + i, *t = s->tri + 6 * ((size_t)j * (b->nx - 1) + i);
      t[0] = a, t[1] = a + 1, t[2] = a + b->nx + 1, t[3] = a, t[4] = a + b->nx + 1, t[5] = a + b->nx;
    }
  s->nv = b->nx * b->ny, s->nf = 2 * (b->nx - 1) * (b->ny - 1);
  return SESSILE_OK;
}

/* Moves the organism so that its base (lowest z, centre of its bounding
 * box in x and y) is the origin; returns its footprint radius (cm). */
static double base_at_origin(sessile_surface *s) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, r = 0;
  for (uint32_t v = 0; v < s->nv; v++)
    for (int a = 0; a < 3; a++) {
      lo[a] = fmin(lo[a], s->pos[3 * v + a]);
      if (a < 2) hi[a] = fmax(hi[a], s->pos[3 * v + a]);
    }
  double c[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2]};
  for (uint32_t v = 0; v < s->nv; v++) {
    double *p = s->pos + 3 * v;
    for (int a = 0; a < 3; a++) p[a] -= c[a];
    r = fmax(r, hypot(p[0], p[1]));
  }
  return r;
}

static void mul3(const double a[9], const double b[9], double out[9]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}

/* Column-major 4x4 (cm): translate to the base, turn +z to the up axis,
 * the random rotations about the organism's x, y then z... applied as
 * Rz Ry Rx, and scale the footprint radius to the placement's size. */
static void transform(const sessile_reef_placement *p, double radius_cm, double m[16]) {
  const double *u = p->up;
  double c = u[2], k = 1 / (1 + c), v[3] = {-u[1], u[0], 0};
  double up[9] = {1 - k * v[1] * v[1], k * v[0] * v[1], v[1], k * v[0] * v[1], 1 - k * v[0] * v[0], -v[0],
                  -v[1], v[0], c};
  double cx = cos(p->angle[0]), sx = sin(p->angle[0]), cy = cos(p->angle[1]), sy = sin(p->angle[1]);
  double cz = cos(p->angle[2]), sz = sin(p->angle[2]);
  double rx[9] = {1, 0, 0, 0, cx, -sx, 0, sx, cx}, ry[9] = {cy, 0, sy, 0, 1, 0, -sy, 0, cy};
  double rz[9] = {cz, -sz, 0, sz, cz, 0, 0, 0, 1}, t1[9], t2[9], r[9];
  mul3(rz, ry, t1), mul3(t1, rx, t2), mul3(up, t2, r);
  double s = radius_cm > 0 ? p->size * CM / radius_cm : 1;
  memset(m, 0, 16 * sizeof *m);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) m[4 * j + i] = r[3 * i + j] * s;
  for (int i = 0; i < 3; i++) m[12 + i] = p->pos[i] * CM;
  m[15] = 1;
}

/* The organism's scalars' PLY names as glTF custom attributes, as --glb
 * names them (io's sessile_gltf_attribute_name). */
static sessile_status attribute_names(sessile_reef_scalars *sc) {
  for (uint32_t i = 0; i < sc->n; i++) {
    char *a = sessile_gltf_attribute_name(sc->names[i]);
    SESSILE_CHECK(a, SESSILE_ERR_NO_MEMORY, "out of host memory");
    free(sc->names[i]), sc->names[i] = a;
  }
  return SESSILE_OK;
}

static sessile_status organisms(const sessile_reef_scene *s, const sessile_reef_placements *pl,
                                sessile_reef_organism_fn fn, void *ctx, sessile_reef_gltf *g) {
  uint32_t *standard = malloc((size_t)s->nentries * sizeof *standard);
  SESSILE_CHECK(standard, SESSILE_ERR_NO_MEMORY, "out of host memory");
  memset(standard, 0xFF, (size_t)s->nentries * sizeof *standard);
  sessile_status st = SESSILE_OK;
  for (uint32_t k = 0; k < pl->n && st == SESSILE_OK; k++) {
    const sessile_reef_placement *p = &pl->p[k];
    const sessile_reef_entry *e = &s->entries[p->entry];
    if (!p->automatic && standard[p->entry] != UINT32_MAX) {
      g->node_mesh[k] = standard[p->entry];
      continue;
    }
    /* a standard entry's one mesh: the generator's default seed 1, no current */
    uint32_t m = g->scene.nmeshes;
    st = fn(ctx, e, p->automatic ? p->seed : 1, p->automatic ? p->exposure : 0, &g->surfaces[m], &g->scalars[m]);
    if (st == SESSILE_OK) st = attribute_names(&g->scalars[m]);
    if (st != SESSILE_OK) { /* what the callback had made of mesh m, which nmeshes does not count */
      sessile_surface_free(&g->surfaces[m]), sessile_reef_scalars_free(&g->scalars[m]);
      st = sessile_error_pass(st, "pool[%u] (%s)", p->entry, e->generator);
      break;
    }
    g->radius_cm[m] = base_at_origin(&g->surfaces[m]);
    g->node_mesh[k] = m, g->scene.nmeshes++;
    if (!p->automatic) standard[p->entry] = m;
  }
  free(standard);
  return st;
}

sessile_status sessile_reef_gltf_make(const sessile_reef_scene *s, const sessile_reef_seabed *b,
                                      const sessile_reef_placements *pl, sessile_reef_organism_fn fn, void *ctx,
                                      sessile_reef_gltf *g) {
  memset(g, 0, sizeof *g);
  size_t nm = (size_t)pl->n + 1;
  g->surfaces = calloc(nm, sizeof *g->surfaces), g->scalars = calloc(nm, sizeof *g->scalars), g->radius_cm = calloc(nm, sizeof *g->radius_cm);
  g->meshes = calloc(nm, sizeof *g->meshes), g->nodes = calloc(nm, sizeof *g->nodes);
  g->node_mesh = calloc(nm, sizeof *g->node_mesh), g->names = calloc(2 * nm, sizeof *g->names);
  g->materials = calloc((size_t)s->nentries + 1, sizeof *g->materials);
  if (!g->surfaces || !g->scalars || !g->radius_cm || !g->meshes || !g->nodes || !g->node_mesh || !g->materials || !g->names) {
    sessile_reef_gltf_free(g);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u placements", pl->n);
  }
  sessile_status st = seabed_mesh(b, &g->surfaces[0]);
  g->scene.nmeshes = 1;
  if (st == SESSILE_OK) st = organisms(s, pl, fn, ctx, g);
  if (st != SESSILE_OK) {
    sessile_reef_gltf_free(g);
    return st;
  }
  g->materials[0] = (sessile_gltf_material){"seabed", {0.76f, 0.70f, 0.50f, 1}, 0, 0.9f};
  for (int e = 0; e < s->nentries; e++)
    g->materials[e + 1] = (sessile_gltf_material){s->entries[e].name, {s->entries[e].rgba[0], s->entries[e].rgba[1],
                                                   s->entries[e].rgba[2], s->entries[e].rgba[3]},
                                                  0, s->entries[e].roughness};
  for (uint32_t m = 0; m < g->scene.nmeshes; m++)
    g->meshes[m] = (sessile_gltf_mesh){.name = g->names[m], .nv = g->surfaces[m].nv, .nt = g->surfaces[m].nf,
                                       .pos = g->surfaces[m].pos, .tri = g->surfaces[m].tri,
                                       .nscalars = g->scalars[m].n,
                                       .scalar_names = (const char *const *)g->scalars[m].names,
                                       .scalars = (const float *const *)g->scalars[m].values};
  snprintf(g->names[0], sizeof g->names[0], "seabed");
  snprintf(g->names[nm], sizeof g->names[0], "seabed");
  g->nodes[0] = (sessile_gltf_node){g->names[nm], 0, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
  for (uint32_t k = 0; k < pl->n; k++) {
    uint32_t m = g->node_mesh[k];
    const char *entry = s->entries[pl->p[k].entry].name;
    g->meshes[m].material = pl->p[k].entry + 1;
    /* a mesh is named by its first placement's entry and the mesh index */
    if (!g->names[m][0]) snprintf(g->names[m], sizeof g->names[m], "%.40s %u", entry, m);
    snprintf(g->names[nm + k + 1], sizeof g->names[0], "%.40s %u", entry, k);
    g->nodes[k + 1].name = g->names[nm + k + 1], g->nodes[k + 1].mesh = m;
    transform(&pl->p[k], g->radius_cm[m], g->nodes[k + 1].matrix);
  }
  g->scene.meshes = g->meshes, g->scene.materials = g->materials, g->scene.nmaterials = (uint32_t)s->nentries + 1;
  g->scene.nodes = g->nodes, g->scene.nnodes = pl->n + 1, g->scene.metres_per_unit = 0.01;
  return SESSILE_OK;
}

void sessile_reef_gltf_free(sessile_reef_gltf *g) {
  if (!g) return;
  for (uint32_t m = 0; g->surfaces && m < g->scene.nmeshes; m++) sessile_surface_free(&g->surfaces[m]);
  for (uint32_t m = 0; g->scalars && m < g->scene.nmeshes; m++) sessile_reef_scalars_free(&g->scalars[m]);
  free(g->surfaces), free(g->scalars), free(g->radius_cm), free(g->meshes), free(g->nodes), free(g->node_mesh), free(g->materials), free(g->names);
  memset(g, 0, sizeof *g);
}

void sessile_reef_scalars_free(sessile_reef_scalars *s) {
  if (!s) return;
  for (uint32_t i = 0; i < s->n; i++) {
    if (s->names) free(s->names[i]);
    if (s->values) free(s->values[i]);
  }
  free(s->names), free(s->values);
  memset(s, 0, sizeof *s);
}
