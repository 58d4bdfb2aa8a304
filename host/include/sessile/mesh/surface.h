/* sessile — the sponge's triangle surface: a closed, consistently oriented
 * 2-manifold (genus 0 as it starts), its adjacency, normals, invariants and
 * the remesher (vertex insertion, fusion, small-triangle deletion; O'Hagan et
 * al. §4.6).  Plain C on the host: topology changes are the host's job.
 *
 * Triangles are counter-clockwise seen from outside, so face normals point
 * out.  Ownership: a sessile_surface owns its arrays; sessile_surface_free
 * releases them (a zeroed struct is valid and empty). */
#ifndef SESSILE_SURFACE_H
#define SESSILE_SURFACE_H

#include <stdint.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_surface {
  uint32_t nv, nf;       /* vertices, triangles */
  uint32_t cap_v, cap_f; /* allocated capacity */
  double *pos;           /* 3 nv */
  uint32_t *tri;         /* 3 nf, counter-clockwise from outside */
} sessile_surface;

void sessile_surface_free(sessile_surface *s);
/* Makes room for nv vertices and nf triangles (keeps contents). */
sessile_status sessile_surface_reserve(sessile_surface *s, uint32_t nv, uint32_t nf);
/* Deep copy (dst is freed first); on failure dst is left empty. */
sessile_status sessile_surface_copy(const sessile_surface *src, sessile_surface *dst);

/* Icosphere: level 1 is the icosahedron (12 vertices, 20 triangles); each
 * further level splits every triangle into 4 and projects onto the sphere:
 * level L has 10*4^(L-1)+2 vertices and 20*4^(L-1) triangles (level 4: 642
 * vertices, 1280 triangles; docs/model.md reconciles Table 1's "642"). */
sessile_status sessile_surface_icosphere(int level, double radius, const double center[3],
                                         sessile_surface *out);

/* Vertex adjacency as CSR: the neighbours of v are nbr[off[v] .. off[v+1]),
 * sorted ascending (so results do not depend on triangle order).  Caller
 * frees off and nbr with free(). */
sessile_status sessile_surface_vertex_neighbours(const sessile_surface *s, uint32_t **off,
                                                 uint32_t **nbr);
/* Vertex -> incident triangles as CSR (ascending triangle index). */
sessile_status sessile_surface_vertex_faces(const sessile_surface *s, uint32_t **off,
                                            uint32_t **faces);

/* Area-weighted vertex normals (sum of the incident faces' cross products,
 * normalised; the reference for the GPU kernel).  n has 3 nv doubles. */
void sessile_surface_normals(const sessile_surface *s, double *n);

/* Mesh statistics for the manifest. */
typedef struct sessile_surface_stats {
  uint32_t nv, nf, ne;
  double area, volume;          /* cm^2, cm^3 (volume by the divergence theorem) */
  double edge_min, edge_mean, edge_max;
  double tri_area_min;
  double bbox_min[3], bbox_max[3];
} sessile_surface_stats;
void sessile_surface_stats_of(const sessile_surface *s, sessile_surface_stats *st);

/* Checks the invariants: indices in range, every edge in exactly two
 * triangles with opposite directions (closed, consistently oriented
 * 2-manifold), Euler characteristic V - E + F == euler, no triangle with
 * area <= min_area, no duplicate triangles, no unreferenced vertices.
 * Returns SESSILE_OK, or SESSILE_ERR_INTERNAL with a message naming the first
 * violation. */
sessile_status sessile_surface_check(const sessile_surface *s, int euler, double min_area);

/* A point on the curve through p0 and p1 that the vertex normals n0, n1 (unit)
 * define: the midpoint of the cubic Bezier whose end tangents are the chord
 * projected onto each end's tangent plane (the PN-triangle edge curve),
 * (p0 + p1) / 2 + (t0 - t1) / 8 with ti = d - (d.ni) ni, d = p1 - p0.  On a
 * sphere of radius R it lies within about 0.375 R phi^4 of the sphere for an
 * edge of half-angle phi (the chord midpoint: R phi^2 / 2). */
void sessile_surface_curve_midpoint(const double p0[3], const double n0[3], const double p1[3],
                                    const double n1[3], double out[3]);

/* --- remeshing (§4.6) ------------------------------------------------------ */
typedef struct sessile_remesh_options {
  double insert_len; /* split edges longer than this (Table 1: 0.6) */
  double fuse_len;   /* fuse vertices of edges shorter than this (Table 1: 0.5) */
  double min_area;   /* collapse triangles with a smaller area (Table 1: 0.1) */
  int max_passes;    /* safety bound on split sweeps (default 8: each sweep halves the
                        longest edges; collapse sweeps always run to a fixed point) */
  double max_turn_deg; /* a collapse may turn no remaining triangle's normal by more
                          than this (default 60 degrees) */
  /* The growth box: inserted and merged vertices are clamped into
   * [clamp_lo, clamp_hi] (default: unbounded), and a vertex lying on a box
   * face keeps its position when an edge to a vertex off the faces is fused. */
  double clamp_lo[3], clamp_hi[3];
  /* Contact inhibition (docs/intersection.md; default 1): no split or
   * collapse makes the surface cross itself.  An inserted vertex whose curve
   * point would cross goes to the edge's midpoint (on the edge: that cannot
   * cross); a collapse whose new triangles would cross is refused. */
  int guard_intersections;
} sessile_remesh_options;
void sessile_remesh_options_default(sessile_remesh_options *o);

typedef struct sessile_remesh_stats {
  /* rejected: candidates (short edges + small triangles) left at the end
   * because a guard refused every collapse of them */
  uint32_t splits, fusions, area_collapses, rejected;
  /* contact_refusals: collapses refused because their new triangles would
   * cross the surface (attempts: a candidate refused in two sweeps counts
   * twice); chord_splits: inserted vertices put on the edge's midpoint
   * instead of the curve point, which would have crossed */
  uint32_t contact_refusals, chord_splits;
} sessile_remesh_stats;

/* Remeshes in place.  normals: the current vertex normals (3 nv), used to
 * place inserted vertices on a curve through both ends (not the straight
 * midpoint); NULL computes them.  The surface stays a closed, consistently
 * oriented 2-manifold; the reading of the thresholds that cannot oscillate is
 * in docs/remesh.md.  Splits run first until no edge exceeds insert_len; then
 * collapses (short edges, small triangles) each guarded so that no edge
 * exceeds insert_len, the link condition holds, no normal turns more than
 * max_turn_deg, no triangle degenerates and (guard_intersections) no new
 * triangle crosses the surface.  Deterministic; the result is a
 * fixed point (remeshing it again changes nothing); vertex and triangle
 * arrays are compacted keeping their relative order.  Fails with
 * SESSILE_ERR_NUMERIC on non-finite positions or when max_passes split
 * sweeps leave an edge too long. */
sessile_status sessile_remesh(sessile_surface *s, const double *normals,
                              const sessile_remesh_options *o, sessile_remesh_stats *st);

#ifdef __cplusplus
}
#endif
#endif
