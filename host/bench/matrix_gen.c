/* Matrix generators for tests and benchmarks: structured PDE matrices (7-point
 * Laplacian, convection-diffusion, P1 tetrahedral K+M) and deterministic
 * random ones.  Every generator is row-parallel and writes each row from data
 * that depend only on the row, so results are bitwise independent of the
 * OpenMP thread count. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/bench/matrix_gen.h"
#include "sessile/rng.h"

/* Below this many rows the thread start-up costs more than the work. */
#define GEN_PAR_MIN_ROWS 4096

/* ---- splitmix64 (sessile/rng.h): its n-th output is a pure function of
 * (seed, n), which makes parallel fills exact. */

/* Independent stream per row (or block row) so rows can be built in any order. */
static uint64_t row_stream(uint64_t seed, uint64_t row) {
  return sessile_rng_mix(seed ^ sessile_rng_mix((row + 1) * UINT64_C(0xD1B54A32D192ED03)));
}

/* Top 53 bits -> [0,1). */
static double unit_double(uint64_t r) { return (double)(r >> 11) * 0x1.0p-53; }

/* Uniform integer in [0, range) for range <= 2^32 (multiply-shift, Lemire 2019;
 * the bias is below 2^-32 and irrelevant here). */
static uint64_t uniform_below(uint64_t r, uint64_t range) { return ((r >> 32) * range) >> 32; }

void sessile_fill_random(double *v, uint64_t n, double lo, double hi, uint64_t seed) {
  const double span = hi - lo;
#pragma omp parallel for schedule(static) if (n >= 32768)
  for (uint64_t i = 0; i < n; i++) {
    /* Output i of the sequential stream started at `seed`, computed directly. */
    double x = lo + span * unit_double(sessile_rng_mix(seed + (i + 1) * SESSILE_RNG_GAMMA));
    /* lo + span*u can round up to hi; keep the interval half-open. */
    if (x >= hi && hi > lo) x = nextafter(hi, lo);
    v[i] = x;
  }
}

/* ---- grid helpers ---- */

/* n = nx*ny*nz as a checked row count (column indices are uint32_t). */
static sessile_status grid_rows(const char *what, uint64_t nx, uint64_t ny, uint64_t nz,
                                uint32_t *n) {
  SESSILE_CHECK(nx >= 1 && ny >= 1 && nz >= 1, SESSILE_ERR_USAGE,
                "%s: grid %" PRIu64 " x %" PRIu64 " x %" PRIu64
                " is empty: every dimension must be at least 1",
                what, nx, ny, nz);
  /* Each factor is < 2^33, so check pairwise products before they could wrap. */
  uint64_t nxy = nx * ny;
  SESSILE_CHECK(nxy <= UINT32_MAX && nxy * nz <= UINT32_MAX, SESSILE_ERR_TOO_LARGE,
                "%s: grid %" PRIu64 " x %" PRIu64 " x %" PRIu64
                " has more than 2^32-1 rows: use a smaller grid",
                what, nx, ny, nz);
  *n = (uint32_t)(nxy * nz);
  return SESSILE_OK;
}

/* 7-point stencil with constant coefficients on the interior nodes of a grid
 * with Dirichlet walls eliminated.  c[] is in column order:
 * z-1, y-1, x-1, centre, x+1, y+1, z+1.  Every in-grid neighbour is stored,
 * even when its coefficient is zero, so the pattern does not depend on c. */
static sessile_status stencil7(const char *what, uint32_t nx, uint32_t ny, uint32_t nz,
                               const double c[7], sessile_csr *out) {
  uint32_t n;
  SESSILE_CALL(grid_rows(what, nx, ny, nz, &n));
  /* Exact nnz: 7 per node minus one per missing neighbour on each wall. */
  uint64_t nnz = 7 * (uint64_t)n - 2 * ((uint64_t)ny * nz + (uint64_t)nx * nz + (uint64_t)nx * ny);
  SESSILE_CALL(sessile_csr_alloc(n, n, nnz, out));

  uint64_t *rowptr = out->rowptr;
  for (uint32_t r = 0; r < n; r++) {
    uint32_t i = r % nx, j = (r / nx) % ny, k = r / nx / ny;
    uint64_t cnt = 1 + (k > 0) + (j > 0) + (i > 0) + (i + 1 < nx) + (j + 1 < ny) + (k + 1 < nz);
    rowptr[r + 1] = rowptr[r] + cnt;
  }

  const uint64_t sx = 1, sy = nx, sz = (uint64_t)nx * ny;
#pragma omp parallel for schedule(static) if (n >= GEN_PAR_MIN_ROWS)
  for (uint32_t r = 0; r < n; r++) {
    uint32_t i = r % nx, j = (r / nx) % ny, k = r / nx / ny;
    const int present[7] = {k > 0, j > 0, i > 0, 1, i + 1 < nx, j + 1 < ny, k + 1 < nz};
    const int64_t offset[7] = {-(int64_t)sz, -(int64_t)sy, -(int64_t)sx, 0,
                               (int64_t)sx,  (int64_t)sy,  (int64_t)sz};
    uint64_t p = rowptr[r];
    for (int s = 0; s < 7; s++) {
      if (!present[s]) continue;
      out->col[p] = (uint32_t)((int64_t)r + offset[s]);
      out->val[p] = c[s];
      p++;
    }
  }
  return SESSILE_OK;
}

sessile_status sessile_csr_laplacian7(uint32_t nx, uint32_t ny, uint32_t nz, sessile_csr *out) {
  /* h² · (-∇²) with the standard second difference in each direction. */
  static const double c[7] = {-1.0, -1.0, -1.0, 6.0, -1.0, -1.0, -1.0};
  return stencil7("laplacian7", nx, ny, nz, c, out);
}

sessile_status sessile_csr_convdiff(uint32_t nx, uint32_t ny, uint32_t nz, double peclet,
                                    sessile_csr *out) {
  SESSILE_CHECK(isfinite(peclet), SESSILE_ERR_USAGE,
                "convdiff: Peclet number %g is not finite", peclet);
  /* h²·w_d·(u[+1] - u[-1])/(2h) = (w_d h/2)(u[+1] - u[-1]); with w_x h/2 = Pe and
   * w = (1, 0.5, 0.25)|w| the convective weights are Pe, Pe/2, Pe/4. */
  const double px = peclet, py = 0.5 * peclet, pz = 0.25 * peclet;
  const double c[7] = {-1.0 - pz, -1.0 - py, -1.0 - px, 6.0, -1.0 + px, -1.0 + py, -1.0 + pz};
  return stencil7("convdiff", nx, ny, nz, c, out);
}

/* ---- P1 tetrahedra (Kuhn / Freudenthal triangulation) ----
 *
 * Cube corners are 3-bit codes c = x | y<<1 | z<<2.  Tetrahedron t of a cube is
 * the monotone path 000 -> one step -> two steps -> 111 along axis order
 * kuhn_axes[t].  All 6 cubes' tetrahedra share the diagonal 000-111 and the
 * triangulation is conforming across cube faces.  Mesh edges join nodes whose
 * offset has no mixed signs, giving the 15-point graph. */

static const int kuhn_axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                    {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

/* Element matrices K + M of the 6 tetrahedra of a cube hx*hy*hz (all cubes
 * are congruent, so 6 small matrices serve the whole mesh), and each tet's
 * corner codes. */
typedef struct p1tet_tables {
  double e[6][4][4];
  int corner[6][4]; /* corner code of local vertex a of tet t */
  int local[6][8];  /* local vertex of corner c in tet t, or -1 */
  int slot[27];     /* (dz+1)*9+(dy+1)*3+(dx+1) -> 0..14 in column order, or -1 */
  int off[15][3];   /* slot -> (dx,dy,dz) */
} p1tet_tables;

static void p1tet_build_tables(double hx, double hy, double hz, p1tet_tables *tb) {
  const double h[3] = {hx, hy, hz};
  for (int t = 0; t < 6; t++) {
    int c1 = 1 << kuhn_axes[t][0];
    int c2 = c1 | 1 << kuhn_axes[t][1];
    const int code[4] = {0, c1, c2, 7};
    double xv[4][3];
    for (int a = 0; a < 4; a++) {
      tb->corner[t][a] = code[a];
      for (int d = 0; d < 3; d++) xv[a][d] = ((code[a] >> d) & 1) * h[d];
    }
    /* J has columns x_a - x_0 (a=1..3); rows of J^{-1} are ∇λ_1..∇λ_3 and
     * ∇λ_0 = -(∇λ_1+∇λ_2+∇λ_3) since the λ sum to 1. */
    double jm[3][3];
    for (int d = 0; d < 3; d++)
      for (int a = 0; a < 3; a++) jm[d][a] = xv[a + 1][d] - xv[0][d];
    double det = jm[0][0] * (jm[1][1] * jm[2][2] - jm[1][2] * jm[2][1]) -
                 jm[0][1] * (jm[1][0] * jm[2][2] - jm[1][2] * jm[2][0]) +
                 jm[0][2] * (jm[1][0] * jm[2][1] - jm[1][1] * jm[2][0]);
    double g[4][3];
    /* J^{-1} = adj(J)/det: row a of the inverse, via cofactors. */
    for (int a = 0; a < 3; a++) {
      int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
      for (int d = 0; d < 3; d++) {
        int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
        g[a + 1][d] = (jm[d1][a1] * jm[d2][a2] - jm[d1][a2] * jm[d2][a1]) / det;
      }
    }
    for (int d = 0; d < 3; d++) g[0][d] = -(g[1][d] + g[2][d] + g[3][d]);
    double vol = fabs(det) / 6.0;
    /* K_ab = |T| ∇λ_a·∇λ_b;  M_ab = |T|/20 (1 + δ_ab)  (exact P1 mass matrix). */
    for (int a = 0; a < 4; a++)
      for (int b = a; b < 4; b++) {
        double k = vol * (g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2]);
        double m = vol / 20.0 * (a == b ? 2.0 : 1.0);
        tb->e[t][a][b] = tb->e[t][b][a] = k + m; /* mirrored: bitwise symmetric */
      }
    for (int c = 0; c < 8; c++) tb->local[t][c] = -1;
    for (int a = 0; a < 4; a++) tb->local[t][code[a]] = a;
  }
  /* Slots in (dz, dy, dx) lexicographic order = increasing column index. */
  int s = 0;
  for (int dz = -1; dz <= 1; dz++)
    for (int dy = -1; dy <= 1; dy++)
      for (int dx = -1; dx <= 1; dx++) {
        int mixed = (dx < 0 || dy < 0 || dz < 0) && (dx > 0 || dy > 0 || dz > 0);
        int idx = (dz + 1) * 9 + (dy + 1) * 3 + (dx + 1);
        tb->slot[idx] = mixed ? -1 : s;
        if (!mixed) {
          tb->off[s][0] = dx;
          tb->off[s][1] = dy;
          tb->off[s][2] = dz;
          s++;
        }
      }
}

sessile_status sessile_csr_p1tet(uint32_t nx, uint32_t ny, uint32_t nz, double hx, double hy,
                                 double hz, sessile_csr *out) {
  SESSILE_CHECK(isfinite(hx) && isfinite(hy) && isfinite(hz) && hx > 0 && hy > 0 && hz > 0,
                SESSILE_ERR_USAGE, "p1tet: spacings (%g, %g, %g) must be positive and finite",
                hx, hy, hz);
  SESSILE_CHECK(nx >= 1 && ny >= 1 && nz >= 1, SESSILE_ERR_USAGE,
                "p1tet: %" PRIu32 " x %" PRIu32 " x %" PRIu32
                " cubes is empty: every dimension must be at least 1",
                nx, ny, nz);
  const uint64_t mx = (uint64_t)nx + 1, my = (uint64_t)ny + 1, mz = (uint64_t)nz + 1;
  uint32_t n;
  SESSILE_CALL(grid_rows("p1tet", mx, my, mz, &n));

  p1tet_tables tb;
  p1tet_build_tables(hx, hy, hz, &tb);

  /* Row counts depend only on which of the 15 offsets stay inside the box. */
  uint64_t *cnt = malloc((size_t)n * sizeof *cnt);
  SESSILE_CHECK(cnt != NULL, SESSILE_ERR_NO_MEMORY,
                "p1tet: out of host memory: cannot allocate %" PRIu32 " row counts: use a smaller mesh", n);
#pragma omp parallel for schedule(static) if (n >= GEN_PAR_MIN_ROWS)
  for (uint32_t r = 0; r < n; r++) {
    int64_t p[3] = {(int64_t)(r % mx), (int64_t)((r / mx) % my), (int64_t)(r / mx / my)};
    const int64_t m[3] = {(int64_t)mx, (int64_t)my, (int64_t)mz};
    uint64_t c = 0;
    for (int s = 0; s < 15; s++) {
      int in = 1;
      for (int d = 0; d < 3; d++) in &= p[d] + tb.off[s][d] >= 0 && p[d] + tb.off[s][d] < m[d];
      c += (uint64_t)in;
    }
    cnt[r] = c;
  }
  uint64_t nnz = 0;
  for (uint32_t r = 0; r < n; r++) nnz += cnt[r];
  sessile_status st = sessile_csr_alloc(n, n, nnz, out);
  if (st != SESSILE_OK) {
    free(cnt);
    return st;
  }
  for (uint32_t r = 0; r < n; r++) out->rowptr[r + 1] = out->rowptr[r] + cnt[r];
  free(cnt);

  /* Node-centred assembly: row r gathers from the (up to) 8 cubes around node
   * r, so rows are independent (no atomics) and an entry (r,q) adds the same
   * tetrahedra in the same absolute (cube z, y, x; tet t) order as (q,r):
   * the matrix is bitwise symmetric. */
#pragma omp parallel for schedule(static) if (n >= GEN_PAR_MIN_ROWS)
  for (uint32_t r = 0; r < n; r++) {
    const int64_t p[3] = {(int64_t)(r % mx), (int64_t)((r / mx) % my), (int64_t)(r / mx / my)};
    const int64_t ncube[3] = {nx, ny, nz};
    double acc[15] = {0};
    /* Corner code c of node r in the cube with origin p - bits(c); visiting
     * c from 7 down to 0 walks those cubes in increasing absolute order. */
    for (int c = 7; c >= 0; c--) {
      int inside = 1;
      for (int d = 0; d < 3; d++) {
        int64_t o = p[d] - ((c >> d) & 1);
        inside &= o >= 0 && o < ncube[d];
      }
      if (!inside) continue;
      for (int t = 0; t < 6; t++) {
        int a = tb.local[t][c];
        if (a < 0) continue;
        for (int b = 0; b < 4; b++) {
          int cb = tb.corner[t][b];
          int dx = (cb & 1) - (c & 1), dy = ((cb >> 1) & 1) - ((c >> 1) & 1),
              dz = ((cb >> 2) & 1) - ((c >> 2) & 1);
          acc[tb.slot[(dz + 1) * 9 + (dy + 1) * 3 + (dx + 1)]] += tb.e[t][a][b];
        }
      }
    }
    /* Compress: slots are already in column order; drop those outside the box. */
    uint64_t q = out->rowptr[r];
    const int64_t m[3] = {(int64_t)mx, (int64_t)my, (int64_t)mz};
    for (int s = 0; s < 15; s++) {
      int in = 1;
      for (int d = 0; d < 3; d++) in &= p[d] + tb.off[s][d] >= 0 && p[d] + tb.off[s][d] < m[d];
      if (!in) continue;
      int64_t colv = (int64_t)r + tb.off[s][0] + tb.off[s][1] * (int64_t)mx +
                     tb.off[s][2] * (int64_t)(mx * my);
      out->col[q] = (uint32_t)colv;
      out->val[q] = acc[s]; /* may be an exact or rounded zero: kept on purpose */
      q++;
    }
  }
  return SESSILE_OK;
}

/* ---- random matrices ---- */

/* Insert v into the sorted array a[0..len) (room for one more). */
static void sorted_insert(uint32_t *a, uint32_t len, uint32_t v) {
  uint32_t lo = 0, hi = len;
  while (lo < hi) {
    uint32_t mid = lo + (hi - lo) / 2;
    if (a[mid] < v) lo = mid + 1;
    else hi = mid;
  }
  memmove(a + lo + 1, a + lo, (size_t)(len - lo) * sizeof *a);
  a[lo] = v;
}

static int sorted_contains(const uint32_t *a, uint32_t len, uint32_t v) {
  uint32_t lo = 0, hi = len;
  while (lo < hi) {
    uint32_t mid = lo + (hi - lo) / 2;
    if (a[mid] < v) lo = mid + 1;
    else hi = mid;
  }
  return lo < len && a[lo] == v;
}

sessile_status sessile_csr_random(uint32_t n, uint32_t per_row, double dominance, uint64_t seed,
                                  sessile_csr *out) {
  SESSILE_CHECK(n >= 1, SESSILE_ERR_USAGE, "random matrix: size n must be at least 1");
  SESSILE_CHECK(per_row >= 1, SESSILE_ERR_USAGE,
                "random matrix: per_row must be at least 1 (the diagonal)");
  SESSILE_CHECK(isfinite(dominance) && dominance > 0, SESSILE_ERR_USAGE,
                "random matrix: dominance %g must be positive and finite", dominance);
  const uint32_t k = per_row < n ? per_row : n; /* entries per row, diagonal included */
  SESSILE_CALL(sessile_csr_alloc(n, n, (uint64_t)n * k, out));
  for (uint32_t r = 0; r <= n; r++) out->rowptr[r] = (uint64_t)r * k;

#pragma omp parallel for schedule(static) if (n >= GEN_PAR_MIN_ROWS)
  for (uint32_t r = 0; r < n; r++) {
    uint64_t state = row_stream(seed, r);
    uint32_t *cols = out->col + out->rowptr[r];
    double *vals = out->val + out->rowptr[r];
    /* Floyd's algorithm: k-1 distinct values of [0, n-1) with exactly k-1
     * draws, kept sorted in place (the row's own slots are the work array). */
    const uint32_t m = n - 1, kk = k - 1;
    for (uint32_t j = m - kk, len = 0; j < m; j++, len++) {
      uint32_t t = (uint32_t)uniform_below(sessile_rng_next(&state), (uint64_t)j + 1);
      sorted_insert(cols, len, sorted_contains(cols, len, t) ? j : t);
    }
    /* Map [0, n-1) onto the columns other than r (monotone, so still sorted)
     * and open a slot for the diagonal. */
    uint32_t dpos = 0;
    while (dpos < kk && cols[dpos] < r) dpos++;
    for (uint32_t i = kk; i > dpos; i--) cols[i] = cols[i - 1] + 1;
    cols[dpos] = r;

    double off = 0.0;
    for (uint32_t i = 0; i < k; i++) {
      if (i == dpos) continue;
      vals[i] = 2.0 * unit_double(sessile_rng_next(&state)) - 1.0;
      off += fabs(vals[i]);
    }
    /* Strict dominance |a_rr| = dominance·Σ|a_rj|; 1 when the row is diagonal only. */
    vals[dpos] = off > 0.0 ? dominance * off : 1.0;
  }
  return SESSILE_OK;
}

/* Dominance of the scalar diagonal of random block matrices: with 2 the scalar
 * matrix is strictly diagonally dominant, so nonsingular and Jacobi-friendly. */
#define BCSR4_DOMINANCE 2.0

sessile_status sessile_bcsr4_random_on(const sessile_csr *pattern, uint64_t seed,
                                       sessile_bcsr4 *out) {
  SESSILE_CHECK(pattern != NULL && pattern->rowptr != NULL, SESSILE_ERR_INTERNAL,
                "bcsr4_random_on: pattern is NULL");
  SESSILE_CHECK(pattern->nrows == pattern->ncols, SESSILE_ERR_USAGE,
                "bcsr4_random_on: pattern is %" PRIu32 " x %" PRIu32 ", it must be square",
                pattern->nrows, pattern->ncols);
  const uint32_t n = pattern->nrows;
  /* Every block row needs its diagonal block to carry the dominant diagonal. */
  for (uint32_t r = 0; r < n; r++) {
    int has_diag = 0;
    for (uint64_t p = pattern->rowptr[r]; p < pattern->rowptr[r + 1]; p++)
      has_diag |= pattern->col[p] == r;
    SESSILE_CHECK(has_diag, SESSILE_ERR_USAGE,
                  "bcsr4_random_on: pattern row %" PRIu32
                  " has no diagonal entry: the block matrix would be singular",
                  r);
  }
  SESSILE_CALL(sessile_bcsr4_alloc(n, n, pattern->nnz, out));
  memcpy(out->rowptr, pattern->rowptr, ((size_t)n + 1) * sizeof *out->rowptr);
  memcpy(out->col, pattern->col, (size_t)pattern->nnz * sizeof *out->col);

#pragma omp parallel for schedule(static) if (n >= GEN_PAR_MIN_ROWS)
  for (uint32_t r = 0; r < n; r++) {
    uint64_t state = row_stream(seed, r);
    uint64_t b0 = out->rowptr[r], b1 = out->rowptr[r + 1], bd = b0;
    for (uint64_t b = b0; b < b1; b++) {
      if (out->col[b] == r) bd = b;
      for (int e = 0; e < 16; e++)
        out->val[16 * b + e] = 2.0 * unit_double(sessile_rng_next(&state)) - 1.0;
    }
    /* Scalar row 4r+i: diagonal = dominance × absolute sum of the rest of the row. */
    for (int i = 0; i < 4; i++) {
      double off = 0.0;
      for (uint64_t b = b0; b < b1; b++)
        for (int j = 0; j < 4; j++)
          if (!(b == bd && j == i)) off += fabs(out->val[16 * b + 4 * i + j]);
      out->val[16 * bd + 4 * i + i] = off > 0.0 ? BCSR4_DOMINANCE * off : 1.0;
    }
  }
  return SESSILE_OK;
}
