/* The parsed SDS process model (docs/sds_rules.md).  Fixed-size tables: the
 * struct never moves once allocated, so muparser handles can bind their
 * variables to the slots below for the model's lifetime. */
#ifndef SESSILE_SDS_RULES_INTERNAL_H
#define SESSILE_SDS_RULES_INTERNAL_H
#include "sessile/expr.h"
#include "sessile/sds/sds_process.h"

enum {
  SDS_MAX_MORPH = 16,
  SDS_MAX_STATE = 32,
  SDS_MAX_CONST = 64,
  SDS_MAX_PARAMS = 64,
  SDS_MAX_TIPS = 64,
  SDS_MAX_RULES = 128,
  SDS_MAX_ACTIONS = 8,
  /* slots: radius, volume, time, then morphogens, then state variables */
  SDS_SLOT_RADIUS = 0,
  SDS_SLOT_VOLUME = 1,
  SDS_SLOT_TIME = 2,
  SDS_SLOT_SURFACE = 3,
  SDS_SLOT_MORPH = 4,
  SDS_SLOT_STATE = SDS_SLOT_MORPH + SDS_MAX_MORPH,
  SDS_SLOTS = SDS_SLOT_STATE + SDS_MAX_STATE
};

typedef sessile_expr sds_expr; /* a constant, or a compiled muparser handle */

typedef struct sds_action {
  int kind, target, sign; /* sign: +1 toward grad, -1 away (divide) */
  sds_expr value;
  char *text; /* the value's text, kept for the bytecode compiler until load ends */
} sds_action;

typedef struct sds_rule {
  char name[SESSILE_SDS_NAME];
  int line;
  sds_expr cond;
  char *text; /* the condition's text, as the action's */
  int nact;
  sds_action act[SDS_MAX_ACTIONS];
} sds_rule;

struct sessile_sds_model {
  char file[256];
  int nmorph, nstate, nconst, nparams, ntips, nrules;
  char mname[SDS_MAX_MORPH][SESSILE_SDS_NAME];
  double diffusion[SDS_MAX_MORPH], decay[SDS_MAX_MORPH], mstart[SDS_MAX_MORPH];
  int capped[SDS_MAX_MORPH], timer[SDS_MAX_MORPH];
  int axis; /* 1 + the morphogen declared axis=1 (its gradient the tissue's axis), 0 none */
  char sname[SDS_MAX_STATE][SESSILE_SDS_NAME];
  double sstart[SDS_MAX_STATE];
  char cname[SDS_MAX_CONST][SESSILE_SDS_NAME];
  double cval[SDS_MAX_CONST];
  sessile_sds_param params[SDS_MAX_PARAMS];
  double tips[SDS_MAX_TIPS][3];
  sds_rule rules[SDS_MAX_RULES];
  double slot[SDS_SLOTS];
  struct sds_prog *prog; /* the rules as bytecode (rules_vm.h); NULL when they do not compile */
  char prog_why[320];    /* why prog is NULL */
};

#endif
