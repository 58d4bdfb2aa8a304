/* Shared inside the venation generator (host/coral/venation*.c). */
#ifndef SESSILE_VENATION_INTERNAL_H
#define SESSILE_VENATION_INTERNAL_H
#include "sessile/mesh/skeleton.h"
#include "sessile/coral/venation.h"

/* The blade's extent at relative height z in [0, 1] for unit width: the
 * left and right Bezier curves' x there (xl > xr: no blade at that height). */
void venation_blade_span(const sessile_venation_params *p, double z, double *xl, double *xr);
/* A point drawn uniformly in the blade (planar) or box of width w: rejection
 * from the bounding box, at most 64 tries; 0 when none hit (rng consumed). */
int venation_blade_sample(const sessile_venation_params *p, double w, uint64_t *rng, double q[3]);
/* Nodes of grid g within distance r of q (ascending index), into a growing list. */
sessile_status venation_grid_within(const sessile_venation_grid *g, const double *nodes, const double *q,
                                    double r, uint32_t **list, uint32_t *n, uint32_t *cap);
#endif
