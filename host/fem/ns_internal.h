/* Internal to the Navier-Stokes solver (host/fem/ns_*.c). */
#ifndef SESSILE_NS_INTERNAL_H
#define SESSILE_NS_INTERNAL_H

#include <stdint.h>

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

#endif
