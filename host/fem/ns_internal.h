/* Internal to the Navier-Stokes solver (host/fem/ns_*.c). */
#ifndef SESSILE_NS_INTERNAL_H
#define SESSILE_NS_INTERNAL_H

#include <stdint.h>
#include "sessile/fem/fluid.h"
#include "sessile/la/pc.h"

/* Coefficients of one assembly: newton = 1 for the full Jacobian, 0 for the
 * Picard (Oseen) linearisation. */
typedef struct ns_coef {
  double rho, eta;
  int lsic;
  double newton;
} ns_coef;

/* One tetrahedron: X the 4 vertices (metres), U the 16 unknowns (4 per
 * vertex: ux uy uz p), F the body force at the 4 quadrature points (or
 * NULL).  Writes the element residual Re[16] and, when Ke is not NULL, its
 * Jacobian Ke[16*16] (row-major, row = test dof, col = unknown). */
void ns_element(const double X[4][3], const double U[16], const double F[4][3], const ns_coef *c,
                double Re[16], double *Ke);

/* The 4-point quadrature rule of degree 2 on a tet: barycentric weights of
 * point q are NS_QA at vertex q and NS_QB at the other three. */
#define NS_QA 0.5854101966249685
#define NS_QB 0.1381966011250105

#define NS_MG_LEVELS 15
/* The largest chunk of tets a thread assembles in a row (ns_colour.c). */
#define NS_CHUNK 2048u

/* The solver object (sessile/fem/fluid.h). */
struct sessile_fluid {
  sessile_la *la;
  uint32_t nnodes, ntets;
  double *x;          /* 3 nnodes, metres */
  uint32_t *tet;      /* 4 ntets */
  uint32_t *tags;     /* nnodes */
  sessile_bcsr4 a;    /* the pattern (node graph), values rewritten each assembly */
  sessile_mat *dev;   /* a on the device, kept across solves (refilled: no new buffers) */
  uint32_t *pos;      /* 16 ntets: block index of (a, b) of each tet */
  uint32_t chunk;     /* consecutive tets a thread assembles in a row (ns_colour.c) */
  uint32_t ncolours;  /* of the chunks */
  uint32_t *corder;   /* the chunks sorted by colour */
  uint32_t *cstart;   /* ncolours + 1: colour c's chunks are corder[cstart[c] .. cstart[c+1]) */
  uint32_t grid[3];   /* the mesh is a Kuhn box of these nodes per axis (ns_box.c); 0: not */
  sessile_bmg *bmg;   /* pc mg: the block hierarchy, kept across solves (created on first use) */
  sessile_bmg_options bmg_opt; /* the options it was made with */
  sessile_pc *mgpc;   /* the pc "mg" on it, kept likewise */
  struct sessile_fluid *coarse[NS_MG_LEVELS]; /* its coarse levels 1.. as fluids (ns_mg.c) */
  struct sessile_fluid *nest; /* the box of twice the spacing for the nested start (ns_nested.c) */
  int ncoarse;
};

/* Pieces of the solver, one file each (ns_fluid.c has the overview). */
sessile_status ns_build_graph(sessile_fluid *fl);   /* fl->a's pattern and fl->pos */
sessile_status ns_build_colours(sessile_fluid *fl); /* fl->chunk, ncolours, corder, cstart */
/* Puts fl->tet in Morton order of the tets' centroids (a mesh that is not a box). */
sessile_status ns_order_tets(sessile_fluid *fl);
/* fl->grid: the box's nodes per axis when the mesh is a structured Kuhn box
 * in box order (sessile_tetmesh_from_box), else zeros. */
void ns_detect_box(sessile_fluid *fl);
/* Residual r (4 per node) and, when jac, the Jacobian into fl->a.val. */
void ns_assemble(sessile_fluid *fl, const sessile_fluid_params *p, const double *up, double newton,
                 int jac, double *r);
/* Dirichlet flags per node: bit 0 velocity, bit 1 pressure. */
uint8_t ns_node_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                   uint32_t i);
/* Writes the Dirichlet values into up. */
void ns_impose_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                  const uint8_t *bc, double *up);
/* Zeroes the residual's Dirichlet rows and, when jac, makes them identity
 * rows; returns ||r|| of the rest. */
double ns_apply_bc_rows(sessile_fluid *fl, const uint8_t *bc, int jac, double *r);
/* du = J⁻¹(-r) for the assembled fl->a on the GPU; fills st's linear fields.
 * solid, up and newton: the state J was assembled at (pc mg rediscretises it). */
sessile_status ns_linear_solve(sessile_fluid *fl, const sessile_fluid_params *p, const uint8_t *solid,
                               const double *up, double newton, const double *r, double *du,
                               sessile_vec *b, sessile_vec *x, sessile_fluid_step *st);
/* pc mg: the coarse levels' operators rediscretised at the injected state
 * (given to fl->bmg), and the coarse fluids' release (ns_mg.c). */
sessile_status ns_mg_operators(sessile_fluid *fl, const sessile_fluid_params *p, const uint8_t *solid,
                               const double *up, double newton);
void ns_mg_free(sessile_fluid *fl);
/* The nested start (params.nested, ns_nested.c): may replace up (its
 * boundary values imposed, bc the nodes' flags) by the interpolated solution
 * on the box of twice the spacing; r is scratch (4 per node).  r_up >= 0:
 * ||R(up)||, already known (a start from rest), else it is assembled. */
sessile_status ns_nested_start(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                               const uint8_t *bc, double *up, double r_up, double *r, sessile_fluid_result *res);
/* One line to the caller's monitor (nothing when it is NULL). */
void ns_monitor(const sessile_fluid_params *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
