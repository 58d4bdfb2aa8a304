/* The cut-cell nutrient object's inside (nutrient_cut.c; the advected
 * solve, nutrient_cut_adv.c, shares it). */
#ifndef SESSILE_NUTRIENT_CUT_INTERNAL_H
#define SESSILE_NUTRIENT_CUT_INTERNAL_H

#include "fem_kernels.h"
#include "sessile/la/mg.h"
#include "sessile/la/pc.h"
#include "sessile/fem/nutrient_cut.h"

#define MAX_LEVELS 12

typedef struct {
  sessile_box box;
  sessile_buffer *solid, *theta, *mask;
  sessile_vec *diag;
} level;

/* The advected nutrient's extra objects, made on its first solve. */
typedef struct {
  sessile_vec *vel[MAX_LEVELS];  /* 3 per node, m/s (coarse levels: injected) */
  sessile_vec *coef[MAX_LEVELS]; /* 6 weights per node (cutcell_adv.comp) */
  double *host_vel;              /* the injection's scratch, all levels */
  sessile_kernel *k_cut;
  sessile_mat *a;                /* the finest advective operator */
  sessile_mg *mg;                /* the advective hierarchy (NULL with one level) */
  sessile_pc *pc;                /* pc "mg" on it */
} cut_adv;

struct sessile_cut_nutrient {
  sessile_la *la;
  sessile_cut_bc bc;
  int nlevels;
  level lv[MAX_LEVELS];
  sessile_vec *lift, *value, *ext;
  sessile_kernel *k_cut, *k_ghost, *k_bc;
  sessile_cmd *cmd;
  sessile_mat *a;  /* the finest operator (Jacobi-PCG, residuals) */
  sessile_mg *mg;  /* NULL with one level */
  cut_adv *adv;    /* NULL until the first advected solve */
};

cut_push nutrient_cut_push(const sessile_cut_nutrient *nt, const sessile_box *b, uint32_t flag);
uint32_t nutrient_cut_groups(const sessile_kernel *k, const sessile_box *b);
/* The multigrid's levels from the object's (coef: per level, or NULL). */
void nutrient_cut_mg_levels(const sessile_cut_nutrient *nt, sessile_vec *const *coef,
                            sessile_mg_level *ml);
/* Records the homogenised start (c = 0 on Dirichlet nodes) into nt->cmd,
 * which the caller began, ends it and submits. */
sessile_status nutrient_cut_start(sessile_cut_nutrient *nt, sessile_vec *c);
/* c = value on Dirichlet nodes (restore), then the extension across the surface. */
sessile_status nutrient_cut_finish(sessile_cut_nutrient *nt, const sessile_vec *c, int restore);
void nutrient_cut_adv_free(sessile_cut_nutrient *nt);

#endif
