/* The SUPG advection-diffusion solver object: the CSR graph of the mesh
 * (built once), the solve (host assembly, upload, la's Krylov solver on the
 * GPU) and its options.  The assembly is in advdiff_assemble.c.
 *
 * The graph is fixed for the mesh; every solve rewrites the values (velocity,
 * D and the Dirichlet mask change between growth iterations), uploads a fresh
 * la matrix and destroys it after the solve. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "advdiff_internal.h"

/* Rows: each node and its edge neighbours, sorted, from a node -> tet map. */
static sessile_status build_graph(const sessile_tetmesh *m, sessile_csr *a) {
  uint32_t n = m->nnodes;
  uint64_t *tptr = calloc((size_t)n + 1, sizeof *tptr);
  uint32_t *tlist = malloc((size_t)m->ntets * 4 * sizeof *tlist + 1);
  uint64_t *rowptr = calloc((size_t)n + 1, sizeof *rowptr);
  uint32_t *buf = NULL;
  sessile_status s = SESSILE_OK;
  if (!tptr || !tlist || !rowptr) {
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the graph of %u nodes", n);
    goto done;
  }
  for (uint64_t q = 0; q < 4ull * m->ntets; q++) tptr[m->tet[q] + 1]++;
  uint32_t maxdeg = 0;
  for (uint32_t i = 0; i < n; i++) {
    if (tptr[i + 1] > maxdeg) maxdeg = (uint32_t)tptr[i + 1];
    tptr[i + 1] += tptr[i];
  }
  {
    uint64_t *fill = malloc((size_t)n * sizeof *fill + 1);
    if (!fill) {
      s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the graph");
      goto done;
    }
    memcpy(fill, tptr, (size_t)n * sizeof *fill);
    for (uint64_t q = 0; q < 4ull * m->ntets; q++) tlist[fill[m->tet[q]]++] = (uint32_t)(q / 4);
    free(fill);
  }
  buf = malloc(((size_t)maxdeg * 4 + 1) * sizeof *buf);
  if (!buf) {
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the graph");
    goto done;
  }
  /* Two passes over the same gather: count, then fill. */
  for (int pass = 0; pass < 2; pass++) {
    for (uint32_t i = 0; i < n; i++) {
      uint32_t len = 0;
      buf[len++] = i;
      for (uint64_t p = tptr[i]; p < tptr[i + 1]; p++)
        for (int k = 0; k < 4; k++) buf[len++] = m->tet[4 * (size_t)tlist[p] + k];
      /* insertion sort + unique: rows are short (~15 of ~100 gathered) */
      for (uint32_t x = 1; x < len; x++) {
        uint32_t key = buf[x], y = x;
        while (y > 0 && buf[y - 1] > key) buf[y] = buf[y - 1], y--;
        buf[y] = key;
      }
      uint32_t u = 0;
      for (uint32_t x = 0; x < len; x++)
        if (u == 0 || buf[x] != buf[u - 1]) buf[u++] = buf[x];
      if (pass == 0) rowptr[i + 1] = rowptr[i] + u;
      else memcpy(a->col + a->rowptr[i], buf, (size_t)u * sizeof *buf);
    }
    if (pass == 0) {
      s = sessile_csr_alloc(n, n, rowptr[n], a);
      if (s != SESSILE_OK) goto done;
      memcpy(a->rowptr, rowptr, ((size_t)n + 1) * sizeof *rowptr);
    }
  }
done:
  free(buf);
  free(rowptr);
  free(tlist);
  free(tptr);
  return s;
}

sessile_status sessile_advdiff_create(sessile_la *la, const sessile_tetmesh *mesh,
                                      sessile_advdiff **out) {
  *out = NULL;
  SESSILE_CHECK(mesh && mesh->nnodes >= 4 && mesh->ntets >= 1, SESSILE_ERR_USAGE,
                "advection-diffusion needs a tet mesh with at least one tet");
  for (uint32_t t = 0; t < mesh->ntets; t++)
    SESSILE_CHECK(sessile_tetmesh_tet_volume(mesh, t) > 0, SESSILE_ERR_USAGE,
                  "tet %u of the mesh has non-positive volume %g cm^3; the mesh must be positively "
                  "oriented", t, sessile_tetmesh_tet_volume(mesh, t));
  sessile_advdiff *ad = calloc(1, sizeof *ad);
  SESSILE_CHECK(ad, SESSILE_ERR_NO_MEMORY, "out of host memory");
  ad->la = la;
  ad->mesh = mesh;
  ad->tau_scale = 1.0;
  sessile_status s = build_graph(mesh, &ad->a);
  if (s == SESSILE_OK) {
    ad->b = calloc(mesh->nnodes, sizeof *ad->b);
    if (!ad->b) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  if (s == SESSILE_OK) s = sessile_vec_create(la, mesh->nnodes, &ad->vb);
  if (s == SESSILE_OK) s = sessile_vec_create(la, mesh->nnodes, &ad->vx);
  if (s != SESSILE_OK) {
    sessile_advdiff_destroy(ad);
    return s;
  }
  *out = ad;
  return SESSILE_OK;
}

void sessile_advdiff_destroy(sessile_advdiff *ad) {
  if (!ad) return;
  sessile_vec_destroy(ad->vx);
  sessile_vec_destroy(ad->vb);
  sessile_csr_free(&ad->a);
  free(ad->b);
  free(ad->f);
  free(ad);
}

sessile_status sessile_advdiff_set_source(sessile_advdiff *ad, const double *f) {
  if (!f) {
    free(ad->f);
    ad->f = NULL;
    return SESSILE_OK;
  }
  /* Validate, then allocate, then copy: on any failure the previous source
   * (or none) stays in force, never a half-written or uninitialised one. */
  size_t n = ad->mesh->nnodes;
  for (size_t i = 0; i < n; i++)
    SESSILE_CHECK(isfinite(f[i]), SESSILE_ERR_NUMERIC, "source is not finite at node %zu", i);
  double *dst = ad->f ? ad->f : malloc(n * sizeof *dst);
  SESSILE_CHECK(dst, SESSILE_ERR_NO_MEMORY, "out of host memory for a source of %zu nodes", n);
  memcpy(dst, f, n * sizeof *f);
  ad->f = dst;
  return SESSILE_OK;
}

void sessile_advdiff_set_tau_scale(sessile_advdiff *ad, double scale) { ad->tau_scale = scale; }

void sessile_advdiff_timing(const sessile_advdiff *ad, double *assemble_s, double *upload_s,
                            double *solve_s) {
  if (assemble_s) *assemble_s = ad->t_assemble;
  if (upload_s) *upload_s = ad->t_upload;
  if (solve_s) *solve_s = ad->t_solve;
}

const sessile_csr *sessile_advdiff_matrix(const sessile_advdiff *ad) { return &ad->a; }
const double *sessile_advdiff_rhs(const sessile_advdiff *ad) { return ad->b; }

sessile_status sessile_advdiff_solve(sessile_advdiff *ad, const double *vel, double D,
                                     const uint8_t *mask, const double *g,
                                     const sessile_ksp_options *opt, double *c,
                                     sessile_solve_result *res) {
  uint32_t n = ad->mesh->nnodes;
  SESSILE_CHECK(D > 0 && isfinite(D), SESSILE_ERR_USAGE,
                "diffusivity D must be positive and finite (got %g m^2/s)", D);
  SESSILE_CHECK(mask && g && c && res, SESSILE_ERR_USAGE,
                "advection-diffusion solve needs a Dirichlet mask, values, a field and a result");
  sessile_ksp_options o;
  if (opt) o = *opt;
  else {
    sessile_ksp_options_default(&o);
    o.type = SESSILE_KSP_BICGSTAB;
  }
  SESSILE_CHECK(!(vel && o.type == SESSILE_KSP_CG), SESSILE_ERR_USAGE,
                "CG needs a symmetric matrix; with a velocity use BiCGSTAB or GMRES");
  if (vel)
    for (size_t q = 0; q < 3 * (size_t)n; q++)
      SESSILE_CHECK(isfinite(vel[q]), SESSILE_ERR_NUMERIC, "velocity is not finite at node %zu",
                    q / 3);
  for (uint32_t i = 0; i < n; i++)
    SESSILE_CHECK(!mask[i] || isfinite(g[i]), SESSILE_ERR_NUMERIC,
                  "Dirichlet value of node %u is not finite", i);
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_advdiff_assemble_(ad, vel, D, mask, g));
  double t1 = sessile_wall_seconds();
  /* Homogenised unknown u = c - g: the warm start is c on free nodes. */
  double *x = malloc((size_t)n * sizeof *x);
  SESSILE_CHECK(x, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t i = 0; i < n; i++) x[i] = mask[i] || !isfinite(c[i]) ? 0.0 : c[i];
  sessile_mat *a = NULL;
  sessile_status s = sessile_mat_create_csr(ad->la, &ad->a, &a);
  if (s == SESSILE_OK) s = sessile_vec_upload(ad->vb, ad->b);
  if (s == SESSILE_OK) s = sessile_vec_upload(ad->vx, x);
  double t2 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_ksp_solve(ad->la, &o, a, ad->vb, ad->vx, res);
  double t3 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_vec_download(ad->vx, x);
  sessile_mat_destroy(a);
  if (s == SESSILE_OK) {
    for (uint32_t i = 0; i < n; i++) c[i] = mask[i] ? g[i] : x[i];
    ad->t_assemble = t1 - t0;
    ad->t_upload = t2 - t1;
    ad->t_solve = t3 - t2;
    res->seconds = sessile_wall_seconds() - t0;
  }
  free(x);
  return s;
}
