/* The stationary Navier-Stokes solver (O'Hagan et al. §4.2): mesh graph,
 * tet colouring, parallel assembly into 4x4 block CSR, boundary rows, and
 * the Newton loop with GPU linear solves.  The element is ns_element.c;
 * decisions and measurements are in docs/fluid.md. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/fluid.h"
#include "sessile/la_ref.h"

struct sessile_fluid {
  sessile_la *la;
  uint32_t nnodes, ntets;
  double *x;          /* 3 nnodes, metres */
  uint32_t *tet;      /* 4 ntets */
  uint32_t *tags;     /* nnodes */
  sessile_bcsr4 a;    /* the pattern (node graph), values rewritten each assembly */
  uint32_t *pos;      /* 16 ntets: block index of (a, b) of each tet */
  uint32_t ncolours;
  uint32_t *corder;   /* ntets, tets sorted by colour */
  uint32_t *cstart;   /* ncolours + 1 */
};

void sessile_fluid_params_default(sessile_fluid_params *p) {
  memset(p, 0, sizeof *p);
  p->rho = 1000.0;
  p->eta = 5.0e-2;
  p->inlet[0] = 0.05;
  p->velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_SPONGE;
  p->noslip_tags = SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_SPONGE;
  p->pressure_tags = SESSILE_TAG_OUTLET;
  p->lsic = 1;
  p->newton_rtol = 1e-3;
  p->newton_max = 100;
  p->picard_steps = 0;
  p->linear_rtol = 1e-6;
  p->linear_max = 100;
  p->ksp = SESSILE_KSP_GMRES;
  p->pc = SESSILE_PC_ILU0; /* 47-100 GMRES iterations per Newton step on the default box */
  p->restart = 50;
  p->block_jacobi = 0;
}

/* One line to the caller's monitor (nothing when it is NULL). */
static void fluid_monitor(const sessile_fluid_params *p, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void fluid_monitor(const sessile_fluid_params *p, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  sessile_monitor_vprintf(p->monitor, p->monitor_user, fmt, ap);
  va_end(ap);
}

static int cmp_u32(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

/* Node graph (each node with itself and every node sharing a tet), as the
 * block pattern, and each tet's 16 block positions. */
static sessile_status build_graph(sessile_fluid *fl) {
  uint32_t n = fl->nnodes, nt = fl->ntets;
  uint64_t *cnt = calloc((size_t)n + 1, sizeof *cnt);
  SESSILE_CHECK(cnt, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint64_t t = 0; t < nt; t++)
    for (int a = 0; a < 4; a++) cnt[fl->tet[4 * t + a] + 1] += 4;
  for (uint32_t i = 0; i < n; i++) cnt[i + 1] += cnt[i];
  uint32_t *tmp = malloc((size_t)(cnt[n] ? cnt[n] : 1) * sizeof *tmp);
  uint64_t *fill = malloc((size_t)(n ? n : 1) * sizeof *fill);
  sessile_status s = SESSILE_OK;
  if (!tmp || !fill) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    memcpy(fill, cnt, (size_t)n * sizeof *fill);
    for (uint64_t t = 0; t < nt; t++)
      for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) tmp[fill[fl->tet[4 * t + a]]++] = fl->tet[4 * t + b];
    uint64_t nnzb = 0;
    for (uint32_t i = 0; i < n; i++) { /* sort, unique, count */
      uint32_t *row = tmp + cnt[i];
      size_t len = (size_t)(cnt[i + 1] - cnt[i]), u = 0;
      qsort(row, len, sizeof *row, cmp_u32);
      for (size_t k = 0; k < len; k++)
        if (u == 0 || row[k] != row[u - 1]) row[u++] = row[k];
      fill[i] = u;
      nnzb += u;
    }
    s = sessile_bcsr4_alloc(n, n, nnzb, &fl->a);
    if (s == SESSILE_OK) {
      fl->a.rowptr[0] = 0;
      for (uint32_t i = 0; i < n; i++) {
        memcpy(fl->a.col + fl->a.rowptr[i], tmp + cnt[i], (size_t)fill[i] * sizeof *tmp);
        fl->a.rowptr[i + 1] = fl->a.rowptr[i] + fill[i];
      }
      fl->pos = malloc((size_t)nt * 16 * sizeof *fl->pos);
      if (!fl->pos) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    }
    for (uint64_t t = 0; s == SESSILE_OK && t < nt; t++)
      for (int a = 0; a < 4 && s == SESSILE_OK; a++) {
        uint32_t r = fl->tet[4 * t + a];
        const uint32_t *row = fl->a.col + fl->a.rowptr[r];
        size_t len = (size_t)(fl->a.rowptr[r + 1] - fl->a.rowptr[r]);
        for (int b = 0; b < 4; b++) {
          uint32_t key = fl->tet[4 * t + b];
          const uint32_t *hit = bsearch(&key, row, len, sizeof *row, cmp_u32);
          if (!hit) { /* the pattern holds every pair of a tet: cannot happen */
            s = sessile_error_set(SESSILE_ERR_INTERNAL, "fluid graph: node %u misses neighbour %u of tet %llu",
                                  r, key, (unsigned long long)t);
            break;
          }
          fl->pos[16 * t + 4 * a + b] = (uint32_t)(fl->a.rowptr[r] + (uint64_t)(hit - row));
        }
      }
  }
  free(cnt);
  free(tmp);
  free(fill);
  return s;
}

/* Greedy colouring: no two tets of a colour share a node, so each colour's
 * tets scatter into disjoint block rows without locks. */
static sessile_status build_colours(sessile_fluid *fl) {
  enum { W = 4 }; /* up to 256 colours */
  uint64_t *used = calloc((size_t)fl->nnodes * W + 1, sizeof *used);
  uint32_t *col = malloc(((size_t)fl->ntets + 1) * sizeof *col);
  fl->cstart = calloc(257, sizeof *fl->cstart);
  fl->corder = malloc(((size_t)fl->ntets + 1) * sizeof *fl->corder);
  sessile_status s = SESSILE_OK;
  if (!used || !col || !fl->cstart || !fl->corder)
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint32_t nc = 0;
  for (uint32_t t = 0; s == SESSILE_OK && t < fl->ntets; t++) {
    const uint32_t *v = fl->tet + 4 * (size_t)t;
    int c = -1;
    for (int wd = 0; wd < W && c < 0; wd++) {
      uint64_t m = 0;
      for (int a = 0; a < 4; a++) m |= used[(size_t)v[a] * W + wd];
      if (~m) c = 64 * wd + __builtin_ctzll(~m);
    }
    if (c < 0) {
      s = sessile_error_set(SESSILE_ERR_INTERNAL, "tet colouring needs more than 256 colours");
      break;
    }
    for (int a = 0; a < 4; a++) used[(size_t)v[a] * W + c / 64] |= 1ull << (c % 64);
    col[t] = (uint32_t)c;
    if ((uint32_t)c + 1 > nc) nc = (uint32_t)c + 1;
    fl->cstart[c + 1]++;
  }
  if (s == SESSILE_OK) {
    for (uint32_t c = 0; c < nc; c++) fl->cstart[c + 1] += fl->cstart[c];
    uint32_t fillc[256];
    memcpy(fillc, fl->cstart, sizeof fillc);
    for (uint32_t t = 0; t < fl->ntets; t++) fl->corder[fillc[col[t]]++] = t;
    fl->ncolours = nc;
  }
  free(used);
  free(col);
  return s;
}

void sessile_fluid_destroy(sessile_fluid *fl) {
  if (!fl) return;
  free(fl->x);
  free(fl->tet);
  free(fl->tags);
  free(fl->pos);
  free(fl->corder);
  free(fl->cstart);
  sessile_bcsr4_free(&fl->a);
  free(fl);
}

sessile_status sessile_fluid_create(sessile_la *la, const sessile_tetmesh *m, sessile_fluid **out) {
  *out = NULL;
  SESSILE_CHECK(m && m->nnodes >= 4 && m->ntets >= 1 && m->xyz && m->tet, SESSILE_ERR_USAGE,
                "fluid mesh needs at least one tetrahedron");
  SESSILE_CHECK(m->nnodes <= UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "fluid mesh too large");
  for (uint64_t k = 0; k < 4ull * m->ntets; k++)
    SESSILE_CHECK(m->tet[k] < m->nnodes, SESSILE_ERR_USAGE, "tet %llu names node %u of %u",
                  (unsigned long long)(k / 4), m->tet[k], m->nnodes);
  sessile_fluid *fl = calloc(1, sizeof *fl);
  SESSILE_CHECK(fl, SESSILE_ERR_NO_MEMORY, "out of host memory");
  fl->la = la;
  fl->nnodes = m->nnodes;
  fl->ntets = m->ntets;
  fl->x = malloc((size_t)m->nnodes * 3 * sizeof *fl->x);
  fl->tet = malloc((size_t)m->ntets * 4 * sizeof *fl->tet);
  fl->tags = malloc((size_t)m->nnodes * sizeof *fl->tags);
  sessile_status s = SESSILE_OK;
  if (!fl->x || !fl->tet || !fl->tags) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    for (size_t k = 0; k < (size_t)m->nnodes * 3; k++) fl->x[k] = 0.01 * m->xyz[k]; /* cm -> m */
    memcpy(fl->tet, m->tet, (size_t)m->ntets * 4 * sizeof *fl->tet);
    if (m->node_tags) memcpy(fl->tags, m->node_tags, (size_t)m->nnodes * sizeof *fl->tags);
    else memset(fl->tags, 0, (size_t)m->nnodes * sizeof *fl->tags);
    s = build_graph(fl);
  }
  if (s == SESSILE_OK) s = build_colours(fl);
  if (s != SESSILE_OK) {
    sessile_fluid_destroy(fl);
    return s;
  }
  *out = fl;
  return SESSILE_OK;
}

/* Residual r (4 per node) and, when jac, the Jacobian into fl->a.val. */
static void assemble(sessile_fluid *fl, const sessile_fluid_params *p, const double *up, double newton,
                     int jac, double *r) {
  ns_coef c = {p->rho, p->eta, p->lsic, newton};
  memset(r, 0, (size_t)fl->nnodes * 4 * sizeof *r);
  if (jac) memset(fl->a.val, 0, (size_t)fl->a.nnzb * 16 * sizeof *fl->a.val);
#pragma omp parallel
  {
    double Ke[256], Re[16];
    for (uint32_t col = 0; col < fl->ncolours; col++) {
#pragma omp for schedule(static)
      for (uint32_t k = fl->cstart[col]; k < fl->cstart[col + 1]; k++) {
        uint32_t t = fl->corder[k];
        const uint32_t *v = fl->tet + 4 * (size_t)t;
        double X[4][3], U[16], F[4][3];
        for (int a = 0; a < 4; a++)
          for (int i = 0; i < 4; i++) {
            if (i < 3) X[a][i] = fl->x[3 * (size_t)v[a] + i];
            U[4 * a + i] = up[4 * (size_t)v[a] + i];
          }
        if (p->force_fn)
          for (int q = 0; q < 4; q++) {
            double xq[3];
            for (int i = 0; i < 3; i++) {
              xq[i] = NS_QB * (X[0][i] + X[1][i] + X[2][i] + X[3][i]) + (NS_QA - NS_QB) * X[q][i];
            }
            p->force_fn(xq, F[q], p->bc_ctx);
          }
        ns_element((const double(*)[3])X, U, p->force_fn ? (const double(*)[3])F : NULL, &c, Re,
                   jac ? Ke : NULL);
        for (int a = 0; a < 4; a++) {
          for (int i = 0; i < 4; i++) r[4 * (size_t)v[a] + i] += Re[4 * a + i];
          if (!jac) continue;
          for (int b = 0; b < 4; b++) {
            double *blk = fl->a.val + 16 * (size_t)fl->pos[16 * (size_t)t + 4 * a + b];
            for (int i = 0; i < 4; i++)
              for (int j = 0; j < 4; j++) blk[4 * i + j] += Ke[(4 * a + i) * 16 + 4 * b + j];
          }
        }
      }
    }
  }
}

sessile_status sessile_fluid_residual(sessile_fluid *fl, const sessile_fluid_params *p,
                                      const double *up, double *r) {
  SESSILE_CHECK(fl && p && up && r, SESSILE_ERR_USAGE,
                "fluid residual needs a solver, parameters, a state and an output");
  assemble(fl, p, up, 1.0, 0, r);
  return SESSILE_OK;
}

/* Dirichlet flags per node: bit 0 velocity, bit 1 pressure. */
static uint8_t node_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                       uint32_t i) {
  uint8_t f = 0;
  if ((fl->tags[i] & p->velocity_tags) || (solid && solid[i])) f |= 1;
  if (fl->tags[i] & p->pressure_tags) f |= 2;
  return f;
}

/* Writes the Dirichlet values into up. */
static void impose_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                      const uint8_t *bc, double *up) {
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    const double *x = fl->x + 3 * (size_t)i;
    if (bc[i] & 1) {
      double u[3] = {0, 0, 0};
      int solid_node = solid && solid[i];
      if (solid_node) { /* immersed sponge: no-slip */
      } else if (p->velocity_fn) p->velocity_fn(x, fl->tags[i], u, p->bc_ctx);
      else if (!(fl->tags[i] & p->noslip_tags))
        for (int k = 0; k < 3; k++) u[k] = p->inlet[k];
      for (int k = 0; k < 3; k++) up[4 * (size_t)i + k] = u[k];
    }
    if (bc[i] & 2) up[4 * (size_t)i + 3] = p->pressure_fn ? p->pressure_fn(x, fl->tags[i], p->bc_ctx) : 0.0;
  }
}

/* Zeroes the residual's Dirichlet rows (their values are imposed) and, when
 * jac, makes them identity rows; returns ||r|| of the rest. */
static double apply_bc_rows(sessile_fluid *fl, const uint8_t *bc, int jac, double *r) {
  double ss = 0;
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    for (int k = 0; k < 4; k++) {
      int fixed = (k < 3) ? (bc[i] & 1) : (bc[i] & 2);
      if (fixed) r[4 * (size_t)i + k] = 0;
      else ss += r[4 * (size_t)i + k] * r[4 * (size_t)i + k];
      if (!fixed || !jac) continue;
      for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++) {
        double *row = fl->a.val + 16 * e + 4 * k;
        row[0] = row[1] = row[2] = row[3] = 0;
        if (fl->a.col[e] == i) row[k] = 1.0;
      }
    }
  }
  return sqrt(ss);
}

/* Inverts the 4x4 matrix a (row-major) into inv by Gauss-Jordan with
 * partial pivoting; returns 0 if singular. */
static int inv4(const double *a, double *inv) {
  double m[4][8];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 8; j++) m[i][j] = j < 4 ? a[4 * i + j] : (j - 4 == i);
  for (int c = 0; c < 4; c++) {
    int piv = c;
    for (int i = c + 1; i < 4; i++)
      if (fabs(m[i][c]) > fabs(m[piv][c])) piv = i;
    if (!(fabs(m[piv][c]) > 0)) return 0;
    for (int j = 0; j < 8; j++) {
      double t = m[c][j];
      m[c][j] = m[piv][j];
      m[piv][j] = t;
    }
    double d = 1.0 / m[c][c];
    for (int j = 0; j < 8; j++) m[c][j] *= d;
    for (int i = 0; i < 4; i++)
      if (i != c) {
        double f = m[i][c];
        for (int j = 0; j < 8; j++) m[i][j] -= f * m[c][j];
      }
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) inv[4 * i + j] = m[i][j + 4];
  return 1;
}

/* Block-Jacobi by explicit left scaling: every block row and its right-hand
 * side multiplied by the inverse of its diagonal block, so the Krylov solver
 * sees D^-1 A x = D^-1 b (its relative residual is then that of the scaled
 * system).  la's point Jacobi cannot couple a node's u and p. */
static sessile_status block_scale(sessile_fluid *fl, double *rhs) {
  /* A failure in a worker is reduced to the lowest failing node and reported
   * once, on the calling thread, after the parallel loop: the error message
   * is thread-local, so a worker's sessile_error_set would be lost. */
  uint32_t bad = UINT32_MAX;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    double D[16], Di[16], tmp[16];
    int found = 0;
    for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++)
      if (fl->a.col[e] == i) {
        memcpy(D, fl->a.val + 16 * e, sizeof D);
        found = 1;
      }
    if (!found || !inv4(D, Di)) {
      if (i < bad) bad = i;
      continue;
    }
    for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++) {
      double *B = fl->a.val + 16 * e;
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
          tmp[4 * r + c] = Di[4 * r] * B[c] + Di[4 * r + 1] * B[4 + c] + Di[4 * r + 2] * B[8 + c] + Di[4 * r + 3] * B[12 + c];
      memcpy(B, tmp, sizeof tmp);
    }
    double *b = rhs + 4 * (size_t)i, bt[4];
    for (int r = 0; r < 4; r++) bt[r] = Di[4 * r] * b[0] + Di[4 * r + 1] * b[1] + Di[4 * r + 2] * b[2] + Di[4 * r + 3] * b[3];
    memcpy(b, bt, sizeof bt);
  }
  if (bad != UINT32_MAX)
    return sessile_error_set(SESSILE_ERR_NUMERIC,
                             "Navier-Stokes Jacobian: singular diagonal block at node %u", bad);
  return SESSILE_OK;
}

static sessile_status linear_solve(sessile_fluid *fl, const sessile_fluid_params *p, const double *r,
                                   double *du, sessile_vec *b, sessile_vec *x, sessile_fluid_step *st) {
  size_t n4 = (size_t)fl->nnodes * 4;
  for (size_t k = 0; k < n4; k++) du[k] = -r[k];
  if (p->block_jacobi) SESSILE_CALL(block_scale(fl, du));
  sessile_mat *m = NULL;
  SESSILE_CALL(sessile_mat_create_bcsr4(fl->la, &fl->a, &m));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = p->ksp;
  o.pc = p->pc;
  /* la factorises ILU(0) only on a matrix stored in one piece */
  st->lin_chunks = sessile_mat_chunks(m);
  if (o.pc == SESSILE_PC_ILU0 && st->lin_chunks > 1) o.pc = SESSILE_PC_JACOBI;
  st->lin_pc = o.pc;
  o.rtol = p->linear_rtol;
  o.max_it = p->linear_max;
  o.restart = p->restart;
  sessile_solve_result lr;
  sessile_status s = sessile_vec_upload(b, du);
  if (s == SESSILE_OK) s = sessile_vec_fill(fl->la, 0.0, x);
  if (s == SESSILE_OK) s = sessile_ksp_solve(fl->la, &o, m, b, x, &lr);
  if (s == SESSILE_OK) s = sessile_vec_download(x, du);
  sessile_mat_destroy(m);
  if (s != SESSILE_OK) return s;
  if (p->check_linear && p->monitor) {
    double *y = malloc(n4 * sizeof *y), e = 0, nb = 0;
    SESSILE_CHECK(y, SESSILE_ERR_NO_MEMORY, "out of host memory for the linear-solve check");
    sessile_ref_spmv_bcsr4(&fl->a, du, y);
    for (size_t k = 0; k < n4; k++) { e += (y[k] + r[k]) * (y[k] + r[k]); nb += r[k] * r[k]; }
    if (p->block_jacobi) e = NAN; /* the matrix is scaled */
    free(y);
    fluid_monitor(p, "host check |J du + r|/|r| = %g", sqrt(e / nb));
  }
  st->lin_iterations = lr.iterations;
  st->lin_relres = lr.true_relres;
  st->lin_status = lr.status;
  return SESSILE_OK;
}

sessile_status sessile_fluid_solve(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                                   double *up, sessile_fluid_result *res) {
  SESSILE_CHECK(fl && p && up && res, SESSILE_ERR_USAGE,
                "fluid solve needs a solver, parameters, a state and a result");
  memset(res, 0, sizeof *res);
  SESSILE_CHECK(p->eta > 0 && p->rho >= 0 && isfinite(p->rho) && isfinite(p->eta), SESSILE_ERR_USAGE,
                "fluid needs eta > 0 and rho >= 0 (got eta %g, rho %g)", p->eta, p->rho);
  SESSILE_CHECK(p->newton_max >= 1 && p->newton_max < SESSILE_FLUID_MAX_STEPS, SESSILE_ERR_USAGE,
                "newton_max must be between 1 and %d (got %d)", SESSILE_FLUID_MAX_STEPS - 1,
                p->newton_max);
  double t0 = sessile_wall_seconds();
  size_t n4 = (size_t)fl->nnodes * 4;
  uint8_t *bc = malloc(fl->nnodes);
  double *r = malloc(n4 * sizeof *r), *du = malloc(n4 * sizeof *du);
  sessile_vec *b = NULL, *x = NULL;
  sessile_status s = SESSILE_OK;
  if (!bc || !r || !du) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) s = sessile_vec_create(fl->la, (uint32_t)n4, &b);
  if (s == SESSILE_OK) s = sessile_vec_create(fl->la, (uint32_t)n4, &x);
  if (s == SESSILE_OK) {
    for (uint32_t i = 0; i < fl->nnodes; i++) bc[i] = node_bc(fl, solid, p, i);
    /* the reference residual: the rest state with the boundary values */
    memset(du, 0, n4 * sizeof *du);
    impose_bc(fl, solid, p, bc, du);
    assemble(fl, p, du, 1.0, 0, r);
    res->residual_rest = apply_bc_rows(fl, bc, 0, r);
    impose_bc(fl, solid, p, bc, up);
  }
  int stalled = 0; /* Newton steps running whose line search found no decrease */
  for (int it = 0; s == SESSILE_OK; it++) {
    int picard = it < p->picard_steps;
    double ta = sessile_wall_seconds();
    assemble(fl, p, up, picard ? 0.0 : 1.0, 1, r);
    double rn = apply_bc_rows(fl, bc, 1, r);
    double tass = sessile_wall_seconds() - ta;
    if (!isfinite(rn)) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "Navier-Stokes residual is not finite at step %d; try picard_steps > 0 "
                            "or a smaller inlet velocity", it);
      break;
    }
    if (it == 0) res->residual0 = rn;
    res->residual = rn;
    res->assembly_s += tass;
    if (rn <= p->newton_rtol * res->residual_rest || rn <= p->newton_atol || rn == 0) {
      res->converged = 1;
      break;
    }
    if (it >= p->newton_max) break;
    /* A hopeless but in-range setting (e.g. eta = 1e-9 Pa s, Re ~ 1e9) must
     * fail with a message, not run for hours: a wall-clock bound, and a
     * stop once the line search finds no decrease several steps running. */
    double el = sessile_wall_seconds() - t0;
    if (p->max_seconds > 0 && el > p->max_seconds) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve passed its time bound (%.0f s > %g s) after %d Newton steps at "
                            "residual %.2e (%.2e of the rest state's); the setting may be hopeless "
                            "(Reynolds number, viscosity) or raise fluid_max_seconds",
                            el, p->max_seconds, it, rn, res->residual_rest > 0 ? rn / res->residual_rest : 0.0);
      break;
    }
    if (it >= 20 && rn > 10 * p->newton_rtol * res->residual_rest) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve is not converging: after %d Newton steps the residual is "
                            "still %.2e of the rest state's (the target is %g); the setting may be "
                            "hopeless (Reynolds number, viscosity)", it, rn / res->residual_rest,
                            p->newton_rtol);
      break;
    }
    if (stalled >= 5) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve stagnated: %d Newton steps running found no decrease of the "
                            "residual (%.2e, %.2e of the rest state's); the setting may be hopeless "
                            "(Reynolds number, viscosity)", stalled, rn,
                            res->residual_rest > 0 ? rn / res->residual_rest : 0.0);
      break;
    }
    sessile_fluid_step *st = &res->step[it];
    st->residual = rn;
    st->picard = picard;
    st->assembly_s = tass;
    double ts = sessile_wall_seconds();
    s = linear_solve(fl, p, r, du, b, x, st);
    st->solve_s = sessile_wall_seconds() - ts;
    if (s != SESSILE_OK) break;
    res->solve_s += st->solve_s;
    res->lin_iterations += st->lin_iterations;
    res->nsteps = it + 1;
    /* backtracking on ||R||: halve the step while the residual does not
     * decrease (at most 6 times); a full step near the solution (quadratic) */
    double lam = 1.0;
    for (int ls = 0; ls < 7; ls++) {
      for (size_t k = 0; k < n4; k++) up[k] += lam * du[k];
      if (ls == 6) {
        stalled++; /* no decrease: the smallest step is taken anyway */
        break;
      }
      assemble(fl, p, up, 1.0, 0, r);
      double rt = apply_bc_rows(fl, bc, 0, r);
      if (isfinite(rt) && rt < (1.0 - 1e-4 * lam) * rn) {
        stalled = 0;
        break;
      }
      for (size_t k = 0; k < n4; k++) up[k] -= lam * du[k];
      lam *= 0.5;
    }
    st->step_length = lam;
    fluid_monitor(p, "fluid %s %d: |R| %.3e (rel %.2e)  step %.3g  lin %d it relres %.2e %s  asm %.2f s solve %.2f s",
                  picard ? "picard" : "newton", it, rn, rn / res->residual_rest, lam, st->lin_iterations,
                  st->lin_relres, sessile_solve_status_name(st->lin_status), tass, st->solve_s);
  }
  if (s == SESSILE_OK)
    fluid_monitor(p, "fluid: %s after %d steps, |R| %.3e (rel %.2e)",
                  res->converged ? "converged" : "NOT converged", res->nsteps, res->residual,
                  res->residual_rest > 0 ? res->residual / res->residual_rest : 0.0);
  sessile_vec_destroy(b);
  sessile_vec_destroy(x);
  free(bc);
  free(r);
  free(du);
  res->seconds = sessile_wall_seconds() - t0;
  return s;
}
