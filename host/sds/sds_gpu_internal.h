/* The SDS physics on the GPU, shared by its files (sessile/sds/sds.h;
 * sds_gpu_buffers.c: the buffers, their uploads and the kernels' choice;
 * sds_gpu_contacts.c: the contact lists; sds_gpu_step.c: forces, steps and
 * their control, the inverted flags; sds_gpu_batch.c: a batch of steps with
 * the control on the device). */
#ifndef SESSILE_SDS_GPU_INTERNAL_H
#define SESSILE_SDS_GPU_INTERNAL_H
#include <stdint.h>
#include "sds/sds_internal.h"
#include "sessile/sds/sds_batch.h"
#include "sds_kernels.h"

enum { B_SP, B_X0, B_X1, B_V0, B_V1, B_RM, B_ATTRACT, B_TOPO, B_SM, B_ELF, B_WORLD, B_OBSTRI, B_F, B_MOVE,
       B_FLAG, B_HASH, B_FSPH, B_LIST, B_XB, B_LMAX, B_STAB, B_STEP, B_EVENT, B_RB, B_DISP, B_CNT, B_SLIVER, B_COUNT };

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
/* Fused kernels only for small complexes (docs/sds.md, "Fewer dispatches a
 * step"): llvmpipe runs both sides of every branch, masked, so a fused
 * dispatch costs each invocation the code of all its parts; above these
 * sizes that costs more than the thread pool's round trip it saves
 * (lavapipe, 2026-12-01).  elem_force (an edge's and a tet's code a
 * invocation) up to SDS_FUSE_ELEM_TETS tets; stable_all and step_check (the
 * last subgroup's minimum and check, run masked by every subgroup) up to
 * SDS_FUSE_MIN_CELLS cells and SDS_FUSE_CHECK_TETS tets, and at any size on
 * a CPU device, where they run on a few workgroups (sds_gpu_tail_cap,
 * 2026-12-04).  Either way the same bits. */
#define SDS_FUSE_ELEM_TETS 1000u
#define SDS_FUSE_MIN_CELLS 400u
#define SDS_FUSE_CHECK_TETS 2000u

/* A batch's per-step hook (sds_gpu_batch.c): records dispatches after step
 * k's check, once the step is accepted, and before step k + 1's forces,
 * which read pair c: the rules kernel and the morphogens (docs/sds.md, "The
 * loop on the device").  Its kernels must honour ev[0] and take the step's
 * dt and end time from the device (step[SDS_STEP_LOG + 2 k], + 1). */
typedef sessile_status (*sds_gpu_batch_hook)(sessile_sds_gpu *s, void *ctx, uint32_t k, int c);

struct sessile_sds_gpu {
  sessile_gpu *gpu;
  uint32_t real_bytes;
  uint32_t tail_cap; /* a fused kernel's most workgroups (sds_gpu_tail_cap; 0: one item an invocation) */
  sessile_kernel *k[SDS_MORPH_STEP]; /* the physics' kernels (kernels.def: the morphogens' come after) */
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
   * when the buffers are not mapped.  A batch, which ends on either pair,
   * downloads both in its submission: the other into hx2, hv2 (swapped in
   * when it is the current), and the radii its rules grew (rm_fresh until
   * the next recording). */
  double *rm, *hx, *hv, *hx2, *hv2;
  int rm_pending, rm_in_rec, mirror, rm_fresh;
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
  struct sds_gpu_rules *rules; /* the rules on the device, borrowed (sds_gpu_rules.h; NULL: on the host) */
  uint32_t nsub_max;           /* a batch with the rules: morphogen sub-steps recorded per step */
  double rules_dt;             /* the step of the last sds_gpu_rules_record */
  int batch_split;  /* a batch checks each step in its own dispatch (sessile_sds_gpu_batch_split) */
  sessile_sds_fuse fuse; /* where the fused kernels run (sessile_sds_gpu_fuse) */
  sds_gpu_batch_hook hook; /* a batch's per-step hook (implies split checks), and its context */
  void *hook_ctx;
  int check_fused; /* a batch step's check made by the rules' step_check (sds_gpu_batch_rules_check) */
  uint32_t batch_slivers; /* entries of the batch being recorded's slivers' table (0: step_check_nosl) */
};
/* A fused kernel's most workgroups on this device.  llvmpipe runs both
 * sides of every branch, so each subgroup of a fused kernel runs the tail
 * (the last subgroup's one-workgroup code) masked: on a CPU device the
 * kernels loop over their items, launched on a few workgroups for each of
 * the device's threads (two per processor online, at most 32); elsewhere, and
 * with a discrete GPU's paths taken (SESSILE_STAGED), one item an
 * invocation (0).  The same bits either way (docs/sds.md, "Tails
 * that every subgroup runs"). */
uint32_t sds_gpu_tail_cap(sessile_gpu *g);
/* Workgroups of a fused kernel k over `items`, capped at cap (0: none). */
static inline uint32_t sds_gpu_tail_groups(uint32_t local, uint32_t items, uint32_t cap) {
  uint32_t n = items ? (items + local - 1) / local : 1;
  return cap && n > cap ? cap : n;
}
/* Does a fused kernel run for a part of `size` elements (SDS_FUSE_*)? */
static inline int sds_gpu_fused(const sessile_sds_gpu *s, uint32_t size, uint32_t limit) {
  return s->fuse == SESSILE_SDS_FUSE_ALWAYS || (s->fuse == SESSILE_SDS_FUSE_AUTO && size <= limit);
}
/* The same for a kernel with a tail (stable_all, step_check): at any size
 * where the tail's masked runs are capped (a CPU device, sds_gpu_tail_cap). */
static inline int sds_gpu_fused_tail(const sessile_sds_gpu *s, uint32_t size, uint32_t limit) {
  return sds_gpu_fused(s, size, s->tail_cap ? UINT32_MAX : limit);
}


/* A real as the device stores it (r, m kept on the host: rm). */
static inline double dev_real(const sessile_sds_gpu *s, double v) { return s->real_bytes == 8 ? v : (double)(float)v; }

/* The contact lists must be built again, every cell's. */
static inline void lists_invalidate(sessile_sds_gpu *s) { s->lists_valid = 0, s->lists_part = 0; }

/* sds_gpu_buffers.c: buffer i with room for bytes; a recording begun (r, m
 * first when pending) and submitted; kernel k or its _tex variant; the
 * workgroups for items; the push constants of a dispatch. */
sessile_status sds_gpu_ensure(sessile_sds_gpu *s, int i, size_t bytes);
sessile_status sds_gpu_begin(sessile_sds_gpu *s);
sessile_status sds_gpu_submit(sessile_sds_gpu *s);
sessile_kernel *sds_gpu_kern(const sessile_sds_gpu *s, int k);
uint32_t sds_gpu_groups(const sessile_sds_gpu *s, int k, uint32_t items);
/* stable_all (the bound and its minimum in one dispatch) rather than
 * stable_tex and stable_min?  Its workgroups (those of stable otherwise). */
int sds_gpu_stable_all(const sessile_sds_gpu *s);
uint32_t sds_gpu_stable_groups(const sessile_sds_gpu *s);
/* elem_force's workgroups: invocation i edge i and tet i. */
uint32_t sds_gpu_elem_groups(const sessile_sds_gpu *s);
sds_push sds_gpu_push_of(const sessile_sds_gpu *s, double dt, int damping, int mode);

/* sds_gpu_step.c: edge, tet and gather dispatches (mode 0, 1 or 2; mode 2
 * with the stable bound between them) reading pair c and writing pair
 * 1 - c; the inverted-tet flags of pair c's x; stable_min alone (a batch's
 * last check; c: the pair of the state it checks).  batch: 0, or 1 + the
 * step's index in a batch (kernels.def). */
sessile_status sds_gpu_record_forces(sessile_sds_gpu *s, int c, double dt, int damping, int mode, uint32_t batch);
sessile_status sds_gpu_record_inverted(sessile_sds_gpu *s, int c, uint32_t batch);
sessile_status sds_gpu_record_stable_min(sessile_sds_gpu *s, const sds_push *p, int c);

/* sds_gpu_contacts.c: the lists' staleness after moves, checks at an upload
 * of radii or of a new complex, a build recorded, and the lists made
 * complete before an evaluation. */
/* contact_scale, or twice it with the obstacle's adhesion: how far a radius's growth moves the lists' reach */
double sds_gpu_reach_scale(const sessile_sds_gpu *s);
int sds_gpu_lists_stale(const sessile_sds_gpu *s, double far_all, double far_surf);
void sds_gpu_lists_check_moves(sessile_sds_gpu *s, const sessile_sds *o);
sessile_status sds_gpu_lists_check_upload(sessile_sds_gpu *s, const sessile_sds *o, uint32_t *topo, size_t ntopo);
sessile_status sds_gpu_record_lists(sessile_sds_gpu *s, int c, uint32_t lsub);
int sds_gpu_contacts_on(const sessile_sds_gpu *s);
sessile_status sds_gpu_lists_ensure(sessile_sds_gpu *s);
#endif
