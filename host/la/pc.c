/* Preconditioner objects: the registry (a constant table, indexed by
 * sessile_pc_type, looked up by name), creation, setup, a stand-alone
 * application and destruction.  The implementations are pc_*.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pc_internal.h"

/* Indexed by sessile_pc_type; a new pc adds its enum value and one line. */
static const la_pc_ops *const registry[] = {
    [SESSILE_PC_NONE] = &la_pc_none_ops,
    [SESSILE_PC_JACOBI] = &la_pc_jacobi_ops,
    [SESSILE_PC_ILU0] = &la_pc_ilu_ops,
    [SESSILE_PC_BLOCK_JACOBI] = &la_pc_bjacobi_ops,
    [SESSILE_PC_MG] = &la_pc_mg_ops,
};
enum { NREG = (int)(sizeof registry / sizeof registry[0]) };

const la_pc_ops *la_pc_ops_of(sessile_pc_type t) {
  return (int)t >= 0 && (int)t < NREG ? registry[t] : NULL;
}

const char *sessile_pc_type_name(sessile_pc_type t) {
  const la_pc_ops *o = la_pc_ops_of(t);
  return o ? o->name : "?";
}

const char *sessile_pc_registered(int i) { return i >= 0 && i < NREG ? registry[i]->name : NULL; }

sessile_status sessile_pc_type_from_name(const char *name, sessile_pc_type *out) {
  for (int i = 0; name && i < NREG; i++)
    if (!strcmp(name, registry[i]->name)) {
      *out = registry[i]->type;
      return SESSILE_OK;
    }
  char known[128] = "";
  for (int i = 0; i < NREG; i++) {
    size_t len = strlen(known);
    snprintf(known + len, sizeof known - len, "%s%s", i ? ", " : "", registry[i]->name);
  }
  return sessile_error_set(SESSILE_ERR_USAGE, "unknown preconditioner '%s' (registered: %s)",
                           name ? name : "(null)", known);
}

sessile_status sessile_pc_create_type(sessile_la *la, sessile_pc_type type, sessile_pc **out) {
  *out = NULL;
  const la_pc_ops *ops = la_pc_ops_of(type);
  SESSILE_CHECK(ops, SESSILE_ERR_USAGE, "unknown preconditioner type %d", (int)type);
  SESSILE_CHECK(la, SESSILE_ERR_USAGE, "a preconditioner needs an la context");
  sessile_pc *pc = calloc(1, sizeof *pc);
  SESSILE_CHECK(pc, SESSILE_ERR_NO_MEMORY, "out of host memory");
  pc->la = la;
  pc->ops = ops;
  *out = pc;
  return SESSILE_OK;
}

sessile_status sessile_pc_create(sessile_la *la, const char *type, sessile_pc **out) {
  *out = NULL;
  sessile_pc_type t;
  SESSILE_CALL(sessile_pc_type_from_name(type, &t));
  return sessile_pc_create_type(la, t, out);
}

static void release(sessile_pc *pc) {
  pc->ops->release(pc);
  pc->n = 0;
  pc->diag = NULL;
}

sessile_status sessile_pc_setup(sessile_pc *pc, const sessile_mat *a) {
  SESSILE_CHECK(pc && a, SESSILE_ERR_USAGE, "pc setup needs a pc and a matrix");
  SESSILE_CHECK(a->la == pc->la, SESSILE_ERR_USAGE, "pc %s: the matrix belongs to another la",
                pc->ops->name);
  release(pc);
  sessile_status s = pc->ops->setup(pc, a);
  if (s != SESSILE_OK) {
    release(pc);
    return s;
  }
  pc->n = a->nrows;
  return SESSILE_OK;
}

sessile_status sessile_pc_apply(sessile_pc *pc, const sessile_vec *x, sessile_vec *y) {
  SESSILE_CHECK(pc && x && y, SESSILE_ERR_USAGE, "pc apply needs a pc, x and y");
  SESSILE_CHECK(pc->n, SESSILE_ERR_USAGE, "pc %s is not set up (sessile_pc_setup)", pc->ops->name);
  SESSILE_CHECK(x->n == pc->n && y->n == pc->n && x != y && x->la == pc->la && y->la == pc->la,
                SESSILE_ERR_USAGE,
                "pc %s apply: set up for %u rows, x has %u and y %u entries (distinct, same la)",
                pc->ops->name, pc->n, x->n, y->n);
  sessile_la *la = pc->la;
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(rec_pc(pc, la->cmd, vref_of(x), vref_of(y), -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

void sessile_pc_destroy(sessile_pc *pc) {
  if (!pc) return;
  release(pc);
  free(pc);
}

const char *sessile_pc_name(const sessile_pc *pc) { return pc->ops->name; }
sessile_pc_type sessile_pc_get_type(const sessile_pc *pc) { return pc->ops->type; }
int sessile_pc_symmetric(const sessile_pc *pc) { return pc->ops->symmetric; }
