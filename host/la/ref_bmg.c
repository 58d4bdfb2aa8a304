/* Plain-C reference of the block-multigrid V-cycle (bmg_record.c's
 * recording, step by step, in double on the host copies of the levels). */
#include <stdlib.h>
#include <string.h>
#include "bmg_internal.h"
#include "sessile/la/la_ref.h"

static void node_ijk(const uint32_t n[3], uint32_t i, uint32_t c[3]) {
  c[0] = i % n[0], c[1] = (i / n[0]) % n[1], c[2] = i / (n[0] * n[1]);
}

/* One block update of node i: y_i = (zero ? 0 : x_i) + omega Dinv_i (b - A x)_i. */
static void update(const sessile_bmg *mg, const bmg_level *v, uint32_t i, const double *b, const double *x,
                   double *y, int zero) {
  double r[4];
  for (int a = 0; a < 4; a++) r[a] = b[4 * i + a];
  if (!zero) {
    const sessile_bcsr4 *A = v->ah;
    for (uint64_t k = A->rowptr[i]; k < A->rowptr[i + 1]; k++)
      for (int a = 0; a < 4; a++)
        for (int q = 0; q < 4; q++) r[a] -= A->val[16 * k + 4 * a + q] * x[4 * A->col[k] + q];
  }
  const double *d = v->dinv + 16 * (size_t)i;
  for (int a = 0; a < 4; a++) {
    double dz = 0;
    for (int q = 0; q < 4; q++) dz += d[4 * a + q] * r[q];
    y[4 * i + a] = (zero ? 0.0 : x[4 * i + a]) + mg->o.omega * dz;
  }
}

static void smooth(const sessile_bmg *mg, int l, const double *b, double *x, double *t, int sweeps, int zero,
                   int backward) {
  const bmg_level *v = &mg->lv[l];
  if (zero)
    for (uint32_t i = 0; i < v->nodes; i++) update(mg, v, i, b, x, x, 1);
  for (int s = 0; s < sweeps; s++) {
    if (mg->o.smoother == SESSILE_BMG_JACOBI) {
      for (uint32_t i = 0; i < v->nodes; i++) update(mg, v, i, b, x, t, 0);
      memcpy(x, t, (size_t)v->nodes * 4 * sizeof *x);
      continue;
    }
    int back = backward ^ (s & 1 && l == mg->nl - 1);
    for (int q = 0; q < 8; q++) {
      uint32_t col = back ? 7 - q : q;
      for (uint32_t i = 0; i < v->nodes; i++) {
        uint32_t c[3];
        node_ijk(v->n, i, c);
        if (((c[0] & 1) | (c[1] & 1) << 1 | (c[2] & 1) << 2) == col) update(mg, v, i, b, x, x, 0);
      }
    }
  }
}

static double free_of(uint8_t fixed, int a) { return (fixed >> a) & 1u ? 0.0 : 1.0; }

static sessile_status level(const sessile_bmg *mg, int l, const double *b, double *x) {
  const bmg_level *v = &mg->lv[l];
  size_t n4 = (size_t)v->nodes * 4;
  if (l == mg->nl - 1 && mg->cinvm) {
    for (size_t i = 0; i < n4; i++) {
      double s = 0;
      for (size_t j = 0; j < n4; j++) s += mg->cinv[i * n4 + j] * b[j];
      x[i] = s;
    }
    return SESSILE_OK;
  }
  double *t = malloc(n4 * sizeof *t);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (l == mg->nl - 1) {
    smooth(mg, l, b, x, t, mg->o.coarse_sweeps, 1, 0);
    free(t);
    return SESSILE_OK;
  }
  const bmg_level *c = &mg->lv[l + 1];
  size_t c4 = (size_t)c->nodes * 4;
  double *bc = calloc(c4, sizeof *bc), *xc = calloc(c4, sizeof *xc);
  sessile_status s = bc && xc ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) smooth(mg, l, b, x, t, mg->o.pre, 1, 0);
  int corr = bmg_corrections(mg, l);
  for (int k = 0; k < corr && s == SESSILE_OK; k++) {
    sessile_ref_spmv_bcsr4(v->ah, x, t);
    for (size_t i = 0; i < n4; i++) t[i] = b[i] - t[i];
    for (uint32_t p = 0; p < c->nodes; p++) { /* R = P^T, the 15 children */
      uint32_t cp[3];
      node_ijk(c->n, p, cp);
      double sum[4] = {0}, half[4] = {0};
      for (int o = 0; o < BMG_NOFF; o++) {
        long f3[3] = {2L * cp[0] + v->off[o][0], 2L * cp[1] + v->off[o][1], 2L * cp[2] + v->off[o][2]};
        if (f3[0] < 0 || f3[1] < 0 || f3[2] < 0 || f3[0] >= v->n[0] || f3[1] >= v->n[1] || f3[2] >= v->n[2]) continue;
        uint32_t f = (uint32_t)(f3[0] + v->n[0] * (f3[1] + (long)v->n[1] * f3[2]));
        int centre = !v->off[o][0] && !v->off[o][1] && !v->off[o][2];
        for (int a = 0; a < 4; a++) (centre ? sum : half)[a] += free_of(v->fixed[f], a) * t[4 * f + a];
      }
      for (int a = 0; a < 4; a++) bc[4 * p + a] = free_of(c->fixed[p], a) * (sum[a] + 0.5 * half[a]);
    }
    s = level(mg, l + 1, bc, xc);
    for (uint32_t i = 0; s == SESSILE_OK && i < v->nodes; i++) { /* x += P xc */
      uint32_t f[3], c0[3], c1[3];
      node_ijk(v->n, i, f);
      for (int a = 0; a < 3; a++) c0[a] = f[a] >> 1, c1[a] = c0[a] + (f[a] & 1);
      uint32_t i0 = c0[0] + c->n[0] * (c0[1] + c->n[1] * c0[2]), i1 = c1[0] + c->n[0] * (c1[1] + c->n[1] * c1[2]);
      for (int a = 0; a < 4; a++) {
        double w = i0 == i1 ? xc[4 * i0 + a] : 0.5 * (xc[4 * i0 + a] + xc[4 * i1 + a]);
        x[4 * i + a] += free_of(v->fixed[i], a) * w;
      }
    }
  }
  if (s == SESSILE_OK) {
    smooth(mg, l, b, x, t, mg->o.post, 0, 1);
  }
  free(bc);
  free(xc);
  free(t);
  return s;
}

sessile_status sessile_ref_bmg_vcycle(const sessile_bmg *mg, const double *r, double *z) {
  SESSILE_CHECK(mg && r && z && mg->ready, SESSILE_ERR_USAGE, "ref bmg vcycle needs a set-up hierarchy");
  return level(mg, 0, r, z);
}
