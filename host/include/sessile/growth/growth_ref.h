/* sessile — plain-C references of the growth kernels (O'Hagan et al.
 * §4.4-4.5): the same algorithms as the kernels in shaders/growth/, in double, for the
 * tests to compare the GPU with.  docs/growth.md explains each one.
 *
 * Nothing here allocates except where a status is returned; arrays are owned
 * by the caller. */
#ifndef SESSILE_GROWTH_REF_H
#define SESSILE_GROWTH_REF_H

#include <stdint.h>
#include "sessile/mesh/box.h"
#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/grow_params.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most crossings one vertical line may have with the surface (the GPU kernel
 * keeps them in a fixed private array; more is an error, never silent). */
#define SESSILE_GROWTH_MAX_CROSSINGS 64

/* Fills p with the defaults documented in docs/growth.md (Table 1 where it
 * gives a value, ours otherwise). */
/* The `sessile grow` table's defaults (sessile/growth/grow_params.h), mapped. */
void sessile_growth_params_default(sessile_growth_params *p);
/* The kernels' parameters from a run's. */
void sessile_growth_params_from(const sessile_grow_params *p, sessile_growth_params *g);
/* Checks ranges (samples >= 2, t_give in [0,1], passes >= 0, ...). */
sessile_status sessile_growth_params_check(const sessile_growth_params *p);

/* --- solid classification ------------------------------------------------ */
/* Bins the triangles by the box columns (i,j) their xy-projection may cover:
 * the triangles of column c = i + n0 j are tri_of[off[c] .. off[c+1]).
 * Triangles with zero xy-area are left out.  The bins are conservative (a
 * triangle may be listed in a column its projection misses).  Caller frees
 * off and tri_of with free(). */
sessile_status sessile_growth_bin_columns(const sessile_box *box, const sessile_surface *s,
                                          uint32_t **off, uint32_t **tri_of);

/* The same for the lines along `axis` (0 x, 1 y, 2 z): lines are indexed by
 * the two other axes in cyclic order (u, v) = (axis+1, axis+2) mod 3, line
 * c = iu + n_u iv; triangles parallel to the lines are left out.
 * sessile_growth_bin_columns is axis 2. */
sessile_status sessile_growth_bin_lines(const sessile_box *box, const sessile_surface *s, int axis,
                                        uint32_t **off, uint32_t **tri_of);
/* The crossing coordinates along `axis` of the line through (u, v) = (x, y)
 * (axes as in sessile_growth_bin_lines), in list order; -1 past
 * SESSILE_GROWTH_MAX_CROSSINGS. */
int sessile_growth_line_crossings(const double *pos, const uint32_t *tri, const uint32_t *list,
                                  uint32_t count, int axis, double x, double y,
                                  double z[SESSILE_GROWTH_MAX_CROSSINGS]);

/* The crossing heights of the vertical line through (x, y) with the listed
 * triangles, by the watertight edge-function rule (docs/growth.md), in list
 * order.  Returns the count, or -1 when there are more than
 * SESSILE_GROWTH_MAX_CROSSINGS. */
int sessile_growth_column_crossings(const double *pos, const uint32_t *tri, const uint32_t *list,
                                    uint32_t count, double x, double y,
                                    double z[SESSILE_GROWTH_MAX_CROSSINGS]);

/* solid[node] = 1 inside the closed surface, else 0 (a node exactly on the
 * surface counts the crossing at its own height as below it).  Fails with
 * SESSILE_ERR_NUMERIC naming the column when a column has too many
 * crossings. */
sessile_status sessile_growth_ref_classify(const sessile_box *box, const sessile_surface *s,
                                           uint32_t *solid);
/* The cut cells of the surface on the box (docs/nutrient.md): solid as
 * above, and, when theta is not NULL, theta[6 n + 2 a + s] (a the axis, s = 0
 * towards the node at -h, 1 towards +h) = the distance in units of h from
 * node n to the nearest surface crossing before that neighbour, or 1 when
 * the surface does not cross that edge.  A node whose neighbour differs in
 * solidity has a crossing on their edge by the parity rule. */
sessile_status sessile_growth_ref_cut(const sessile_box *box, const sessile_surface *s,
                                      uint32_t *solid, double *theta);

/* --- per-vertex kernels ---------------------------------------------------- */
/* Eq 6: probed[v] = (1/S) sum_k w(d_k) c(x_v + d_k offset N_v), d_k = k/(S-1),
 * w(d) = 1/(20 d + 1), c the P1 interpolant of field on the box. */
void sessile_growth_ref_probe(const sessile_box *box, const double *pos, const double *normals,
                              uint32_t nv, const double *field, double offset, uint32_t samples,
                              double *probed);

/* The flux probe: max(0, (4 c(x + d N) - c(x + 2 d N)) / (2 d) / flux_ref),
 * c the P1 interpolant of field (the extended cut-cell solution). */
void sessile_growth_ref_probe_flux(const sessile_box *box, const double *pos, const double *normals,
                                   uint32_t nv, const double *field, double delta, double flux_ref,
                                   double *probed);

/* Translocation (eqs 7-8).  The paper gives at each vertex and then at each
 * of its neighbours, so in one sweep a vertex of degree N gives 1 + N times.
 * The order-independent sweep is SESSILE_TRANSLOCATE_SWEEP simultaneous
 * passes (1 + 6, a regular vertex: every vertex gives in every pass, so
 * uniform fields stay uniform and the sum is conserved):
 *   out[x] = clamp(c[x] - N_x T c[x] + T sum_{x' in nbr(x)} c[x'], 0, cmax).
 * _pass does one pass; _sweep all of them (out may equal c). */
#define SESSILE_TRANSLOCATE_SWEEP 7
void sessile_growth_ref_translocate_pass(const uint32_t *nbr_off, const uint32_t *nbr, uint32_t nv,
                                         double t_give, double cmax, const double *c, double *out);
sessile_status sessile_growth_ref_translocate_sweep(const uint32_t *nbr_off, const uint32_t *nbr,
                                                    uint32_t nv, double t_give, double cmax,
                                                    const double *c, double *out);
/* The paper's literal sweep, in place and order-dependent: for x = 0..nv-1,
 * give(x), then give(x') for each neighbour x' of x, where give(y) adds
 * T c[y] to each neighbour of y (clamped to [0, cmax]) and sets
 * c[y] = clamp(c[y] - N_y T c[y]), c[y] read when the give starts. */
void sessile_growth_ref_translocate_sequential(const uint32_t *nbr_off, const uint32_t *nbr,
                                               uint32_t nv, double t_give, double cmax, double *c);

/* Translocation's upper clamp: 1 for the paper's concentrations, none
 * (1e30) for the flux probe's C, which is not bounded by 1. */
double sessile_growth_translocate_cmax(const sessile_growth_params *p);

/* Eq 10 (Chindapol): clamp(Gr Lmax C^n / (K + C^n), 0, maxgrowth); C <= 0 gives 0. */
double sessile_growth_chindapol(const sessile_growth_params *p, double c);

/* The counter-based random numbers of the Halichondrid directions (eqs 1-2):
 * a uint32 hash of (seed, iteration, vertex, component), the same in GLSL
 * (shaders/growth/growth_common.glsl), and its uniform in [0, 1) with 24 bits
 * (exact in float and double). */
uint32_t sessile_growth_hash(uint64_t seed, uint32_t iteration, uint32_t vertex, uint32_t component);
double sessile_growth_uniform(uint64_t seed, uint32_t iteration, uint32_t vertex, uint32_t component);

/* Eq 9 with the thresholds: a vertex moves by g(C) along dir (N, or
 * normalize(N + r) for Halichondrid) when C > nutrient_threshold and g >
 * growth_threshold, then is clamped into the box.  length[v] = the distance
 * moved before clamping (0 for a vertex that does not grow); dir (3 nv, may be
 * NULL) = the growth direction. */
void sessile_growth_ref_grow(const sessile_box *box, const double *pos, const double *normals,
                             uint32_t nv, const double *c_tr, const sessile_growth_params *p,
                             uint64_t seed, uint32_t iteration, double *new_pos, double *length,
                             double *dir);

/* The whole step as sessile_growth_gpu_step computes it (normals, probe,
 * translocate passes in the parallel form, grow).  probed, translocated,
 * length may be NULL. */
sessile_status sessile_growth_ref_step(const sessile_box *box, const sessile_surface *s,
                                       const double *field, const sessile_growth_params *p,
                                       uint64_t seed, uint32_t iteration, double *new_pos,
                                       double *probed, double *translocated, double *length);

#ifdef __cplusplus
}
#endif
#endif
