/* Internal definitions of the geometric multigrid (host/la/mg*.c). */
#ifndef SESSILE_MG_INTERNAL_H
#define SESSILE_MG_INTERNAL_H

#include <stdio.h>
#include "la_internal.h"
#include "sessile/la/mg.h"

#define MG_MAX_LEVELS 16

typedef struct {
  uint32_t n[3], nodes;
  double h;
  sessile_buffer *mask;    /* the caller's */
  const sessile_vec *diag; /* the caller's */
  const sessile_vec *coef; /* the caller's advective weights, or NULL */
  sessile_mat *a;          /* the level's operator (sessile_mat_create_stencil7_cut) */
  sessile_vec *t;          /* the other sweep buffer (ping-pong) */
  sessile_vec *x, *b;      /* coarse levels: the correction and the restricted residual */
} mg_level;

struct sessile_mg {
  sessile_la *la;
  int nl;
  sessile_mg_options o;
  mg_level lv[MG_MAX_LEVELS];
  sessile_vec *r, *z, *p, *q;  /* CG on the finest level */
  sessile_vec *w;              /* omega / (h diag) on free finest nodes, 1 on Dirichlet ones */
  sessile_vec *rb, *dx;        /* fp32 refinement: residual and correction (created on first use) */
  sessile_cmd *start, *iter, *resid, *misc; /* misc: sessile_mg_vcycle */
  uint64_t rec_b, rec_x;       /* serials of the b and x the recordings were made for (0: none) */
  unsigned recordings;         /* times start/iter/resid were recorded (tests read it) */
};

/* Records MG-PCG for b and x (mg_record.c): `start` (up to the first
 * convergence test), `iter` (one iteration, from V-cycle to the next test)
 * and `resid` (the true residual). */
sessile_status mg_record(sessile_mg *mg, const sessile_vec *b, const sessile_vec *x);
/* Records out = M r (one V-cycle) into c; the first sweep x = omega D^-1 r is
 * recorded too unless first_done (then the caller has written it into
 * mg_first_target(mg, out)).  With count, the last sweep also writes the
 * partials of r·out into partial set `set` and *count is their number. */
sessile_status mg_rec_vcycle(sessile_mg *mg, sessile_cmd *c, vref r, vref out, int first_done,
                             uint32_t set, uint32_t *count, int guard);
/* Where the finest level's first sweep goes so that the last lands in out. */
vref mg_first_target(const sessile_mg *mg, vref out);

#endif
