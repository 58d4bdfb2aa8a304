/* Morphogen diffusion and decay, §3.3: the paper's capped discrete Laplacian
 * with explicit Euler.  Plain-C reference of shaders/sds/morph_step.comp:
 * the operations are written in the kernel's order so both give the same
 * doubles (docs/sds_morphogens.md). */
#include <math.h>
#include <stdlib.h>
#include "sessile/sds/sds_process.h"

/* 4/3 pi, rounded as the kernel rounds its literal (4.0lf / 3.0lf * pi). */
static const double FOUR_THIRDS_PI = 4.0 / 3.0 * 3.14159265358979311600;

double sessile_morph_vol(double r) { return FOUR_THIRDS_PI * r * r * r; }

static double dist(const double *pos, int a, int b) {
  double dx = pos[3 * a] - pos[3 * b], dy = pos[3 * a + 1] - pos[3 * b + 1], dz = pos[3 * a + 2] - pos[3 * b + 2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

double sessile_morph_laplacian(const sessile_morph_cells *cl, int nmorph, const double *phi, int c, int k) {
  double vc = sessile_morph_vol(cl->radius[c]), pc = phi[(size_t)c * nmorph + k], s = 0;
  for (uint32_t q = cl->nbr_off[c]; q < cl->nbr_off[c + 1]; q++) {
    int n = (int)cl->nbr[q];
    double vn = sessile_morph_vol(cl->radius[n]), pn = phi[(size_t)n * nmorph + k];
    s += (fmin(pn, vc) - fmin(pc, vn)) / dist(cl->pos, c, n);
  }
  return s;
}

double sessile_morph_dt_max(const sessile_morph_cells *cl, const sessile_morph_coef *co) {
  double best = INFINITY;
  for (int c = 0; c < cl->ncells; c++) {
    double w = 0;
    for (uint32_t q = cl->nbr_off[c]; q < cl->nbr_off[c + 1]; q++) {
      double d = dist(cl->pos, c, (int)cl->nbr[q]);
      if (!(d > 0)) return 0;
      w += 1.0 / d;
    }
    for (int k = 0; k < co->nmorph; k++) {
      double rate = co->diffusion[k] * w + co->decay[k];
      if (rate > 0 && 1.0 / rate < best) best = 1.0 / rate;
    }
  }
  return best;
}

sessile_status sessile_morph_step(const sessile_morph_cells *cl, const sessile_morph_coef *co, const double *phi,
                                  const double *src, double dt, double *phi_out, size_t *clamped) {
  SESSILE_CHECK(dt > 0 && isfinite(dt), SESSILE_ERR_USAGE, "morphogen step: dt = %g must be positive and finite", dt);
  double dtm = sessile_morph_dt_max(cl, co);
  SESSILE_CHECK(dtm > 0, SESSILE_ERR_NUMERIC, "morphogen step: two adjacent cells coincide (zero distance)");
  SESSILE_CHECK(dt <= dtm * (1 + 1e-12), SESSILE_ERR_USAGE,
                "morphogen step: dt = %g exceeds the explicit Euler bound %g (1 / (D sum 1/|c-n| + C)); "
                "sub-step with dt <= %g",
                dt, dtm, dtm);
  int nm = co->nmorph;
  size_t nclamp = 0;
  for (int c = 0; c < cl->ncells; c++) {
    double vc = sessile_morph_vol(cl->radius[c]);
    for (int k = 0; k < nm; k++) {
      size_t i = (size_t)c * nm + k;
      double lap = sessile_morph_laplacian(cl, nm, phi, c, k);
      double rate = co->diffusion[k] * lap - co->decay[k] * phi[i];
      if (src) rate += src[i];
      double v = phi[i] + dt * rate;
      double cap = (!co->capped || co->capped[k]) ? vc : INFINITY;
      double w = fmin(fmax(v, 0.0), cap);
      if (w != v) nclamp++;
      phi_out[i] = w;
    }
  }
  if (clamped) *clamped = nclamp;
  return SESSILE_OK;
}

double sessile_morph_total(int ncells, int nmorph, const double *phi, int k) {
  double s = 0;
  for (int c = 0; c < ncells; c++) s += phi[(size_t)c * nmorph + k];
  return s;
}

/* Solves the 3x3 symmetric system by Cramer's rule; 0 when (near) singular. */
static int solve3(double A[3][3], const double b[3], double x[3]) {
  double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
               A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  double scale = A[0][0] + A[1][1] + A[2][2];
  if (!(fabs(det) > 1e-12 * scale * scale * scale)) return 0;
  for (int j = 0; j < 3; j++) {
    double M[3][3];
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) M[r][s] = s == j ? b[r] : A[r][s];
    x[j] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
            M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
           det;
  }
  return 1;
}

int sessile_morph_gradient(const sessile_morph_cells *cl, int nmorph, const double *phi, int c, int k,
                           double grad[3]) {
  double A[3][3] = {{0}}, b[3] = {0}, fb[3] = {0};
  double pc = phi[(size_t)c * nmorph + k];
  for (uint32_t q = cl->nbr_off[c]; q < cl->nbr_off[c + 1]; q++) {
    int n = (int)cl->nbr[q];
    double d[3], dp = phi[(size_t)n * nmorph + k] - pc, dd = 0;
    for (int a = 0; a < 3; a++) d[a] = cl->pos[3 * n + a] - cl->pos[3 * c + a], dd += d[a] * d[a];
    for (int a = 0; a < 3; a++) {
      b[a] += d[a] * dp;
      if (dd > 0) fb[a] += dp * d[a] / dd;
      for (int s = 0; s < 3; s++) A[a][s] += d[a] * d[s];
    }
  }
  if (!solve3(A, b, grad))
    for (int a = 0; a < 3; a++) grad[a] = fb[a];
  return grad[0] != 0 || grad[1] != 0 || grad[2] != 0;
}
