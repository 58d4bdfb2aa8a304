/* The SDS physics on the GPU (shaders/sds): per-element forces, a per-cell
 * gather (and integrator step), the inverted-tet flags; x and v ping-pong
 * between two buffer pairs so that a rejected step is undone by switching
 * back.  Contacts go through per-cell candidate lists (Verlet lists with a
 * skin, docs/sds.md "Collisions"), rebuilt only when they may have gone
 * stale.  Buffer layouts: shaders/sds/kernels.def.
 * This file: the buffers and their uploads (the organism, the parameters,
 * the obstacle), the kernels' choice (storage or texel reads) and the
 * recordings' start and end. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "sds/sds_gpu_internal.h"

/* (Re)creates buffer i with room for `bytes` (contents lost when it grows). */
sessile_status sds_gpu_ensure(sessile_sds_gpu *s, int i, size_t bytes) {
  if (bytes < 16) bytes = 16;
  sessile_buffer_kind kind =
      (i == B_MOVE || i == B_FLAG || i == B_SP || i == B_LMAX || i == B_STEP || i == B_EVENT) ? SESSILE_BUFFER_MAPPED
                                                                              : SESSILE_BUFFER_DEVICE;
  return sessile_buffer_reserve(s->gpu, &s->b[i], bytes, kind);
}

/* Starts a recording: r, m first when update_radii left them pending. */
sessile_status sds_gpu_begin(sessile_sds_gpu *s) {
  SESSILE_CALL(sessile_cmd_begin(s->cmd));
  s->rm_in_rec = s->rm_pending, s->rm_fresh = 0;
  if (s->rm_pending) return sessile_cmd_upload_reals(s->cmd, s->b[B_RM], 0, s->rm, 2 * (size_t)s->ncells);
  return SESSILE_OK;
}

sessile_status sds_gpu_submit(sessile_sds_gpu *s) {
  SESSILE_CALL(sessile_cmd_submit_wait(s->cmd));
  if (s->rm_in_rec) s->rm_pending = 0, s->rm_in_rec = 0;
  return SESSILE_OK;
}

/* Do the views of every buffer the _tex kernels read through texels fit
 * the device's maxTexelBufferElements (texels of one real, or one uint)? */
static int texel_fits(const sessile_sds_gpu *s) {
  static const int reals[] = {B_X0, B_X1, B_V0, B_V1, B_RM, B_SM, B_ELF, B_WORLD, B_FSPH};
  static const int words[] = {B_TOPO, B_LIST, B_OBSTRI, B_HASH};
  for (size_t i = 0; i < sizeof reals / sizeof *reals; i++)
    if (!sessile_buffer_texels_fit(s->b[reals[i]], s->real_bytes)) return 0;
  for (size_t i = 0; i < sizeof words / sizeof *words; i++)
    if (!sessile_buffer_texels_fit(s->b[words[i]], 4)) return 0;
  return 1;
}

/* Kernel k, or its _tex variant (shaders/sds/sds_load.glsl: vector loads on
 * lavapipe, the same bits) when texel reads are allowed and fit. */
sessile_kernel *sds_gpu_kern(const sessile_sds_gpu *s, int k) {
  if (s->reads == 0 && texel_fits(s)) switch (k) {
    case SDS_EDGE: return s->k[SDS_EDGE_TEX];
    case SDS_TET: return s->k[SDS_TET_TEX];
    case SDS_ELEM: return s->k[SDS_ELEM_TEX];
    case SDS_GATHER: return s->k[SDS_GATHER_TEX];
    case SDS_INVERTED: return s->k[SDS_INVERTED_TEX];
    case SDS_CONTACT_LIST: return s->k[SDS_CONTACT_LIST_TEX];
    case SDS_CONTACT_SELF: return s->k[SDS_CONTACT_SELF_TEX];
    case SDS_STABLE: return s->k[SDS_STABLE_TEX];
    default: break;
    }
  return s->k[k];
}

void sessile_sds_gpu_set_reads(sessile_sds_gpu *s, int storage) {
  s->reads = storage != 0;
  lists_invalidate(s); /* the next evaluation builds its lists, */
  s->flags_cur = -1;  /* and the next query its flags, with the kernels chosen */
}

uint32_t sds_gpu_groups(const sessile_sds_gpu *s, int k, uint32_t items) {
  uint32_t l = sessile_kernel_local_size(s->k[k]);
  return (items + l - 1) / l;
}

uint32_t sds_gpu_tail_cap(sessile_gpu *g) {
  /* a CPU device's memory is unified, unless the options take a discrete
   * GPU's paths (SESSILE_STAGED): then its launches too */
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  if (strcmp(i->type, "cpu") != 0 || !i->unified_memory) return 0;
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n < 1 ? 2 : n > 16 ? 32 : 2 * (uint32_t)n;
}

sds_push sds_gpu_push_of(const sessile_sds_gpu *s, double dt, int damping, int mode) {
  sds_push p;
  memset(&p, 0, sizeof p);
  p.dt = sessile_push_real_of(dt, s->real_bytes);
  p.ncells = s->ncells, p.nedges = s->nedges, p.ntets = s->ntets;
  p.nobs = s->nobs, p.nattract = s->nattract;
  p.box = s->p.box != 0, p.damping = damping != 0, p.mode = (uint32_t)mode;
  p.nfaces = s->nfaces;
  p.tsize = s->p.self_collide && s->nfaces && !s->no_contact ? s->tsize : 0;
  p.tsize_obs = s->tsize_obs, p.nobs_v = s->nobs_v;
  if (s->no_contact) p.nobs = 0;
  p.lcap = p.tsize || p.nobs ? s->lcap : 0;
  p.lbase = s->lbase;
  return p;
}

static sessile_status obstacle_upload(sessile_sds_gpu *s, const sessile_sds_params *p, const double *v,
                                      const sds_hash *ho);

sessile_status sessile_sds_gpu_set_params(sessile_sds_gpu *s, const sessile_sds_params *p) {
  SESSILE_CHECK(p->nattract == 0 || p->attract_pos, SESSILE_ERR_USAGE, "sds: %u attraction points without positions",
                p->nattract);
  SESSILE_CHECK(p->obstacle.nf == 0 || (p->obstacle.pos && p->obstacle.tri), SESSILE_ERR_USAGE,
                "sds: an obstacle with %u triangles but no vertices", p->obstacle.nf);
  SESSILE_CHECK(p->obstacle.nf < SDS_LIST_OBS, SESSILE_ERR_TOO_LARGE, "sds: an obstacle of %u triangles is too large",
                p->obstacle.nf);
  s->p = *p;
  double v[SP_COUNT] = {0};
  v[SP_K_EDGE] = p->k_edge, v[SP_K_VOL] = p->k_vol, v[SP_SURF] = p->surface_mult;
  v[SP_UNIFORM] = p->uniform_stiffness ? 1 : 0;
  v[SP_DAMP_VISC] = p->damp_visc, v[SP_DAMP_VOL] = p->damp_vol, v[SP_GRAVITY] = p->gravity;
  for (int i = 0; i < 3; i++) v[SP_LO + i] = p->box_lo[i], v[SP_HI + i] = p->box_hi[i];
  v[SP_K_WALL] = p->k_wall, v[SP_K_ATTRACT] = p->k_attract;
  v[SP_K_CONTACT] = p->k_contact, v[SP_CONTACT] = p->contact_scale, v[SP_H_SELF] = s->h_self;
  /* the stable bound's constants (stable.glsl, as sessile_sds_stable_dt) */
  v[SP_SAFETY] = p->stable_safety, v[SP_DT_MAX] = p->dt_max;
  v[SP_STAB_WALL] = p->box || p->obstacle.nf ? p->k_wall : 0;
  v[SP_STAB_CONTACT] = p->self_collide ? p->k_contact : 0;
  v[SP_ADHESION] = p->obstacle.nf ? p->adhesion : 0, v[SP_FRICTION] = p->obstacle.nf ? p->friction : 0;
  v[SP_STAB_ADH] = sds_stab_adhesion(p);
  v[SP_MASS_DT] = p->mass_scaling_dt;
  /* a batch's step control (stable_min.comp, as sessile_sds_gpu_advance) */
  v[SP_MAX_MOVE] = p->max_move, v[SP_DT_MIN] = p->dt_min, v[SP_AIM] = SDS_MOVE_AIM, v[SP_GROW] = SDS_GROW;
  /* the obstacle is static: its hash table is built here, once, on the host */
  sds_hash ho = {0};
  if (p->obstacle.nf)
    SESSILE_CALL(sds_hash_build(&ho, p->obstacle.pos, p->obstacle.tri, p->obstacle.nf,
                                SDS_HASH_CELL * sds_mean_side(p->obstacle.pos, p->obstacle.tri, p->obstacle.nf)));
  v[SP_H_OBS] = ho.h, v[SP_RHO_OBS] = ho.rho;
  for (int i = 0; i < 3; i++) v[SP_OBS_GLO + i] = ho.glo[i], v[SP_OBS_GHI + i] = ho.ghi[i];
  sessile_status st = obstacle_upload(s, p, v, &ho);
  sds_hash_free(&ho);
  SESSILE_CALL(st);
  s->nobs = p->obstacle.nf, s->nattract = p->nattract;
  s->p.attract_pos = NULL, s->p.obstacle.pos = NULL, s->p.obstacle.tri = NULL; /* not kept */
  lists_invalidate(s);
  return SESSILE_OK;
}

/* Params, attraction points, obstacle vertices, triangles and table. */
static sessile_status obstacle_upload(sessile_sds_gpu *s, const sessile_sds_params *p, const double *v,
                                      const sds_hash *ho) {
  SESSILE_CALL(sds_gpu_ensure(s, B_SP, SP_COUNT * 8));
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_SP], 0, v, SP_COUNT));
  size_t nw = 3 * ((size_t)p->nattract + p->obstacle.nv) + (SDS_OBS_NRM + 4) * (size_t)p->obstacle.nf;
  SESSILE_CALL(sds_gpu_ensure(s, B_WORLD, nw * s->real_bytes));
  size_t nf = p->obstacle.nf, nt = nf ? ho->tsize + 1 + nf : 0;
  SESSILE_CALL(sds_gpu_ensure(s, B_OBSTRI, (3 * nf + nt) * 4));
  if (p->nattract)
    SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_WORLD], 0, p->attract_pos, 3 * (size_t)p->nattract));
  if (p->obstacle.nv)
    SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_WORLD], 3 * (size_t)p->nattract, p->obstacle.pos,
                                             3 * (size_t)p->obstacle.nv));
  if (nf) {
    double *nrm = NULL;
    SESSILE_CALL(sds_obstacle_normals(&p->obstacle, &nrm));
    size_t o0 = 3 * ((size_t)p->nattract + p->obstacle.nv);
    sessile_status st = sessile_buffer_upload_reals(s->b[B_WORLD], o0, nrm, SDS_OBS_NRM * nf);
    free(nrm);
    double *sph = st == SESSILE_OK ? malloc(4 * nf * sizeof *sph) : NULL;
    if (st == SESSILE_OK && !sph)
      st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu spheres", nf);
    if (sph) {
      sds_tri_spheres(p->obstacle.pos, p->obstacle.tri, (uint32_t)nf, sph);
      st = sessile_buffer_upload_reals(s->b[B_WORLD], o0 + SDS_OBS_NRM * nf, sph, 4 * nf);
      free(sph);
    }
    SESSILE_CALL(st);
    SESSILE_CALL(sessile_buffer_upload(s->b[B_OBSTRI], 0, p->obstacle.tri, 3 * nf * 4));
    SESSILE_CALL(sessile_buffer_upload(s->b[B_OBSTRI], 3 * nf * 4, ho->off, ((size_t)ho->tsize + 1) * 4));
    SESSILE_CALL(sessile_buffer_upload(s->b[B_OBSTRI], (3 * nf + ho->tsize + 1) * 4, ho->ent, nf * 4));
  }
  s->tsize_obs = nf ? ho->tsize : 0, s->nobs_v = p->obstacle.nv;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_update_radii(sessile_sds_gpu *s, const sessile_sds *o) {
  SESSILE_CHECK(o->ncells == s->ncells && o->ntets == s->ntets && o->nedges == s->nedges &&
                    o->nfaces == s->nfaces && s->topo_up,
                SESSILE_ERR_USAGE, "sds: radii of %u cells and %u tets for a device organism of %u and %u "
                "(a topology change needs sessile_sds_gpu_upload)", o->ncells, o->ntets, s->ncells, s->ntets);
  size_t n = o->ncells;
  /* they go up with the next recording (begin) */
  for (size_t c = 0; c < n; c++) s->rm[2 * c] = dev_real(s, o->r[c]), s->rm[2 * c + 1] = dev_real(s, o->m[c]);
  s->rm_pending = 1, s->rm_fresh = 0;
  memcpy(s->r_up, o->r, n * sizeof *s->r_up);
  if (s->lists_valid) sds_gpu_lists_check_moves(s, o); /* the topology is the same */
  s->h_self = SDS_HASH_CELL * sds_mean_side(o->x, o->face, o->nfaces);
  double hs = s->h_self;
  return sessile_buffer_upload_reals(s->b[B_SP], SP_H_SELF, &hs, 1);
}

sessile_status sessile_sds_gpu_update_edge_sm(sessile_sds_gpu *s, const sessile_sds *o) {
  SESSILE_CHECK(o->ncells == s->ncells && o->ntets == s->ntets && o->nedges == s->nedges && s->topo_up,
                SESSILE_ERR_USAGE, "sds: rest multipliers of %u edges for a device organism of %u "
                "(a topology change needs sessile_sds_gpu_upload)", o->nedges, s->nedges);
  return o->nedges ? sessile_buffer_upload_reals(s->b[B_SM], o->ntets, o->edge_sm, o->nedges) : SESSILE_OK;
}

sessile_status sessile_sds_gpu_download_edge_sm(sessile_sds_gpu *s, sessile_sds *o) {
  SESSILE_CHECK(o->ncells == s->ncells && o->ntets == s->ntets && o->nedges == s->nedges && s->topo_up,
                SESSILE_ERR_USAGE, "sds: rest multipliers of %u edges from a device organism of %u", o->nedges,
                s->nedges);
  return o->nedges ? sessile_buffer_download_reals(s->b[B_SM], o->ntets, o->edge_sm, o->nedges) : SESSILE_OK;
}

sessile_status sessile_sds_gpu_upload(sessile_sds_gpu *s, const sessile_sds *o) {
  SESSILE_CHECK(o->edge && o->cell_tet_off, SESSILE_ERR_USAGE, "sds: the organism has no derived data (call sessile_sds_rebuild)");
  size_t n = o->ncells, E = o->nedges, T = o->ntets, rb = s->real_bytes;
  size_t nsurf = 0;
  for (size_t c = 0; c < n; c++) nsurf += o->surface[c] != 0;
  size_t F = o->nfaces, ntopo = 4 * T + 2 * E + 2 * (n + 1) + 2 * E + 4 * T + T + E + 3 * F + n + 1 + nsurf;
  SESSILE_CHECK(ntopo < UINT32_MAX && F < SDS_LIST_OBS, SESSILE_ERR_TOO_LARGE,
                "sds: %zu cells and %zu tets are too many for 32-bit indices", n, T);
  for (int i = 0; i < 2; i++) {
    SESSILE_CALL(sds_gpu_ensure(s, B_X0 + i, 3 * n * rb));
    SESSILE_CALL(sds_gpu_ensure(s, B_V0 + i, 3 * n * rb));
  }
  SESSILE_CALL(sds_gpu_ensure(s, B_RM, 2 * n * rb));
  SESSILE_CALL(sds_gpu_ensure(s, B_ATTRACT, n * 4));
  SESSILE_CALL(sds_gpu_ensure(s, B_TOPO, ntopo * 4));
  SESSILE_CALL(sds_gpu_ensure(s, B_SM, (T + 2 * E) * rb)); /* tet_sm, edge_sm, edge_k */
  SESSILE_CALL(sds_gpu_ensure(s, B_ELF, (20 * T + 4 * E) * rb)); /* forces, then the stable bound's terms */
  SESSILE_CALL(sds_gpu_ensure(s, B_F, 3 * n * rb));
  SESSILE_CALL(sds_gpu_ensure(s, B_MOVE, 2 * n * rb));
  SESSILE_CALL(sds_gpu_ensure(s, B_STAB, (5 * n + 3) * rb)); /* bounds, 3 scalars, element sums, inertia */
  SESSILE_CALL(sds_gpu_ensure(s, B_STEP, (SDS_STEP_LOG + 2 * (size_t)SDS_BATCH_MAX) * rb)); /* a batch's log too */
  SESSILE_CALL(sds_gpu_ensure(s, B_EVENT, 4 * 4));
  SESSILE_CALL(sds_gpu_ensure(s, B_SLIVER, SL_WORDS * 4)); /* a batch's lasting slivers (kernels.def, SL_*) */
  SESSILE_CALL(sds_gpu_ensure(s, B_RB, n * rb)); /* a batch with the rules: the radii at the lists' build */
  SESSILE_CALL(sds_gpu_ensure(s, B_DISP, (4 + 3 * SESSILE_INDIRECT_MAX) * 4)); /* a batch's indirect counts */
  if (!s->b[B_CNT]) { /* stable_all's counter, zero between its dispatches (shaders/common/last_group.glsl) */
    const uint32_t zero[4] = {0, 0, 0, 0};
    SESSILE_CALL(sds_gpu_ensure(s, B_CNT, sizeof zero));
    SESSILE_CALL(sessile_buffer_upload(s->b[B_CNT], 0, zero, sizeof zero));
  }
  /* the lists' buffers are sized by their builds (lists_ensure), which keep
   * room for the cells a partial build appends: never shrunk or grown here */
  SESSILE_CALL(sds_gpu_ensure(s, B_XB, 16));
  if (!s->lcap) s->lcap = SDS_LIST_MIN;
  SESSILE_CALL(sds_gpu_ensure(s, B_LIST, 16));
  SESSILE_CALL(sds_gpu_ensure(s, B_LMAX, 16));
  SESSILE_CALL(sds_gpu_ensure(s, B_FLAG, T * 4));
  uint32_t tsize = sds_table_size((uint32_t)F);
  SESSILE_CALL(sds_gpu_ensure(s, B_HASH, (4 * (size_t)tsize + 1 + F + 1) * 4)); /* kernels.def, "The surface hash" */
  SESSILE_CALL(sds_gpu_ensure(s, B_FSPH, 4 * F * rb));
  size_t nh = 2 * n > T + 2 * E ? 2 * n : T + 2 * E;
  double *h = malloc((nh ? nh : 1) * sizeof *h);
  uint32_t *topo = malloc(ntopo * 4);
  if (!h || !topo) {
    free(h), free(topo);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory staging %zu cells", n);
  }
  for (size_t c = 0; c < n; c++) h[2 * c] = o->r[c], h[2 * c + 1] = o->m[c];
  sessile_status st = sessile_buffer_upload_reals(s->b[B_RM], 0, h, 2 * n);
  if (T) memcpy(h, o->tet_sm, T * sizeof *h);
  if (E) memcpy(h + T, o->edge_sm, E * sizeof *h);
  for (size_t e = 0; e < E; e++) h[T + E + e] = o->edge_k ? o->edge_k[e] : 1.0;
  for (size_t e = 0; st == SESSILE_OK && e < E; e++)
    if (!(h[T + E + e] > 0 && h[T + E + e] < INFINITY))
      st = sessile_error_set(SESSILE_ERR_USAGE, "sds: spring %zu has no stiffness multiplier (edge_k %g)", e, h[T + E + e]);
  if (st == SESSILE_OK && T + E) st = sessile_buffer_upload_reals(s->b[B_SM], 0, h, T + 2 * E);
  uint32_t *q = topo;
  if (T) memcpy(q, o->tet, 4 * T * 4);
  q += 4 * T;
  if (E) memcpy(q, o->edge, 2 * E * 4);
  q += 2 * E;
  memcpy(q, o->cell_edge_off, (n + 1) * 4), q += n + 1;
  memcpy(q, o->cell_tet_off, (n + 1) * 4), q += n + 1;
  /* the CSR entries carry the cell's side of the edge and corner of the tet
   * (kernels.def), so that a gather need not search for them */
  for (size_t c = 0; c < n; c++)
    for (uint32_t k = o->cell_edge_off[c]; k < o->cell_edge_off[c + 1]; k++) {
      uint32_t e = o->cell_edge[k];
      q[k] = 2 * e + (o->edge[2 * (size_t)e + 1] == c);
    }
  q += 2 * E;
  for (size_t c = 0; c < n; c++)
    for (uint32_t k = o->cell_tet_off[c]; k < o->cell_tet_off[c + 1]; k++) {
      uint32_t t = o->cell_tet[k], j = 0;
      while (j < 3 && o->tet[4 * (size_t)t + j] != c) j++;
      q[k] = 4 * t + j;
    }
  q += 4 * T;
  for (size_t t = 0; t < T; t++) *q++ = o->tet_surface[t];
  for (size_t e = 0; e < E; e++) *q++ = o->edge_surface[e];
  if (F) memcpy(q, o->face, 3 * F * 4);
  q += 3 * F;
  for (size_t c = 0; c < n; c++) *q++ = o->surface[c];
  *q++ = (uint32_t)nsurf; /* the surface cells, for contact_self's dispatch */
  for (size_t c = 0; c < n; c++)
    if (o->surface[c]) *q++ = (uint32_t)c;
  if (st == SESSILE_OK) st = sessile_buffer_upload(s->b[B_TOPO], 0, topo, ntopo * 4);
  free(h);
  if (st == SESSILE_OK) st = sds_gpu_lists_check_upload(s, o, topo, ntopo);
  else free(topo);
  SESSILE_CALL(st);
  s->cur = 0, s->flags_cur = -1;
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_X0], 0, o->x, 3 * n));
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_V0], 0, o->v, 3 * n));
  SESSILE_CALL(sessile_buffer_upload(s->b[B_ATTRACT], 0, o->attract, n * 4));
  double *sc = realloc(s->scratch, (n ? 3 * n : 1) * sizeof *sc);
  SESSILE_CHECK(sc, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->scratch = sc;
  double *rm = realloc(s->rm, (n ? 2 * n : 1) * sizeof *rm), *hx = NULL, *hv = NULL, *hx2 = NULL, *hv2 = NULL;
  if (rm) s->rm = rm, hx = realloc(s->hx, (n ? 3 * n : 1) * sizeof *hx);
  if (hx) s->hx = hx, hv = realloc(s->hv, (n ? 3 * n : 1) * sizeof *hv);
  if (hv) s->hv = hv, hx2 = realloc(s->hx2, (n ? 3 * n : 1) * sizeof *hx2);
  if (hx2) s->hx2 = hx2, hv2 = realloc(s->hv2, (n ? 3 * n : 1) * sizeof *hv2);
  SESSILE_CHECK(rm && hx && hv && hx2 && hv2, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->hv2 = hv2;
  for (size_t c = 0; c < n; c++) s->rm[2 * c] = dev_real(s, o->r[c]), s->rm[2 * c + 1] = dev_real(s, o->m[c]);
  s->rm_pending = 0, s->mirror = -1, s->rm_fresh = 0;
  s->ncells = (uint32_t)n, s->nedges = (uint32_t)E, s->ntets = (uint32_t)T;
  s->nfaces = (uint32_t)F, s->tsize = tsize, s->nsurf = (uint32_t)nsurf;
  /* hash cell size: the mean boundary side (Teschner et al.: about the mean
   * edge length); only the cost depends on it, never the result */
  s->h_self = SDS_HASH_CELL * sds_mean_side(o->x, o->face, o->nfaces);
  double hs = s->h_self;
  return sessile_buffer_upload_reals(s->b[B_SP], SP_H_SELF, &hs, 1);
}

sessile_status sessile_sds_gpu_create(sessile_gpu *g, const sessile_sds *o, const sessile_sds_params *p,
                                      sessile_sds_gpu **out) {
  *out = NULL;
  sessile_sds_gpu *s = calloc(1, sizeof *s);
  SESSILE_CHECK(s, SESSILE_ERR_NO_MEMORY, "sds: out of memory");
  s->gpu = g;
  s->real_bytes = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  s->tail_cap = sds_gpu_tail_cap(g);
  sessile_status st = SESSILE_OK;
  /* the physics' kernels: the layer's morphogen kernels, declared last, are
   * morph_gpu.c's */
  for (int i = 0; i < SDS_MORPH_STEP && st == SESSILE_OK; i++)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[i], s->real_bytes, 0, &s->k[i]);
  if (st == SESSILE_OK) st = sessile_cmd_create(g, &s->cmd);
  if (st == SESSILE_OK) st = sessile_sds_gpu_set_params(s, p);
  if (st == SESSILE_OK) st = sessile_sds_gpu_upload(s, o);
  if (st != SESSILE_OK) {
    sessile_sds_gpu_destroy(s);
    return st;
  }
  *out = s;
  return SESSILE_OK;
}

void sessile_sds_gpu_destroy(sessile_sds_gpu *s) {
  if (!s) return;
  for (int i = 0; i < B_COUNT; i++) sessile_buffer_destroy(s->b[i]);
  for (int i = 0; i < SDS_MORPH_STEP; i++) sessile_kernel_destroy(s->k[i]);
  sessile_cmd_destroy(s->cmd);
  free(s->scratch), free(s->xb), free(s->rb), free(s->r_up), free(s->topo_up), free(s->sub);
  free(s->rm), free(s->hx), free(s->hv), free(s->hx2), free(s->hv2);
  free(s);
}

sessile_status sessile_sds_gpu_download(sessile_sds_gpu *s, sessile_sds *o) {
  SESSILE_CHECK(o->ncells == s->ncells && o->ntets == s->ntets, SESSILE_ERR_USAGE,
                "sds: downloading into an organism of %u cells, %u tets (uploaded: %u, %u)", o->ncells,
                o->ntets, s->ncells, s->ntets);
  size_t n = s->ncells;
  if (s->mirror == s->cur) { /* the step's own submission downloaded them */
    memcpy(o->x, s->hx, 3 * n * sizeof *o->x);
    memcpy(o->v, s->hv, 3 * n * sizeof *o->v);
  } else {
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_X0 + s->cur], 0, o->x, 3 * n));
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_V0 + s->cur], 0, o->v, 3 * n));
  }
  for (size_t c = 0; c < n; c++) o->r[c] = s->rm[2 * c], o->m[c] = s->rm[2 * c + 1];
  return SESSILE_OK;
}
