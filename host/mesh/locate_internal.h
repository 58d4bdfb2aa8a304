/* Internal: the locator's fields (sessile/mesh/locate.h). */
#ifndef SESSILE_LOCATE_INTERNAL_H
#define SESSILE_LOCATE_INTERNAL_H
#include "sessile/mesh/locate.h"

struct sessile_locator {
  const sessile_tetmesh *m; /* not owned */
  double lo[3], inv_h[3];
  uint32_t dims[3], nbins, nentries, max_per_bin;
  uint32_t *cell_off; /* nbins + 1 */
  uint32_t *cell_tet; /* nentries, ascending tet index within a bin */
};

/* Barycentric weights of p in tet (x0, x1, x2, x3); mirrored by locate.comp. */
void locate_weights(const double *x0, const double *x1, const double *x2, const double *x3,
                    const double p[3], double w[4]);
#endif
