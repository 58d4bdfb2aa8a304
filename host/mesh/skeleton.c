/* A coral's skeleton (sessile/mesh/skeleton.h): storage, bounds and the tube mesh.
 * The welded surface lives in weld.c (GPU) and weld_ref.c (host reference). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/skeleton.h"

void sessile_skeleton_free(sessile_skeleton *s) {
  if (!s) return;
  free(s->a), free(s->b), free(s->ra), free(s->rb), free(s->up), free(s->value);
  memset(s, 0, sizeof *s);
}

static sessile_status grow(sessile_skeleton *s, uint32_t need) {
  if (need <= s->cap) return SESSILE_OK;
  SESSILE_CHECK(need < UINT32_MAX / 2, SESSILE_ERR_NO_MEMORY, "a skeleton of %u segments is too large", need);
  uint32_t cap = s->cap ? s->cap : 64;
  while (cap < need) cap *= 2;
  double **v3[3] = {&s->a, &s->b, &s->up}, **v1[3] = {&s->ra, &s->rb, &s->value};
  for (int k = 0; k < 3; k++) {
    double *p = realloc(*v3[k], (size_t)cap * 3 * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %u skeleton segments", cap);
    *v3[k] = p;
    p = realloc(*v1[k], (size_t)cap * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %u skeleton segments", cap);
    *v1[k] = p;
  }
  s->cap = cap;
  return SESSILE_OK;
}

static double dot3(const double *x, const double *y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
static void cross3(const double *x, const double *y, double *o) {
  o[0] = x[1] * y[2] - x[2] * y[1], o[1] = x[2] * y[0] - x[0] * y[2], o[2] = x[0] * y[1] - x[1] * y[0];
}

/* up made unit and normal to d = b - a; any normal when up is parallel to d. */
static void normal_frame(const double d[3], const double up[3], double out[3]) {
  double l2 = dot3(d, d), u[3] = {up[0], up[1], up[2]};
  double k = l2 > 0 ? dot3(u, d) / l2 : 0;
  for (int i = 0; i < 3; i++) u[i] -= k * d[i];
  double l = sqrt(dot3(u, u));
  if (!(l > 1e-12 * sqrt(l2 > 0 ? l2 : 1))) {
    /* the axis least aligned with d, made normal to it */
    double e[3] = {0, 0, 0};
    int m = fabs(d[0]) <= fabs(d[1]) ? (fabs(d[0]) <= fabs(d[2]) ? 0 : 2) : (fabs(d[1]) <= fabs(d[2]) ? 1 : 2);
    e[m] = 1;
    cross3(d, e, u);
    l = sqrt(dot3(u, u));
    if (!(l > 0)) u[0] = 1, u[1] = u[2] = 0, l = 1;
  }
  for (int i = 0; i < 3; i++) out[i] = u[i] / l;
}

sessile_status sessile_skeleton_add(sessile_skeleton *s, const double a[3], const double b[3], double ra,
                                    double rb, const double up[3], double value) {
  SESSILE_CHECK(isfinite(a[0] + a[1] + a[2] + b[0] + b[1] + b[2] + ra + rb + value) && ra > 0 && rb > 0,
                SESSILE_ERR_USAGE, "a skeleton segment needs finite ends and positive radii (got %g, %g)", ra, rb);
  SESSILE_CALL(grow(s, s->n + 1));
  uint32_t i = s->n++;
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, u[3];
  normal_frame(d, up, u);
  memcpy(s->a + 3 * i, a, 3 * sizeof *a);
  memcpy(s->b + 3 * i, b, 3 * sizeof *b);
  memcpy(s->up + 3 * i, u, sizeof u);
  s->ra[i] = ra, s->rb[i] = rb, s->value[i] = value;
  return SESSILE_OK;
}

void sessile_skeleton_bounds(const sessile_skeleton *s, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
  for (uint32_t i = 0; i < s->n; i++)
    for (int k = 0; k < 3; k++) {
      double a = s->a[3 * i + k], b = s->b[3 * i + k];
      lo[k] = fmin(lo[k], fmin(a - s->ra[i], b - s->rb[i]));
      hi[k] = fmax(hi[k], fmax(a + s->ra[i], b + s->rb[i]));
    }
}

sessile_status sessile_skeleton_tubes(const sessile_skeleton *s, int sides, sessile_surface *out,
                                      double **vertex_value) {
  return sessile_skeleton_tubes_stop(s, sides, NULL, out, vertex_value);
}

sessile_status sessile_skeleton_tubes_stop(const sessile_skeleton *s, int sides, const volatile sig_atomic_t *stop,
                                           sessile_surface *out, double **vertex_value) {
  if (vertex_value) *vertex_value = NULL;
  SESSILE_CHECK(sides >= 3 && sides <= 256, SESSILE_ERR_USAGE, "tube sides must be in 3..256 (got %d)", sides);
  /* per tube: two rings and two cap centres; 2 sides wall triangles and
   * 2 sides cap triangles */
  uint64_t nv = (uint64_t)s->n * (2 * (uint64_t)sides + 2), nf = (uint64_t)s->n * 4 * (uint64_t)sides;
  SESSILE_CHECK(nv < UINT32_MAX && nf < UINT32_MAX / 3, SESSILE_ERR_NO_MEMORY,
                "%u segments with %d sides make %llu vertices: too many for one mesh", s->n, sides,
                (unsigned long long)nv);
  sessile_surface_free(out);
  SESSILE_CALL(sessile_surface_reserve(out, (uint32_t)nv, (uint32_t)nf));
  double *val = NULL;
  if (vertex_value) {
    val = malloc((size_t)(nv ? nv : 1) * sizeof *val);
    SESSILE_CHECK(val, SESSILE_ERR_NO_MEMORY, "out of host memory for %llu vertex values", (unsigned long long)nv);
  }
  double *cs = malloc(2 * (size_t)sides * sizeof *cs);
  if (!cs) {
    free(val);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  for (int k = 0; k < sides; k++) {
    double t = 6.283185307179586 * k / sides;
    cs[2 * k] = cos(t), cs[2 * k + 1] = sin(t);
  }
  uint32_t v = 0, f = 0;
  for (uint32_t i = 0; i < s->n; i++) {
    if (stop && (i & 4095) == 0 && *stop) {
      free(cs), free(val);
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d while meshing tubes", (int)*stop);
    }
    const double *a = s->a + 3 * i, *b = s->b + 3 * i, *u = s->up + 3 * i;
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3];
    double l = sqrt(dot3(d, d));
    if (l > 0) d[0] /= l, d[1] /= l, d[2] /= l;
    cross3(d, u, w); /* (u, w, d) right-handed: rings run counter-clockwise about d */
    uint32_t base = v;
    for (int e = 0; e < 2; e++) {
      const double *c = e ? b : a;
      double r = e ? s->rb[i] : s->ra[i];
      for (int k = 0; k < sides; k++, v++)
        for (int j = 0; j < 3; j++) out->pos[3 * v + j] = c[j] + r * (cs[2 * k] * u[j] + cs[2 * k + 1] * w[j]);
    }
    for (int j = 0; j < 3; j++) out->pos[3 * v + j] = a[j], out->pos[3 * (v + 1) + j] = b[j];
    uint32_t ca = v, cb = v + 1;
    v += 2;
    for (int k = 0; k < sides; k++) {
      uint32_t k1 = (uint32_t)((k + 1) % sides);
      uint32_t a0 = base + (uint32_t)k, a1 = base + k1, b0 = base + (uint32_t)sides + (uint32_t)k,
               b1 = base + (uint32_t)sides + k1;
      uint32_t t[4][3] = {{a0, a1, b1}, {a0, b1, b0}, {ca, a1, a0}, {cb, b0, b1}};
      for (int q = 0; q < 4; q++, f++) memcpy(out->tri + 3 * f, t[q], sizeof t[q]);
    }
    if (val)
      for (uint32_t q = base; q < v; q++) val[q] = s->value[i];
  }
  out->nv = v, out->nf = f;
  free(cs);
  if (vertex_value) *vertex_value = val;
  return SESSILE_OK;
}
