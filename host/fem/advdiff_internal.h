/* Private state of the SUPG advection-diffusion solver (sessile/fem/advdiff.h),
 * shared by advdiff.c (object, graph, solve) and advdiff_assemble.c. */
#ifndef SESSILE_ADVDIFF_INTERNAL_H
#define SESSILE_ADVDIFF_INTERNAL_H

#include "sessile/fem/advdiff.h"

struct sessile_advdiff {
  sessile_la *la;
  const sessile_tetmesh *mesh;
  sessile_csr a;     /* the graph (self + edge neighbours, sorted), values of the last solve */
  double *b;         /* nnodes: right-hand side of the homogenised system */
  double *f;         /* nnodes source, or NULL */
  double tau_scale;  /* 1: SUPG; 0: plain Galerkin */
  sessile_vec *vb, *vx;
  double t_assemble, t_upload, t_solve;
};

/* Assembles the SUPG system of -D lap c + u . grad c = f into ad->a (values)
 * and ad->b, then eliminates the Dirichlet nodes symmetrically with data g
 * (rows/columns identity, b_D = 0, b_f -= A_fD g_D). */
sessile_status sessile_advdiff_assemble_(sessile_advdiff *ad, const double *velocity, double D,
                                         const uint8_t *mask, const double *g);

#endif
