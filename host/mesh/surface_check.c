/* The surface invariants (sessile_surface_check): what every remesh must
 * preserve.  Sort-based and O(n): half-edges are radix-sorted as 64-bit keys
 * (from << 32 | to) beside their reversals; the two lists agree exactly when
 * every edge has one twin running the other way. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"
#include "sessile/mesh/surface.h"

typedef struct { uint32_t v[3], f; } sorted_tri;

static int cmp_tri(const void *a, const void *b) {
  const sorted_tri *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
  return (x->f > y->f) - (x->f < y->f);
}

/* The triangles holding directed edge a->b (for messages only: linear). */
static void faces_with(const sessile_surface *s, uint32_t a, uint32_t b, uint32_t out[2]) {
  out[0] = out[1] = UINT32_MAX;
  int n = 0;
  for (uint32_t f = 0; f < s->nf && n < 2; f++)
    for (int c = 0; c < 3; c++)
      if (s->tri[3 * f + c] == a && s->tri[3 * f + (c + 1) % 3] == b) out[n++] = f;
}

/* Every directed edge a->b must be unique and have its twin b->a: then the
 * sorted keys equal the sorted reversed keys, element by element. */
static sessile_status check_edges(const sessile_surface *s, uint64_t *key, uint64_t *rev,
                                  uint64_t *tmp) {
  size_t nh = (size_t)s->nf * 3;
  for (uint32_t f = 0; f < s->nf; f++)
    for (int c = 0; c < 3; c++) {
      uint64_t a = s->tri[3 * f + c], b = s->tri[3 * f + (c + 1) % 3];
      key[3 * f + c] = a << 32 | b;
      rev[3 * f + c] = b << 32 | a;
    }
  mesh_sort_u64(key, tmp, nh);
  for (size_t i = 0; i + 1 < nh; i++)
    if (key[i] == key[i + 1]) {
      uint32_t a = (uint32_t)(key[i] >> 32), b = (uint32_t)key[i], f[2];
      faces_with(s, a, b, f);
      return sessile_error_set(SESSILE_ERR_INTERNAL,
                               "surface: directed edge %u->%u is in two triangles (%u and %u): "
                               "the surface is non-manifold there or a triangle is flipped",
                               a, b, f[0], f[1]);
    }
  mesh_sort_u64(rev, tmp, nh);
  for (size_t i = 0; i < nh; i++)
    if (key[i] != rev[i]) {
      /* The smaller one is in one list only: key[i] = a->b lacks b->a, or
       * rev[i] = b->a is the reverse of a key a->b that lacks its twin. */
      uint64_t k = key[i] < rev[i] ? key[i] : rev[i] << 32 | rev[i] >> 32;
      uint32_t a = (uint32_t)(k >> 32), b = (uint32_t)k, f[2];
      faces_with(s, a, b, f);
      return sessile_error_set(SESSILE_ERR_INTERNAL,
                               "surface: edge %u-%u of triangle %u has no triangle on its other "
                               "side running %u->%u: the surface has a hole, an edge in an odd "
                               "number of triangles, or a flipped triangle",
                               a, b, f[0], b, a);
    }
  return SESSILE_OK;
}

static void sort3(uint32_t v[3]) {
  if (v[0] > v[1]) { uint32_t x = v[0]; v[0] = v[1]; v[1] = x; }
  if (v[1] > v[2]) { uint32_t x = v[1]; v[1] = v[2]; v[2] = x; }
  if (v[0] > v[1]) { uint32_t x = v[0]; v[0] = v[1]; v[1] = x; }
}

static sessile_status duplicate_error(const sessile_surface *s, const uint32_t v[3]) {
  uint32_t f[2] = {UINT32_MAX, UINT32_MAX}, n = 0;
  for (uint32_t g = 0; g < s->nf && n < 2; g++) {
    uint32_t w[3];
    memcpy(w, s->tri + 3 * g, sizeof w);
    sort3(w);
    if (!memcmp(v, w, sizeof w)) f[n++] = g;
  }
  return sessile_error_set(SESSILE_ERR_INTERNAL,
                           "surface: triangles %u and %u have the same vertices {%u %u %u}", f[0],
                           f[1], v[0], v[1], v[2]);
}

/* Sorted vertex triples: packed into 64-bit keys and radix-sorted when the
 * indices fit in 21 bits (2M vertices), else qsort. */
static sessile_status check_duplicates(const sessile_surface *s, uint64_t *key, uint64_t *tmp,
                                       sorted_tri *t) {
  if (s->nv <= (1u << 21)) {
    for (uint32_t f = 0; f < s->nf; f++) {
      uint32_t v[3];
      memcpy(v, s->tri + 3 * f, sizeof v);
      sort3(v);
      key[f] = (uint64_t)v[0] << 42 | (uint64_t)v[1] << 21 | v[2];
    }
    mesh_sort_u64(key, tmp, s->nf);
    for (uint32_t i = 0; i + 1 < s->nf; i++)
      if (key[i] == key[i + 1]) {
        uint32_t v[3] = {(uint32_t)(key[i] >> 42), (uint32_t)(key[i] >> 21) & 0x1FFFFF,
                         (uint32_t)key[i] & 0x1FFFFF};
        return duplicate_error(s, v);
      }
    return SESSILE_OK;
  }
  for (uint32_t f = 0; f < s->nf; f++) {
    memcpy(t[f].v, s->tri + 3 * f, sizeof t[f].v);
    sort3(t[f].v);
    t[f].f = f;
  }
  qsort(t, s->nf, sizeof *t, cmp_tri);
  for (uint32_t i = 0; i + 1 < s->nf; i++)
    if (!memcmp(t[i].v, t[i + 1].v, sizeof t[i].v)) return duplicate_error(s, t[i].v);
  return SESSILE_OK;
}

sessile_status sessile_surface_check(const sessile_surface *s, int euler, double min_area) {
  SESSILE_CHECK(s, SESSILE_ERR_USAGE, "surface check: no surface given");
  SESSILE_CHECK(s->nf > 0 && s->nv > 0, SESSILE_ERR_INTERNAL,
                "surface: empty (%u vertices, %u triangles)", s->nv, s->nf);
  SESSILE_CHECK(s->nf <= UINT32_MAX / 3, SESSILE_ERR_TOO_LARGE, "surface: %u triangles is too many",
                s->nf);
  for (uint32_t f = 0; f < s->nf; f++) {
    const uint32_t *t = s->tri + 3 * f;
    for (int c = 0; c < 3; c++)
      SESSILE_CHECK(t[c] < s->nv, SESSILE_ERR_INTERNAL,
                    "surface: triangle %u corner %d is vertex %u but there are only %u vertices", f,
                    c, t[c], s->nv);
    SESSILE_CHECK(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], SESSILE_ERR_INTERNAL,
                  "surface: triangle %u (%u %u %u) repeats a vertex", f, t[0], t[1], t[2]);
  }
  size_t nh = (size_t)s->nf * 3;
  uint64_t *key = malloc(nh * sizeof *key), *tmp = malloc(nh * sizeof *tmp);
  uint64_t *rev = malloc(nh * sizeof *rev);
  sorted_tri *st = s->nv > (1u << 21) ? malloc((size_t)s->nf * sizeof *st) : NULL;
  uint8_t *used = calloc(s->nv, 1);
  sessile_status r = SESSILE_OK;
  if (!key || !tmp || !rev || (!st && s->nv > (1u << 21)) || !used) {
    r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory checking a surface of %u "
                          "triangles", s->nf);
    goto done;
  }
  if ((r = check_edges(s, key, rev, tmp)) != SESSILE_OK) goto done;
  if ((r = check_duplicates(s, key, tmp, st)) != SESSILE_OK) goto done;
  for (size_t k = 0; k < nh; k++) used[s->tri[k]] = 1;
  for (uint32_t v = 0; v < s->nv; v++)
    if (!used[v]) {
      r = sessile_error_set(SESSILE_ERR_INTERNAL, "surface: vertex %u is in no triangle", v);
      goto done;
    }
  {
    long long V = s->nv, E = (long long)nh / 2, F = s->nf, chi = V - E + F;
    if (chi != euler) {
      r = sessile_error_set(SESSILE_ERR_INTERNAL,
                            "surface: Euler characteristic V - E + F = %lld - %lld + %lld = %lld, "
                            "expected %d (a handle or a separate piece appeared)",
                            V, E, F, chi, euler);
      goto done;
    }
  }
  for (uint32_t f = 0; f < s->nf; f++) {
    double c[3];
    mesh_face_cross(s->pos, s->tri + 3 * f, c);
    double area = 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(area > min_area)) { /* NaN fails too */
      const uint32_t *t = s->tri + 3 * f;
      r = sessile_error_set(SESSILE_ERR_INTERNAL,
                            "surface: triangle %u (%u %u %u) has area %g, not above %g", f, t[0],
                            t[1], t[2], area, min_area);
      goto done;
    }
  }
done:
  free(key), free(tmp), free(rev), free(st), free(used);
  return r;
}
