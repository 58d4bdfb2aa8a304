/* The SDS physics on the GPU (shaders/sds): per-element forces, a per-cell
 * gather (and integrator step), the inverted-tet flags; x and v ping-pong
 * between two buffer pairs so that a rejected step is undone by switching
 * back.  Contacts go through per-cell candidate lists (Verlet lists with a
 * skin, docs/sds.md "Collisions"), rebuilt only when they may have gone
 * stale.  Buffer layouts: shaders/sds/kernels.def. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_internal.h"
#include "sds_kernels.h"

enum { B_SP, B_X0, B_X1, B_V0, B_V1, B_RM, B_ATTRACT, B_TOPO, B_SM, B_ELF, B_WORLD, B_OBSTRI, B_F, B_MOVE,
       B_FLAG, B_HASH, B_FSPH, B_LIST, B_XB, B_LMAX, B_STAB, B_STEP, B_COUNT };

/* The contact lists' skin, a fraction of contact_scale x the mean cell
 * radius: a larger skin rebuilds less often but lists more triangles, which
 * every step then visits (docs/sds.md, "Collisions": 1 measured best). */
#define SDS_SKIN_FRAC 1.0
#define SDS_LIST_MIN 16 /* the first capacity per cell */
/* Step control (docs/sds.md, "Integrator"): the next step aims the largest
 * move at this fraction of max_move, so that few steps are undone, and grows
 * by at most SDS_GROW a step. */
#define SDS_MOVE_AIM 0.8
#define SDS_GROW 1.25

struct sessile_sds_gpu {
  sessile_gpu *gpu;
  uint32_t real_bytes;
  sessile_kernel *k[SDS_COUNT];
  sessile_cmd *cmd;
  sessile_buffer *b[B_COUNT];
  uint32_t ncells, nedges, ntets, nobs, nattract;
  uint32_t nfaces, tsize, tsize_obs, nobs_v; /* boundary faces; surface and obstacle hash table sizes */
  uint32_t nsurf;                    /* surface cells (contact_self's invocations) */
  double h_self;                     /* surface hash cell size (mean boundary side at upload) */
  int no_contact;                    /* the benchmark's switch: contacts left out */
  int cur; /* x, v live in B_X0 + cur, B_V0 + cur */
  sessile_sds_params p;
  double *scratch; /* 3 ncells (host side of downloads) */
  /* the contact lists */
  uint32_t lcap;    /* entries per cell */
  int lists_valid;  /* every triangle within delta of a cell is in its list */
  double skin;      /* of the last build, u */
  double grown;     /* largest r - rb at the last upload (radii do not change on the device) */
  double *xb, *rb;  /* host copies: positions and radii at the last build */
  double *r_up;     /* radii of the last upload */
  /* One submission a step on a discrete GPU (gpu.h, sessile_cmd_upload):
   * rm holds r, m as the device holds them (it never writes them), and goes
   * up with the next recording when rm_pending; a step of the loop downloads
   * its x, v into hx, hv inside its own submission (pair `mirror`, -1: none)
   * when the buffers are not mapped. */
  double *rm, *hx, *hv;
  int rm_pending, rm_in_rec, mirror;
  uint32_t *topo_up; /* the topology words of the last upload (a change invalidates the lists) */
  size_t ntopo_up;
  uint64_t builds;  /* list builds so far (partial ones included) */
  uint64_t partial_builds; /* of which partial: the cells a topology change touched */
  uint32_t lbase;   /* cells the list buffer has room for (B_LIST, B_XB) */
  int lists_part;   /* the next build may be partial: only the cells in sub */
  uint32_t *sub;    /* a partial build's cells, then its surface cells */
  size_t nsub, nsub_surf, sub_cap;
  int flags_cur;    /* B_FLAG holds the inverted flags of pair flags_cur's x (-1: of no current state) */
  int reads;        /* 0: texel reads where the views fit, 1: storage reads always (sessile_sds_gpu_set_reads) */
};

/* (Re)creates buffer i with room for `bytes` (contents lost when it grows). */
static sessile_status ensure(sessile_sds_gpu *s, int i, size_t bytes) {
  if (bytes < 16) bytes = 16;
  sessile_buffer_kind kind =
      (i == B_MOVE || i == B_FLAG || i == B_SP || i == B_LMAX || i == B_STEP) ? SESSILE_BUFFER_MAPPED
                                                                              : SESSILE_BUFFER_DEVICE;
  return sessile_buffer_reserve(s->gpu, &s->b[i], bytes, kind);
}

/* Starts a recording: r, m first when update_radii left them pending. */
static sessile_status begin(sessile_sds_gpu *s) {
  SESSILE_CALL(sessile_cmd_begin(s->cmd));
  s->rm_in_rec = s->rm_pending;
  if (s->rm_pending) return sessile_cmd_upload_reals(s->cmd, s->b[B_RM], 0, s->rm, 2 * (size_t)s->ncells);
  return SESSILE_OK;
}

static sessile_status submit(sessile_sds_gpu *s) {
  SESSILE_CALL(sessile_cmd_submit_wait(s->cmd));
  if (s->rm_in_rec) s->rm_pending = 0, s->rm_in_rec = 0;
  return SESSILE_OK;
}

/* A real as the device stores it (r, m kept on the host: rm). */
static double dev_real(const sessile_sds_gpu *s, double v) { return s->real_bytes == 8 ? v : (double)(float)v; }

/* The contact lists must be built again, every cell's. */
static void lists_invalidate(sessile_sds_gpu *s) { s->lists_valid = 0, s->lists_part = 0; }

/* Do the views of every buffer the _tex kernels read through texels fit
 * the device's maxTexelBufferElements (texels of one real, or one uint)? */
static int texel_fits(const sessile_sds_gpu *s) {
  static const int reals[] = {B_X0, B_X1, B_V0, B_V1, B_RM, B_SM, B_ELF, B_WORLD, B_FSPH};
  static const int words[] = {B_TOPO, B_LIST, B_OBSTRI, B_HASH};
  uint64_t maxt = sessile_gpu_info_of(s->gpu)->max_texel_buffer_elements;
  for (size_t i = 0; i < sizeof reals / sizeof *reals; i++)
    if (sessile_buffer_size(s->b[reals[i]]) / s->real_bytes > maxt) return 0;
  for (size_t i = 0; i < sizeof words / sizeof *words; i++)
    if (sessile_buffer_size(s->b[words[i]]) / 4 > maxt) return 0;
  return 1;
}

/* Kernel k, or its _tex variant (shaders/sds/sds_load.glsl: vector loads on
 * lavapipe, the same bits) when texel reads are allowed and fit. */
static sessile_kernel *kern(const sessile_sds_gpu *s, int k) {
  if (s->reads == 0 && texel_fits(s)) switch (k) {
    case SDS_EDGE: return s->k[SDS_EDGE_TEX];
    case SDS_TET: return s->k[SDS_TET_TEX];
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

static uint32_t groups(const sessile_sds_gpu *s, int k, uint32_t items) {
  uint32_t l = sessile_kernel_local_size(s->k[k]);
  return (items + l - 1) / l;
}

static sds_push push_of(const sessile_sds_gpu *s, double dt, int damping, int mode) {
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
  v[SP_DAMP_VISC] = p->damp_visc, v[SP_DAMP_VOL] = p->damp_vol, v[SP_GRAVITY] = p->gravity;
  for (int i = 0; i < 3; i++) v[SP_LO + i] = p->box_lo[i], v[SP_HI + i] = p->box_hi[i];
  v[SP_K_WALL] = p->k_wall, v[SP_K_ATTRACT] = p->k_attract;
  v[SP_K_CONTACT] = p->k_contact, v[SP_CONTACT] = p->contact_scale, v[SP_H_SELF] = s->h_self;
  /* the stable bound's constants (stable.glsl, as sessile_sds_stable_dt) */
  v[SP_SAFETY] = p->stable_safety, v[SP_DT_MAX] = p->dt_max;
  v[SP_STAB_WALL] = p->box || p->obstacle.nf ? p->k_wall : 0;
  v[SP_STAB_CONTACT] = p->self_collide ? p->k_contact : 0;
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
  SESSILE_CALL(ensure(s, B_SP, SP_COUNT * 8));
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_SP], 0, v, SP_COUNT));
  size_t nw = 3 * ((size_t)p->nattract + p->obstacle.nv) + (SDS_OBS_NRM + 4) * (size_t)p->obstacle.nf;
  SESSILE_CALL(ensure(s, B_WORLD, nw * s->real_bytes));
  size_t nf = p->obstacle.nf, nt = nf ? ho->tsize + 1 + nf : 0;
  SESSILE_CALL(ensure(s, B_OBSTRI, (3 * nf + nt) * 4));
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

/* Have the contact lists gone stale, with every cell at most far_all and
 * every surface cell at most far_surf from where the lists were built, and
 * the radii grown by at most s->grown?  A list holds the triangles within
 * delta + skin of its cell at the build.  An obstacle triangle does not
 * move: its distance to a cell changes by at most the cell's move, so the
 * obstacle's entries hold while far_all + contact_scale grown <= skin.  A
 * boundary face's distance changes by at most the cell's move plus its
 * corners' largest move, and both are surface cells (only they query the
 * surface): 2 far_surf + contact_scale grown <= skin.  Interior cells (most
 * daughters of a division) so count once, and only against the obstacle. */
static int lists_stale(const sessile_sds_gpu *s, double far_all, double far_surf) {
  sds_push p = push_of(s, 0.0, 0, 0);
  double g = s->p.contact_scale * s->grown;
  return (p.nobs && !(far_all + g <= s->skin)) || (p.tsize && !(2 * far_surf + g <= s->skin));
}

/* The lists' staleness at o's x and r (the same complex as at their build,
 * but for the cells skip marks): the largest moves since the build, every
 * cell's and the surface cells', and the radii's growth (kept in s->grown). */
static int lists_moved_stale(sessile_sds_gpu *s, const sessile_sds *o, const uint8_t *skip) {
  double moved = 0, moved_surf = 0, grown = 0;
  for (size_t c = 0; c < o->ncells; c++) {
    if (skip && skip[c]) continue;
    double d2 = 0;
    for (int i = 0; i < 3; i++) d2 += (o->x[3 * c + i] - s->xb[3 * c + i]) * (o->x[3 * c + i] - s->xb[3 * c + i]);
    if (!(d2 <= moved)) moved = d2;
    if (o->surface[c] && !(d2 <= moved_surf)) moved_surf = d2;
    if (!(o->r[c] - s->rb[c] <= grown)) grown = o->r[c] - s->rb[c];
  }
  s->grown = grown;
  return lists_stale(s, sqrt(moved), sqrt(moved_surf));
}

static void lists_check_moves(sessile_sds_gpu *s, const sessile_sds *o) {
  if (lists_moved_stale(s, o, NULL)) lists_invalidate(s);
}

/* The neighbours of cell c, sorted, from a topo upload's edges and CSR
 * (kernels.def's layout, entries 2 e + side) into nb (room for its degree). */
static uint32_t topo_neighbours(const uint32_t *topo, uint32_t n, uint32_t E, uint32_t T, uint32_t c, uint32_t *nb) {
  const uint32_t *edge = topo + 4 * (size_t)T, *ceo = edge + 2 * (size_t)E, *ce = ceo + 2 * ((size_t)n + 1);
  uint32_t k = 0;
  for (uint32_t j = ceo[c]; j < ceo[c + 1]; j++) {
    uint32_t w = ce[j], v = edge[2 * (size_t)(w >> 1) + (1 - (w & 1))];
    uint32_t i = k++;
    while (i > 0 && nb[i - 1] > v) nb[i] = nb[i - 1], i--; /* a few entries: insertion */
    nb[i] = v;
  }
  return k;
}

/* After a topology change, can the lists be kept but for a few cells?  Yes
 * when the boundary is the same faces in the same order (boundary faces
 * are sorted by their cells, sds_complex.c, so an unchanged boundary is an
 * unchanged array), the cells were only appended and fit the lists' room,
 * and the other cells are within the skin of their builds: then a list
 * entry still names the same triangle, and only these need listing anew:
 * the new cells, and every cell whose neighbours changed (a surface cell's
 * self list leaves out the faces at its neighbours; a moved dividing cell
 * is among them).  The others' lists are exactly what a full build would
 * make of them while they stay within the skin.  Fills sub; 0 if not. */
static int lists_partial(sessile_sds_gpu *s, const sessile_sds *o, const uint32_t *topo) {
  uint32_t n0 = s->ncells, E0 = s->nedges, T0 = s->ntets, F = s->nfaces, n = o->ncells;
  /* valid lists, or lists valid but for a partial build not made yet */
  if (!(s->lists_valid || s->lists_part) || !s->topo_up || n < n0 || n > s->lbase || o->nfaces != F) return 0;
  size_t f0 = 4 * (size_t)T0 + 2 * (size_t)E0 + 2 * ((size_t)n0 + 1) + 2 * (size_t)E0 + 4 * (size_t)T0 + T0 + E0;
  size_t f1 = 4 * (size_t)o->ntets + 2 * (size_t)o->nedges + 2 * ((size_t)n + 1) + 2 * (size_t)o->nedges +
              4 * (size_t)o->ntets + o->ntets + o->nedges;
  if (F && memcmp(s->topo_up + f0, topo + f1, 3 * (size_t)F * 4)) return 0;
  size_t cap = n + n + 2;
  if (s->sub_cap < cap) {
    uint32_t *q = realloc(s->sub, cap * sizeof *q);
    if (!q) return 0;
    s->sub = q, s->sub_cap = cap;
  }
  uint32_t dmax = 0;
  for (uint32_t c = 0; c < n; c++)
    if (o->cell_edge_off[c + 1] - o->cell_edge_off[c] > dmax) dmax = o->cell_edge_off[c + 1] - o->cell_edge_off[c];
  const uint32_t *ceo0 = s->topo_up + 4 * (size_t)T0 + 2 * (size_t)E0;
  for (uint32_t c = 0; c < n0; c++)
    if (ceo0[c + 1] - ceo0[c] > dmax) dmax = ceo0[c + 1] - ceo0[c];
  uint32_t *nb = malloc(2 * ((size_t)dmax + 1) * sizeof *nb);
  uint8_t *redo_of = calloc(n ? n : 1, 1); /* the pending partial build's cells are redone too */
  if (!nb || !redo_of) {
    free(nb), free(redo_of);
    return 0;
  }
  if (s->lists_part)
    for (size_t i = 0; i < s->nsub; i++)
      if (s->sub[i] < n0) redo_of[s->sub[i]] = 1;
  size_t k = 0;
  for (uint32_t c = 0; c < n; c++) {
    int redo = c >= n0 || redo_of[c];
    if (!redo) {
      uint32_t a = topo_neighbours(s->topo_up, n0, E0, T0, c, nb);
      uint32_t b = topo_neighbours(topo, n, o->nedges, o->ntets, c, nb + dmax + 1);
      redo = a != b || memcmp(nb, nb + dmax + 1, a * sizeof *nb);
    }
    if (redo) s->sub[k++] = c, redo_of[c] = 1;
  }
  free(nb);
  int stale = lists_moved_stale(s, o, redo_of); /* the kept lists: still within the skin? */
  free(redo_of);
  if (stale) return 0;
  size_t ns = 0;
  for (size_t i = 0; i < k; i++)
    if (o->surface[s->sub[i]]) s->sub[k + ns++] = s->sub[i];
  s->nsub = k, s->nsub_surf = ns;
  return 1;
}

/* Are the contact lists still complete for the organism about to be
 * uploaded?  After a topology change, complete but for the cells of a
 * partial build (lists_partial) or not at all; else lists_stale with the
 * host's x and r.  Takes topo (malloc'd, ntopo words) as the new reference. */
static sessile_status lists_check_upload(sessile_sds_gpu *s, const sessile_sds *o, uint32_t *topo, size_t ntopo) {
  size_t n = o->ncells;
  int same = s->topo_up && s->ntopo_up == ntopo && n == s->ncells && !memcmp(s->topo_up, topo, ntopo * 4);
  int part = !same && lists_partial(s, o, topo);
  free(s->topo_up);
  s->topo_up = topo, s->ntopo_up = ntopo;
  double *ru = realloc(s->r_up, (n ? n : 1) * sizeof *ru);
  SESSILE_CHECK(ru, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->r_up = ru;
  memcpy(ru, o->r, n * sizeof *ru);
  if (part) {
    s->lists_valid = 0, s->lists_part = 1;
    return SESSILE_OK;
  }
  if (!same || !s->lists_valid) {
    lists_invalidate(s);
    return SESSILE_OK;
  }
  lists_check_moves(s, o);
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
  s->rm_pending = 1;
  memcpy(s->r_up, o->r, n * sizeof *s->r_up);
  if (s->lists_valid) lists_check_moves(s, o); /* the topology is the same */
  s->h_self = SDS_HASH_CELL * sds_mean_side(o->x, o->face, o->nfaces);
  double hs = s->h_self;
  return sessile_buffer_upload_reals(s->b[B_SP], SP_H_SELF, &hs, 1);
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
    SESSILE_CALL(ensure(s, B_X0 + i, 3 * n * rb));
    SESSILE_CALL(ensure(s, B_V0 + i, 3 * n * rb));
  }
  SESSILE_CALL(ensure(s, B_RM, 2 * n * rb));
  SESSILE_CALL(ensure(s, B_ATTRACT, n * 4));
  SESSILE_CALL(ensure(s, B_TOPO, ntopo * 4));
  SESSILE_CALL(ensure(s, B_SM, (T + E) * rb));
  SESSILE_CALL(ensure(s, B_ELF, (20 * T + 4 * E) * rb)); /* forces, then the stable bound's terms */
  SESSILE_CALL(ensure(s, B_F, 3 * n * rb));
  SESSILE_CALL(ensure(s, B_MOVE, 2 * n * rb));
  SESSILE_CALL(ensure(s, B_STAB, (4 * n + 3) * rb)); /* bounds, 3 scalars, element sums */
  SESSILE_CALL(ensure(s, B_STEP, 3 * rb));
  /* the lists' buffers are sized by their builds (lists_ensure), which keep
   * room for the cells a partial build appends: never shrunk or grown here */
  SESSILE_CALL(ensure(s, B_XB, 16));
  if (!s->lcap) s->lcap = SDS_LIST_MIN;
  SESSILE_CALL(ensure(s, B_LIST, 16));
  SESSILE_CALL(ensure(s, B_LMAX, 16));
  SESSILE_CALL(ensure(s, B_FLAG, T * 4));
  uint32_t tsize = sds_table_size((uint32_t)F);
  SESSILE_CALL(ensure(s, B_HASH, (4 * (size_t)tsize + 1 + F + 1) * 4)); /* kernels.def, "The surface hash" */
  SESSILE_CALL(ensure(s, B_FSPH, 4 * F * rb));
  size_t nh = 2 * n > T + E ? 2 * n : T + E;
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
  if (st == SESSILE_OK && T + E) st = sessile_buffer_upload_reals(s->b[B_SM], 0, h, T + E);
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
  if (st == SESSILE_OK) st = lists_check_upload(s, o, topo, ntopo);
  else free(topo);
  SESSILE_CALL(st);
  s->cur = 0, s->flags_cur = -1;
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_X0], 0, o->x, 3 * n));
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_V0], 0, o->v, 3 * n));
  SESSILE_CALL(sessile_buffer_upload(s->b[B_ATTRACT], 0, o->attract, n * 4));
  double *sc = realloc(s->scratch, (n ? 3 * n : 1) * sizeof *sc);
  SESSILE_CHECK(sc, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->scratch = sc;
  double *rm = realloc(s->rm, (n ? 2 * n : 1) * sizeof *rm), *hx = NULL, *hv = NULL;
  if (rm) s->rm = rm, hx = realloc(s->hx, (n ? 3 * n : 1) * sizeof *hx);
  if (hx) s->hx = hx, hv = realloc(s->hv, (n ? 3 * n : 1) * sizeof *hv);
  SESSILE_CHECK(rm && hx && hv, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->hv = hv;
  for (size_t c = 0; c < n; c++) s->rm[2 * c] = dev_real(s, o->r[c]), s->rm[2 * c + 1] = dev_real(s, o->m[c]);
  s->rm_pending = 0, s->mirror = -1;
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
  sessile_status st = SESSILE_OK;
  for (int i = 0; i < SDS_COUNT && st == SESSILE_OK; i++)
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
  for (int i = 0; i < SDS_COUNT; i++) sessile_kernel_destroy(s->k[i]);
  sessile_cmd_destroy(s->cmd);
  free(s->scratch), free(s->xb), free(s->rb), free(s->r_up), free(s->topo_up), free(s->sub);
  free(s->rm), free(s->hx), free(s->hv);
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

/* Records the surface hash of pair c's x (if self-collision is on) and the
 * contact lists' build (kernels.def, "The contact lists"). */
/* Records a build of the lists: every cell's (lsub 0) or those of a
 * partial build (lsub cells in lmax, kernels.def). */
static sessile_status record_lists(sessile_sds_gpu *s, int c, uint32_t lsub) {
  sds_push p = push_of(s, 0.0, 0, 0);
  p.lsub = lsub;
  if (p.tsize) { /* the surface hash of x (kernels.def, "The surface hash") */
    sessile_buffer *bh[] = {s->b[B_HASH]};
    sessile_buffer *bc[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_TOPO], s->b[B_HASH]};
    sessile_buffer *bs[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_TOPO], s->b[B_HASH], s->b[B_FSPH]};
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_CLEAR], groups(s, SDS_HASH_CLEAR, p.tsize), bh, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_COUNT], groups(s, SDS_HASH_COUNT, p.nfaces), bs, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_SCAN], 1, bh, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_FILL], groups(s, SDS_HASH_FILL, p.nfaces), bc, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_SORT], groups(s, SDS_HASH_SORT, p.tsize), bh, &p));
  }
  sessile_buffer *b[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_RM],   s->b[B_TOPO], s->b[B_WORLD], s->b[B_OBSTRI],
                         s->b[B_HASH], s->b[B_FSPH],   s->b[B_LIST], s->b[B_XB],   s->b[B_LMAX]};
  SESSILE_CALL(sessile_cmd_dispatch(s->cmd, kern(s, SDS_CONTACT_LIST),
                                    groups(s, SDS_CONTACT_LIST, lsub ? lsub : s->ncells), b, &p));
  uint32_t nsurf = lsub ? (uint32_t)s->nsub_surf : s->nsurf;
  if (!p.tsize || !nsurf) return SESSILE_OK;
  sessile_buffer *bs[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_RM],   s->b[B_TOPO],
                          s->b[B_HASH], s->b[B_FSPH],   s->b[B_LIST], s->b[B_LMAX]};
  return sessile_cmd_dispatch(s->cmd, kern(s, SDS_CONTACT_SELF), groups(s, SDS_CONTACT_SELF, nsurf), bs, &p);
}

static int contacts_on(const sessile_sds_gpu *s) {
  sds_push p = push_of(s, 0.0, 0, 0);
  return p.lcap != 0;
}

/* The skin of the next build: SDS_SKIN_FRAC x contact_scale x the mean radius. */
static double skin_now(const sessile_sds_gpu *s) {
  double sum = 0;
  for (uint32_t c = 0; c < s->ncells; c++) sum += s->r_up[c];
  return SDS_SKIN_FRAC * s->p.contact_scale * (s->ncells ? sum / s->ncells : 1.0);
}

/* A partial build (lists_partial): lists only the cells in sub, the others
 * untouched; *ok 0 when a list overflowed (then a full build follows). */
static sessile_status lists_build_part(sessile_sds_gpu *s, int *ok) {
  *ok = 0;
  SESSILE_CALL(ensure(s, B_LMAX, (2 + s->nsub + s->nsub_surf) * 4)); /* rewritten below */
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  SESSILE_CHECK(lmax, SESSILE_ERR_INTERNAL, "sds: the contact-list count buffer is not mapped");
  lmax[0] = 0, lmax[1] = (uint32_t)s->nsub_surf;
  memcpy(lmax + 2, s->sub, (s->nsub + s->nsub_surf) * sizeof *lmax);
  if (s->nsub) {
    SESSILE_CALL(begin(s));
    SESSILE_CALL(record_lists(s, s->cur, (uint32_t)s->nsub));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(submit(s));
  }
  s->builds++, s->partial_builds++;
  if (lmax[0] > s->lcap) return SESSILE_OK;
  size_t n = s->ncells;
  double *xb = realloc(s->xb, (n ? 3 * n : 1) * sizeof *xb), *rb = realloc(s->rb, (n ? n : 1) * sizeof *rb);
  if (xb) s->xb = xb;
  if (rb) s->rb = rb;
  SESSILE_CHECK(xb && rb, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  SESSILE_CALL(sessile_buffer_download_reals(s->b[B_XB], 0, xb, 3 * n)); /* the others' are unchanged */
  for (size_t i = 0; i < s->nsub; i++) rb[s->sub[i]] = s->r_up[s->sub[i]];
  s->lists_valid = 1, s->lists_part = 0;
  *ok = 1;
  return SESSILE_OK;
}

/* Builds the contact lists at the current x (pair cur) when they are stale,
 * growing them until every count fits; keeps xb and the radii on the host.
 * The lists get room for a quarter more cells than there are, so that a
 * division's daughters can be listed by a partial build. */
static sessile_status lists_ensure(sessile_sds_gpu *s) {
  if (s->lists_valid || !contacts_on(s)) return SESSILE_OK;
  if (s->lists_part) {
    int ok = 0;
    SESSILE_CALL(lists_build_part(s, &ok));
    if (ok) return SESSILE_OK;
    lists_invalidate(s); /* an overflow: grow and build every list */
  }
  double skin = skin_now(s);
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_SP], SP_SKIN, &skin, 1));
  size_t lbase = (size_t)s->ncells + s->ncells / 4 + 16;
  SESSILE_CHECK(lbase * ((size_t)s->lcap + 1) < UINT32_MAX, SESSILE_ERR_TOO_LARGE,
                "sds: contact lists of %zu cells x %u entries are too many for 32-bit indices", lbase, s->lcap);
  s->lbase = (uint32_t)lbase;
  SESSILE_CALL(ensure(s, B_LIST, (lbase + lbase * (size_t)s->lcap) * 4));
  SESSILE_CALL(ensure(s, B_XB, 3 * lbase * s->real_bytes));
  SESSILE_CALL(ensure(s, B_LMAX, 16));
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  SESSILE_CHECK(lmax, SESSILE_ERR_INTERNAL, "sds: the contact-list count buffer is not mapped");
  for (;;) {
    lmax[0] = 0;
    SESSILE_CALL(begin(s));
    SESSILE_CALL(record_lists(s, s->cur, 0));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(submit(s));
    s->builds++;
    if (lmax[0] <= s->lcap) break;
    uint32_t cap = s->lcap;
    while (cap < lmax[0]) {
      SESSILE_CHECK(cap <= (1u << 20), SESSILE_ERR_TOO_LARGE, "sds: %u contact candidates for one cell", lmax[0]);
      cap *= 2;
    }
    SESSILE_CHECK(lbase * ((size_t)cap + 1) < UINT32_MAX, SESSILE_ERR_TOO_LARGE,
                  "sds: contact lists of %zu cells x %u entries are too many for 32-bit indices", lbase, cap);
    s->lcap = cap;
    SESSILE_CALL(ensure(s, B_LIST, (lbase + lbase * (size_t)cap) * 4));
  }
  size_t n = s->ncells;
  double *xb = realloc(s->xb, (n ? 3 * n : 1) * sizeof *xb), *rb = realloc(s->rb, (n ? n : 1) * sizeof *rb);
  if (xb) s->xb = xb;
  if (rb) s->rb = rb;
  SESSILE_CHECK(xb && rb, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  SESSILE_CALL(sessile_buffer_download_reals(s->b[B_XB], 0, xb, 3 * n));
  memcpy(rb, s->r_up, n * sizeof *rb);
  s->skin = skin, s->lists_valid = 1, s->grown = 0;
  return SESSILE_OK;
}

static sessile_status record_edge(sessile_sds_gpu *s, int c, const sds_push *p) {
  if (!s->nedges) return SESSILE_OK;
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_RM], s->b[B_TOPO], s->b[B_SM], s->b[B_ELF]};
  return sessile_cmd_dispatch(s->cmd, kern(s, SDS_EDGE), groups(s, SDS_EDGE, s->nedges), b, p);
}

static sessile_status record_tet(sessile_sds_gpu *s, int c, const sds_push *p) {
  if (!s->ntets) return SESSILE_OK;
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_V0 + c], s->b[B_RM], s->b[B_TOPO], s->b[B_SM],
                         s->b[B_ELF]};
  return sessile_cmd_dispatch(s->cmd, kern(s, SDS_TET), groups(s, SDS_TET, s->ntets), b, p);
}

/* Records the stable bound (after record_edge and record_tet in mode 2,
 * whose terms it reads): per cell, then the min and the capped step into
 * stab. */
static sessile_status record_stable(sessile_sds_gpu *s, const sds_push *p) {
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_RM], s->b[B_TOPO], s->b[B_ELF], s->b[B_STAB]};
  SESSILE_CALL(sessile_cmd_dispatch(s->cmd, kern(s, SDS_STABLE), groups(s, SDS_STABLE, s->ncells), b, p));
  sessile_buffer *bm[] = {s->b[B_SP], s->b[B_STAB], s->b[B_STEP]};
  return sessile_cmd_dispatch(s->cmd, s->k[SDS_STABLE_MIN], 1, bm, p);
}

/* Records edge, tet and gather dispatches (mode 0, 1 or 2; mode 2 with the
 * stable bound between them) reading pair c and writing pair 1 - c. */
static sessile_status record_forces(sessile_sds_gpu *s, int c, double dt, int damping, int mode) {
  sds_push p = push_of(s, dt, damping, mode);
  int nx = 1 - c;
  SESSILE_CALL(record_edge(s, c, &p));
  SESSILE_CALL(record_tet(s, c, &p));
  if (mode == 2) SESSILE_CALL(record_stable(s, &p));
  sessile_buffer *b[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_V0 + c], s->b[B_RM],      s->b[B_ATTRACT],
                         s->b[B_TOPO], s->b[B_ELF],    s->b[B_WORLD],  s->b[B_OBSTRI],  s->b[B_LIST],
                         s->b[B_XB],   s->b[B_X0 + nx],
                         s->b[B_V0 + nx], s->b[B_F],   s->b[B_MOVE],    s->b[B_STAB]};
  return sessile_cmd_dispatch(s->cmd, kern(s, SDS_GATHER), groups(s, SDS_GATHER, s->ncells), b, &p);
}

/* Records the inverted-tet flags of pair c's x. */
static sessile_status record_inverted(sessile_sds_gpu *s, int c) {
  sds_push p = push_of(s, 0.0, 0, 0);
  sessile_buffer *b[] = {s->b[B_X0 + c], s->b[B_TOPO], s->b[B_FLAG]};
  return sessile_cmd_dispatch(s->cmd, kern(s, SDS_INVERTED), groups(s, SDS_INVERTED, s->ntets), b, &p);
}

/* One force evaluation (mode 0) or step (mode 1, or 2 with the step capped
 * by the stable bound) in one submission; a step also flags the inverted
 * tets of its result (read by sessile_sds_gpu_inverted without a submission
 * of its own). */
static sessile_status run_forces(sessile_sds_gpu *s, double dt, int damping, int mode) {
  SESSILE_CALL(lists_ensure(s));
  SESSILE_CALL(begin(s));
  SESSILE_CALL(record_forces(s, s->cur, dt, damping, mode));
  int nx = 1 - s->cur, rec = mode != 0 && !sessile_buffer_host_ptr(s->b[B_X0 + nx]);
  if (mode != 0 && s->ntets) SESSILE_CALL(record_inverted(s, nx));
  if (rec) { /* the loop downloads every step's x, v: in this submission */
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_X0 + nx], 0, s->hx, 3 * (size_t)s->ncells));
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_V0 + nx], 0, s->hv, 3 * (size_t)s->ncells));
  }
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  s->flags_cur = -1, s->mirror = -1;
  SESSILE_CALL(submit(s));
  if (mode != 0) s->flags_cur = nx;
  if (rec) s->mirror = nx;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_steps(sessile_sds_gpu *s, uint32_t steps, double dt) {
  SESSILE_CHECK(steps >= 1 && steps <= 1024, SESSILE_ERR_USAGE, "sds: steps per batch must be 1..1024 (got %u)", steps);
  /* no move check inside a batch: the lists are built again before every
   * step (at the capacity of a build at the start), so that a batch gives
   * the bytes of single steps */
  SESSILE_CALL(lists_ensure(s));
  int lists = contacts_on(s);
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  if (lmax) lmax[0] = 0;
  SESSILE_CALL(begin(s));
  for (uint32_t k = 0; k < steps; k++) {
    if (lists && k > 0) SESSILE_CALL(record_lists(s, (s->cur + (int)k) & 1, 0));
    SESSILE_CALL(record_forces(s, (s->cur + (int)k) & 1, dt, 1, 1));
  }
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  s->flags_cur = -1, s->mirror = -1;
  SESSILE_CALL(submit(s));
  s->cur = (s->cur + (int)steps) & 1;
  if (lists && steps > 1) {
    lists_invalidate(s); /* built inside the batch: xb is not on the host */
    SESSILE_CHECK(lmax && lmax[0] <= s->lcap, SESSILE_ERR_TOO_LARGE,
                  "sds: a cell had %u contact candidates inside a batch of steps, more than the lists hold (%u): "
                  "use single steps", lmax ? lmax[0] : 0, s->lcap);
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_forces(sessile_sds_gpu *s, int with_damping, double *f) {
  SESSILE_CALL(run_forces(s, 0.0, with_damping, 0));
  return sessile_buffer_download_reals(s->b[B_F], 0, f, 3 * (size_t)s->ncells);
}

/* One step of mode 1 (dt as given) or 2 (dt capped by the stable bound;
 * B_STEP then holds the step taken, the cap and the bound).  A step that
 * max_move undoes computes the bound again on its retry: 1.7 % of the
 * steps, not worth keeping the bound across submissions. */
static sessile_status step_mode(sessile_sds_gpu *s, double dt, int mode, double *max_move) {
  SESSILE_CALL(run_forces(s, dt, 1, mode));
  s->cur = 1 - s->cur;
  if (s->lists_valid && contacts_on(s)) { /* still complete at the new x? (radii do not change here) */
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_MOVE], s->ncells, s->scratch, s->ncells));
    const uint32_t *surf = s->topo_up + s->ntopo_up - 1 - s->nsurf - s->ncells; /* cell_surf (topo's layout: kernels.def) */
    double far = 0, far_surf = 0;
    for (uint32_t c = 0; c < s->ncells; c++) {
      if (!(s->scratch[c] <= far)) far = s->scratch[c];
      if (surf[c] && !(s->scratch[c] <= far_surf)) far_surf = s->scratch[c];
    }
    if (lists_stale(s, far, far_surf)) lists_invalidate(s);
  }
  if (max_move) {
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_MOVE], 0, s->scratch, s->ncells));
    double mv = 0;
    for (uint32_t c = 0; c < s->ncells; c++)
      if (!(s->scratch[c] <= mv)) mv = s->scratch[c]; /* NaN propagates */
    *max_move = mv;
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_step(sessile_sds_gpu *s, double dt, double *max_move) {
  return step_mode(s, dt, 1, max_move);
}

sessile_status sessile_sds_gpu_stable_dt(sessile_sds_gpu *s, double *bound) {
  sds_push p = push_of(s, 0.0, 1, 2);
  SESSILE_CALL(begin(s));
  SESSILE_CALL(record_edge(s, s->cur, &p));
  SESSILE_CALL(record_tet(s, s->cur, &p));
  SESSILE_CALL(record_stable(s, &p));
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  SESSILE_CALL(submit(s));
  return sessile_buffer_download_reals(s->b[B_STEP], 2, bound, 1);
}

sessile_status sessile_sds_gpu_advance(sessile_sds_gpu *s, uint32_t steps, double *dt, double *elapsed) {
  const sessile_sds_params *p = &s->p;
  double h = *dt; /* asked for: each step takes min(h, the cap of its state's stable bound) */
  uint32_t done = 0;
  while (done < steps) {
    double mv, hc[2]; /* the step taken, the cap */
    SESSILE_CALL(step_mode(s, h, 2, &mv));
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_STEP], 0, hc, 2));
    /* the step taken: the one asked when the device took it (an fp32 device
     * returns it rounded to float, and a time short of a frame by that
     * rounding would ask a step below dt_min next), else its cap */
    if (hc[0] != dev_real(s, h)) h = hc[0];
    if (!isfinite(mv))
      return sessile_error_set(SESSILE_ERR_NUMERIC, "sds: the state is not finite after a step of %g s (blow-up)", h);
    if (mv > p->max_move) { /* undo: the previous x, v are still in the other pair */
      s->cur = 1 - s->cur;
      h *= 0.5;
      SESSILE_CHECK(h >= p->dt_min, SESSILE_ERR_NUMERIC,
                    "sds: the step fell below dt_min = %g s (a cell moves %g radii per step)", p->dt_min, mv);
      continue;
    }
    done++;
    if (elapsed) *elapsed += h;
    /* the next step: a cell's move grows with the step, so aim the largest
     * at SDS_MOVE_AIM x max_move, growing by at most SDS_GROW a step (the
     * device caps whatever is asked at its bound) */
    double f = mv > 0 ? SDS_MOVE_AIM * p->max_move / mv : SDS_GROW, taken = h;
    h *= f < SDS_GROW ? f : SDS_GROW;
    if (h > p->dt_max) h = p->dt_max;
    SESSILE_CHECK(h >= p->dt_min, SESSILE_ERR_NUMERIC,
                  "sds: the step fell below dt_min = %g s (a cell moved %g radii in a step of %g s)", p->dt_min, mv,
                  taken);
  }
  *dt = h;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_inverted(sessile_sds_gpu *s, uint32_t **list, uint32_t *n) {
  *list = NULL, *n = 0;
  if (s->ntets && s->flags_cur != s->cur) { /* not flagged by the step that made this state */
    SESSILE_CALL(begin(s));
    SESSILE_CALL(record_inverted(s, s->cur));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(submit(s));
    s->flags_cur = s->cur;
  }
  const uint32_t *flag = sessile_buffer_host_ptr(s->b[B_FLAG]);
  SESSILE_CHECK(flag, SESSILE_ERR_INTERNAL, "sds: the inverted-flag buffer is not mapped");
  uint32_t cnt = 0;
  for (uint32_t t = 0; t < s->ntets; t++) cnt += flag[t] != 0;
  *list = malloc((cnt ? cnt : 1) * sizeof **list);
  SESSILE_CHECK(*list, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u inverted tets", cnt);
  for (uint32_t t = 0, k = 0; t < s->ntets; t++)
    if (flag[t]) (*list)[k++] = t;
  *n = cnt;
  return SESSILE_OK;
}

void sessile_sds_gpu_list_builds(const sessile_sds_gpu *s, uint64_t *all, uint64_t *partial) {
  *all = s->builds, *partial = s->partial_builds;
}

sessile_status sessile_sds_gpu_hash_table(sessile_sds_gpu *s, uint32_t **table, size_t *n) {
  *table = NULL, *n = 0;
  size_t len = 3 * (size_t)s->tsize + 1 + s->nfaces + 1;
  uint32_t *t = malloc(len * 4);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "sds: out of memory for a hash table of %zu words", len);
  sessile_status st = sessile_buffer_download(s->b[B_HASH], 0, t, len * 4);
  if (st != SESSILE_OK) {
    free(t);
    return st;
  }
  *table = t, *n = len;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_time_contacts(sessile_sds_gpu *s, int reps, double *ms_all, double *ms_nocontact,
                                             double *ms_build) {
  *ms_build = 0;
  if (contacts_on(s)) {
    double t0 = sessile_wall_seconds();
    for (int k = 0; k < reps; k++) {
      lists_invalidate(s);
      SESSILE_CALL(lists_ensure(s));
    }
    *ms_build = 1e3 * (sessile_wall_seconds() - t0) / (reps > 0 ? reps : 1);
  }
  for (int pass = 0; pass < 2; pass++) {
    s->no_contact = pass;
    SESSILE_CALL(run_forces(s, 0.0, 1, 0)); /* warm-up */
    double t0 = sessile_wall_seconds();
    for (int k = 0; k < reps; k++) {
      sessile_status st = run_forces(s, 0.0, 1, 0);
      if (st != SESSILE_OK) {
        s->no_contact = 0;
        return st;
      }
    }
    *(pass ? ms_nocontact : ms_all) = 1e3 * (sessile_wall_seconds() - t0) / (reps > 0 ? reps : 1);
  }
  s->no_contact = 0;
  return SESSILE_OK;
}
