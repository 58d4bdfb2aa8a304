/* The cut-cell sphere problem (matrix.h: sessile_cut_sphere): the test and
 * benchmark geometry of the multigrid, generated the same way on every level
 * so that nested levels are rediscretisations of one domain. */
#include <math.h>
#include "sessile/bench/matrix_gen.h"

typedef struct {
  uint32_t n[3];
  double h, c[3], r2;
} sphere;

static double sq(double v) { return v * v; }

static int inside(const sphere *s, int64_t i, int64_t j, int64_t k) {
  return sq(i * s->h - s->c[0]) + sq(j * s->h - s->c[1]) + sq(k * s->h - s->c[2]) < s->r2;
}

/* Fraction along the edge from outside node p to inside node p + e where the
 * sphere is crossed: the smaller root of |d + t e|^2 = r^2, d = p - c, in the
 * form that does not cancel. */
static double theta(const sphere *s, const int64_t p[3], int axis, int dir) {
  double d[3], de, dd = 0;
  for (int a = 0; a < 3; a++) {
    d[a] = p[a] * s->h - s->c[a];
    dd += d[a] * d[a];
  }
  de = dir * s->h * d[axis];
  double c0 = dd - s->r2, disc = de * de - s->h * s->h * c0;
  double t = c0 / (-de + sqrt(disc > 0 ? disc : 0));
  return t > 1e-3 ? (t < 1 ? t : 1) : 1e-3;
}

void sessile_cut_sphere(uint32_t nx, uint32_t ny, uint32_t nz, double h, const double centre[3],
                        double radius, uint32_t *mask, double *diag, double *b) {
  sphere s = {{nx, ny, nz}, h, {centre[0], centre[1], centre[2]}, radius * radius};
  const int64_t s1 = nx, s2 = (int64_t)nx * ny;
#pragma omp parallel for schedule(static)
  for (int64_t k = 0; k < (int64_t)nz; k++)
    for (int64_t j = 0; j < ny; j++)
      for (int64_t i = 0; i < nx; i++) {
        int64_t n = i + s1 * j + s2 * k, p[3] = {i, j, k};
        mask[n] = inside(&s, i, j, k) || k == 0 || k == (int64_t)nz - 1;
        diag[n] = 1;
        if (b) b[n] = 0;
        if (mask[n]) continue;
        double half[3];
        for (int a = 0; a < 3; a++) half[a] = p[a] == 0 || p[a] == (int64_t)s.n[a] - 1 ? 0.5 : 1;
        double d = 0, rhs = 0;
        for (int a = 0; a < 3; a++)
          for (int dir = -1; dir <= 1; dir += 2) {
            int64_t q[3] = {i, j, k};
            q[a] += dir;
            if (q[a] < 0 || q[a] >= (int64_t)s.n[a]) continue; /* zero-flux wall */
            double f = half[(a + 1) % 3] * half[(a + 2) % 3];
            if (inside(&s, q[0], q[1], q[2])) {
              d += f / theta(&s, p, a, dir); /* a cut edge; u = 0 on the sphere */
            } else {
              d += f;                                     /* w = 1 */
              if (q[2] == (int64_t)nz - 1) rhs += f;      /* u = 1 on the top plane */
            }
          }
        diag[n] = d;
        if (b) b[n] = h * rhs;
      }
}
