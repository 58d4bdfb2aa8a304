/* "mg" on a 4x4 block matrix: one V-cycle of a block multigrid hierarchy
 * (sessile_bmg, bmg_record.c) as the right preconditioner of GMRES or
 * BiCGSTAB.  Registered under the name "mg" with the scalar hierarchy
 * (pc_mg.c); sessile_pc_mg_set_block turns an "mg" pc into this one before
 * its setup.  The setup builds the hierarchy's operators from the matrix
 * (sessile_bmg_setup).  The kernels read whole vectors, so an r or z inside
 * a larger buffer (GMRES's basis) goes through a scratch vector; the fp32
 * cycle's casts read and write them in place (no scratch).
 * Nonsymmetric (Gauss-Seidel, and the Jacobian is): CG refuses it. */
#include <stdlib.h>
#include "bmg_internal.h"
#include "pc_internal.h"

typedef struct { sessile_vec *in, *out; } bmg_scratch;

static void bmg_release(sessile_pc *pc) {
  bmg_scratch *s = pc->data;
  if (!s) return;
  sessile_vec_destroy(s->in);
  sessile_vec_destroy(s->out);
  free(s);
  pc->data = NULL;
}

static sessile_status bmg_setup(sessile_pc *pc, const sessile_mat *a) {
  sessile_bmg *mg = pc->conf;
  SESSILE_CHECK(mg, SESSILE_ERR_USAGE, "pc mg: no block hierarchy (sessile_pc_mg_set_block)");
  SESSILE_CALL(sessile_bmg_setup(mg, a));
  bmg_scratch *s = calloc(1, sizeof *s);
  SESSILE_CHECK(s, SESSILE_ERR_NO_MEMORY, "out of host memory");
  pc->data = s;
  if (mg->f32) return SESSILE_OK;
  SESSILE_CALL(sessile_vec_create(pc->la, a->nrows, &s->in));
  return sessile_vec_create(pc->la, a->nrows, &s->out);
}

static sessile_status bmg_rec(const sessile_pc *pc, sessile_cmd *c, vref r, vref z, int guard) {
  const bmg_scratch *s = pc->data;
  sessile_la *la = pc->la;
  vref none = {0};
  if (!s->in) return bmg_rec_cycle(pc->conf, c, r, z, guard); /* fp32: the casts take offsets */
  if (r.off4) {
    SESSILE_CALL(rec_vec(la, c, K_COPY, pc->n, r, vref_of(s->in), none, -1, 0, guard));
    r = vref_of(s->in);
  }
  vref out = z.off4 ? vref_of(s->out) : z;
  SESSILE_CALL(bmg_rec_cycle(pc->conf, c, r, out, guard));
  if (z.off4) SESSILE_CALL(rec_vec(la, c, K_COPY, pc->n, out, z, none, -1, 0, guard));
  return SESSILE_OK;
}

static const la_pc_ops la_pc_bmg_ops = {"mg", SESSILE_PC_MG, 0, bmg_setup, bmg_rec, bmg_release};

sessile_status sessile_pc_mg_set_block(sessile_pc *pc, sessile_bmg *mg) {
  SESSILE_CHECK(pc && mg, SESSILE_ERR_USAGE, "pc mg: needs a pc and a block hierarchy");
  SESSILE_CHECK(pc->ops->type == SESSILE_PC_MG, SESSILE_ERR_USAGE,
                "pc %s: a block multigrid hierarchy is for pc mg only", pc->ops->name);
  SESSILE_CHECK(mg->la == pc->la, SESSILE_ERR_USAGE, "pc mg: the hierarchy belongs to another la");
  pc->ops->release(pc); /* whatever the other kind set up */
  pc->n = 0;
  pc->ops = &la_pc_bmg_ops;
  pc->conf = mg;
  return SESSILE_OK;
}
