/* "mg": one V-cycle of a geometric multigrid hierarchy (sessile_mg,
 * mg_record.c) as the preconditioner of any Krylov method.  The hierarchy
 * comes from sessile_pc_mg_set (it is built from the caller's level masks
 * and diagonals, not from one matrix); the setup checks that the matrix has
 * the finest level's rows.  The V-cycle kernels read whole buffers, so an
 * r or z inside a larger buffer (GMRES's basis) goes through a scratch
 * vector.  Symmetric (docs/la.md: equal smoothing, R = Pᵀ), so CG takes it;
 * sessile_mg_solve stays the fused MG-PCG for that case. */
#include <stdlib.h>
#include "mg_internal.h"
#include "pc_internal.h"

typedef struct { sessile_vec *in, *out; } mg_scratch;

sessile_status sessile_pc_mg_set(sessile_pc *pc, sessile_mg *mg) {
  SESSILE_CHECK(pc && mg, SESSILE_ERR_USAGE, "pc mg: needs a pc and a multigrid hierarchy");
  SESSILE_CHECK(pc->ops == &la_pc_mg_ops, SESSILE_ERR_USAGE,
                "pc %s: a multigrid hierarchy is for pc mg only", pc->ops->name);
  SESSILE_CHECK(mg->la == pc->la, SESSILE_ERR_USAGE, "pc mg: the hierarchy belongs to another la");
  pc->conf = mg;
  return SESSILE_OK;
}

static void mg_release(sessile_pc *pc) {
  mg_scratch *s = pc->data;
  if (!s) return;
  sessile_vec_destroy(s->in);
  sessile_vec_destroy(s->out);
  free(s);
  pc->data = NULL;
}

static sessile_status mg_setup(sessile_pc *pc, const sessile_mat *a) {
  sessile_mg *mg = pc->conf;
  SESSILE_CHECK(mg, SESSILE_ERR_USAGE,
                "pc mg: no multigrid hierarchy (give one with sessile_pc_mg_set before the setup)");
  SESSILE_CHECK(a->nrows == mg->lv[0].nodes, SESSILE_ERR_USAGE,
                "pc mg: the matrix has %u rows, the hierarchy's finest level %u nodes", a->nrows,
                mg->lv[0].nodes);
  mg_scratch *s = calloc(1, sizeof *s);
  SESSILE_CHECK(s, SESSILE_ERR_NO_MEMORY, "out of host memory");
  pc->data = s;
  SESSILE_CALL(sessile_vec_create(pc->la, a->nrows, &s->in));
  return sessile_vec_create(pc->la, a->nrows, &s->out);
}

static sessile_status mg_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  const mg_scratch *s = pc->data;
  sessile_la *la = pc->la;
  vref none = {0};
  if (r.off4) { /* the kernels read from the buffer's start */
    SESSILE_CALL(rec_vec(la, c, K_COPY, pc->n, r, vref_of(s->in), none, -1, 0, guard));
    r = vref_of(s->in);
  }
  vref out = z.off4 ? vref_of(s->out) : z;
  SESSILE_CALL(mg_rec_vcycle(pc->conf, c, r, out, 0, 0, NULL, guard));
  if (z.off4) SESSILE_CALL(rec_vec(la, c, K_COPY, pc->n, out, z, none, -1, 0, guard));
  return SESSILE_OK;
}

const la_pc_ops la_pc_mg_ops = {"mg", SESSILE_PC_MG, 1, mg_setup, mg_rec, mg_release};
