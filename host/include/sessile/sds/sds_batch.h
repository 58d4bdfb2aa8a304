/* A batch of SDS physics steps in one submission, the step control on the
 * device (docs/sds.md, "The loop on the device"): the host wakes only when
 * the batch ends or an event stops it. */
#ifndef SESSILE_SDS_BATCH_H
#define SESSILE_SDS_BATCH_H
#include <stdint.h>
#include "sessile/sds/sds.h"

/* The events that stop a batch after the step that raised them (the bits of
 * shaders/sds/kernels.def's SDS_EV_*). */
enum {
  SESSILE_SDS_EV_DIVIDE = 1,     /* a cell asks to divide (with the rules on the device) */
  SESSILE_SDS_EV_REJECT = 2,     /* a step moved a cell more than max_move: undone, dt halved */
  SESSILE_SDS_EV_NONFINITE = 4,  /* a move not finite (the batch then fails: SESSILE_ERR_NUMERIC) */
  SESSILE_SDS_EV_INVERTED = 8,   /* a tet is inverted after the last accepted step */
  SESSILE_SDS_EV_LISTS = 16,     /* the contact lists may be stale (the next batch builds them) */
  SESSILE_SDS_EV_TIME = 32,      /* the last step ended at or past t_stop */
  SESSILE_SDS_EV_DTMIN = 64,     /* the next step would fall below dt_min (SESSILE_ERR_NUMERIC) */
  SESSILE_SDS_EV_HOST = 128      /* with the rules on the device: the last step's rules are the host's */
};
#define SESSILE_SDS_BATCH_MAX 1024 /* steps per batch */

typedef struct sessile_sds_batch {
  uint32_t steps; /* in: at most this many steps (1..SESSILE_SDS_BATCH_MAX) */
  double t_stop;  /* in: stop after the first step ending at or past it (INFINITY: never) */
  double time;    /* in/out: the simulated time */
  double dt;      /* in/out: the step to try (as sessile_sds_gpu_advance's *dt), then the next one */
  uint32_t done;  /* out: the steps accepted */
  uint32_t events;/* out: SESSILE_SDS_EV_* of the step that stopped the batch (0: it ran all its steps) */
  double *log;    /* out, may be NULL: room for 2 x steps, each accepted step's dt and end time */
  /* in, may be NULL: lasting slivers a step may keep (with the rules' hook
   * only; docs/sds.md "The loop on the device"): nslivers pairs of a tet and
   * the steps from the batch's start until its repair is due.  A step whose
   * inverted tets are exactly these, none due and none inverting within the
   * step, goes on; any other inverted tet stops the batch.  NULL: any. */
  const uint32_t *slivers;
  uint32_t nslivers;    /* in: at most SESSILE_SDS_SLIVERS_MAX */
  uint32_t quiet;       /* out: the inverted tets of the accepted steps that went on, summed over the steps */
  uint32_t quiet_last;  /* out: those of the last accepted step */
} sessile_sds_batch;
#define SESSILE_SDS_SLIVERS_MAX 64

/* Up to b->steps accepted steps in one submission, each exactly the step of
 * sessile_sds_gpu_advance (the same bits on an fp64 device: the stable cap,
 * the move check, the next step's aim, the time t + dt, all on the device),
 * with the contact lists built before the batch when stale.  The batch stops
 * after the first step that raises an event: a rejected step (undone; b->dt
 * then holds half its dt, and the next batch retries it), an inverted tet, a
 * stale list, t_stop passed.  The state, and the inverted flags
 * (sessile_sds_gpu_inverted), are those after the last accepted step.  Fails
 * with SESSILE_ERR_NUMERIC as sessile_sds_gpu_advance does. */
sessile_status sessile_sds_gpu_batch(sessile_sds_gpu *s, sessile_sds_batch *b);
/* split 1: a batch checks each step in dispatches of its own (the inverted
 * flags, then the check) right after its gather, the order the rules kernel
 * needs (a step's rules run once it is accepted, before the next step's
 * forces): seven dispatches a step instead of five, the same steps. */
void sessile_sds_gpu_batch_split(sessile_sds_gpu *s, int split);
/* Where the fused kernels run (elem_force, stable_all, step_check; the
 * device_fuse key, docs/sds.md "Fewer dispatches a step"): by the complex's
 * size (the default), always, or never.  The same bits every way. */
typedef enum sessile_sds_fuse { SESSILE_SDS_FUSE_AUTO = 0, SESSILE_SDS_FUSE_ALWAYS = 1, SESSILE_SDS_FUSE_NEVER = 2 } sessile_sds_fuse;
void sessile_sds_gpu_fuse(sessile_sds_gpu *s, sessile_sds_fuse fuse);
#endif
