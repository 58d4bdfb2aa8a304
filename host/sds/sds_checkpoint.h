/* The SDS loop's checkpoint (docs/sds.md, "Checkpoint and resume"): the
 * whole organism (every array of sessile_sds, the derived ones included, so
 * that a restored complex is the same bytes without a rebuild, which would
 * re-orient a tet left inverted) and the loop's scalars, as sections of the
 * run framework's checkpoint.bin.  Host byte order, doubles as their bytes. */
#ifndef SESSILE_SDS_CHECKPOINT_H
#define SESSILE_SDS_CHECKPOINT_H
#include <stdint.h>
#include "sessile/run/run.h"
#include "sessile/sds/sds.h"
#include "sessile/sds/sds_run.h"

/* Everything the loop carries from one step to the next besides the
 * organism.  Only 8-byte members: no padding, the same layout everywhere. */
typedef struct sds_ckpt_loop {
  uint64_t version;              /* SDS_CKPT_VERSION */
  uint64_t key;                  /* sds_ckpt_key of the model and options that made it */
  double time, dt;               /* simulated time, next step */
  int64_t stalled;               /* steps in a row rewound to their start */
  uint64_t rng;                  /* the division-direction stream */
  int64_t frame;                 /* the next frame to write */
  uint64_t steps_frame;          /* steps since the last frame */
  uint64_t div_interval, inv_interval; /* counts since the last record */
  uint64_t steps, divisions, inversions, resisted, slivers, deferred, repairs; /* run totals */
  double c0[3], size0;           /* the starting organism's centroid and size (blow-up test) */
  uint64_t retry_cap;            /* entries of retry_at */
  uint64_t nsliver;              /* entries of the repairs' backoff table (3 words each: sds_inversions.c, repair) */
} sds_ckpt_loop;

#define SDS_CKPT_VERSION 7u /* 7: the springs' edge_k; 6: frames do not cut steps, their times kept; 5: the step control keeps no counter */

/* A 64-bit FNV-1a over the model text and the options that shape the
 * outputs (seed, t_end, frames, cell limit). */
uint64_t sds_ckpt_key(const char *model_text, uint64_t seed, double t_end, int frames, uint32_t max_cells);

/* The key continued over the parameters whose values differ from the model
 * text's own (own): names and values.  None differ: the key as it was, so a
 * run without --set or --config keeps its checkpoint bytes. */
uint64_t sds_ckpt_key_params(uint64_t key, const sessile_sds_run_params *own, const sessile_sds_run_params *p);

/* The state as checkpoint sections (SDS_CKPT_NSECTIONS of them, into s):
 * the organism's arrays, counts (kept in counts_store), the loop's
 * scalars, the deferred divisions, the repairs' backoff and the times of
 * the l->frame frames written ("frame_times").  Returns how many. */
#define SDS_CKPT_NSECTIONS 25
int sds_ckpt_sections(const sessile_sds *o, const sds_ckpt_loop *l, const double *retry_at, const uint64_t *sliver,
                      const double *frame_times, uint64_t counts_store[6], sessile_ckpt_section *s);

/* Reads it back: o (freed first) gets every array, l the scalars, *retry_at
 * a new array of l->retry_cap entries and *sliver one of 3 l->nsliver words
 * (caller frees both).  SESSILE_ERR_USAGE
 * when the checkpoint belongs to another model or configuration (key !=
 * want_key), SESSILE_ERR_IO when it is damaged (sizes that do not fit). */
sessile_status sds_ckpt_read(const sessile_ckpt *ck, uint64_t want_key, uint32_t nmorph, uint32_t nstate,
                             sessile_sds *o, sds_ckpt_loop *l, double **retry_at, uint64_t **sliver);
#endif
