/* Host P1 assembly on the Kuhn box: the reference that shows (tests/fem) the
 * assembled stiffness is the 7-point stencil times h, so the GPU solve can
 * run matrix-free (host/la/stencil.c), and the CSR system that la's plain-C
 * reference CG solves for comparison. */
#include <stdlib.h>
#include <string.h>
#include "sessile/fem/nutrient.h"

/* Gradients of the 4 barycentric functions of tet (p0..p3); returns its
 * signed volume. */
static double tet_grads(double p[4][3], double gr[4][3]) {
  double j[3][3]; /* columns: p1-p0, p2-p0, p3-p0 */
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) j[a][c] = p[c + 1][a] - p[0][a];
  double det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) -
               j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
               j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
  /* Row q of J^-1 is grad lambda_{q+1}: J^-1 = cof(J)^T / det. */
  for (int q = 0; q < 3; q++)
    for (int a = 0; a < 3; a++) {
      int r1 = (a + 1) % 3, r2 = (a + 2) % 3, c1 = (q + 1) % 3, c2 = (q + 2) % 3;
      gr[q + 1][a] = (j[r1][c1] * j[r2][c2] - j[r1][c2] * j[r2][c1]) / det;
    }
  for (int a = 0; a < 3; a++) gr[0][a] = -(gr[1][a] + gr[2][a] + gr[3][a]);
  return det / 6.0;
}

static void node_ijk(const sessile_box *b, uint32_t node, int64_t c[3]) {
  c[0] = node % b->n[0];
  c[1] = (node / b->n[0]) % b->n[1];
  c[2] = node / (b->n[0] * b->n[1]);
}

sessile_status sessile_p1_laplace_assemble(const sessile_box *box, sessile_csr *out) {
  memset(out, 0, sizeof *out);
  uint32_t n = sessile_box_nodes(box);
  /* 27 slots per row (offsets -1..1 per axis); touched marks the Kuhn graph. */
  double *v = calloc((size_t)n * 27, sizeof *v);
  uint8_t *touched = calloc((size_t)n * 27, 1);
  sessile_status s = (v && touched) ? SESSILE_OK
                                    : sessile_error_set(SESSILE_ERR_NO_MEMORY,
                                                        "out of host memory assembling %u nodes", n);
  for (uint32_t k = 0; s == SESSILE_OK && k + 1 < box->n[2]; k++)
    for (uint32_t j = 0; j + 1 < box->n[1]; j++)
      for (uint32_t i = 0; i + 1 < box->n[0]; i++)
        for (int t = 0; t < 6; t++) {
          uint32_t nd[4];
          double p[4][3], gr[4][3];
          int64_t c[4][3];
          sessile_box_tet(box, i, j, k, t, nd);
          for (int q = 0; q < 4; q++) {
            sessile_box_node_pos(box, nd[q], p[q]);
            node_ijk(box, nd[q], c[q]);
          }
          double vol = tet_grads(p, gr);
          for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++) {
              int slot = (int)((c[b][0] - c[a][0] + 1) + 3 * (c[b][1] - c[a][1] + 1) +
                               9 * (c[b][2] - c[a][2] + 1));
              size_t e = (size_t)nd[a] * 27 + slot;
              v[e] += vol * (gr[a][0] * gr[b][0] + gr[a][1] * gr[b][1] + gr[a][2] * gr[b][2]);
              touched[e] = 1;
            }
        }
  uint64_t nnz = 0;
  for (size_t e = 0; s == SESSILE_OK && e < (size_t)n * 27; e++) nnz += touched[e];
  if (s == SESSILE_OK) s = sessile_csr_alloc(n, n, nnz, out);
  if (s == SESSILE_OK) {
    uint64_t e = 0;
    out->rowptr[0] = 0;
    for (uint32_t r = 0; r < n; r++) {
      for (int slot = 0; slot < 27; slot++) { /* dk major: increasing columns */
        if (!touched[(size_t)r * 27 + slot]) continue;
        int64_t di = slot % 3 - 1, dj = (slot / 3) % 3 - 1, dk = slot / 9 - 1;
        out->col[e] = (uint32_t)((int64_t)r + di + (int64_t)box->n[0] * (dj + (int64_t)box->n[1] * dk));
        out->val[e++] = v[(size_t)r * 27 + slot];
      }
      out->rowptr[r + 1] = e;
    }
  }
  free(v);
  free(touched);
  return s;
}

sessile_status sessile_p1_dirichlet(const sessile_csr *k, const uint8_t *dir, const double *g,
                                    sessile_csr *a, double *b) {
  memset(a, 0, sizeof *a);
  uint64_t nnz = 0;
  for (uint32_t r = 0; r < k->nrows; r++) {
    if (dir[r]) {
      nnz++;
      continue;
    }
    for (uint64_t e = k->rowptr[r]; e < k->rowptr[r + 1]; e++) nnz += !dir[k->col[e]];
  }
  SESSILE_CALL(sessile_csr_alloc(k->nrows, k->ncols, nnz, a));
  uint64_t o = 0;
  a->rowptr[0] = 0;
  for (uint32_t r = 0; r < k->nrows; r++) {
    if (dir[r]) {
      a->col[o] = r;
      a->val[o++] = 1.0;
      b[r] = g[r];
    } else {
      double sum = 0;
      for (uint64_t e = k->rowptr[r]; e < k->rowptr[r + 1]; e++) {
        uint32_t c = k->col[e];
        if (dir[c]) {
          sum -= k->val[e] * g[c];
        } else {
          a->col[o] = c;
          a->val[o++] = k->val[e];
        }
      }
      b[r] = sum;
    }
    a->rowptr[r + 1] = o;
  }
  return SESSILE_OK;
}
