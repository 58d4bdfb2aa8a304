/* sessile — SDS topology on the host (Porter & McCormack §3.1): the validity
 * check of a tetrahedral complex, cell division (§3.1.1), the inversion time
 * of a tetrahedron under linear motion and the two movement transformations
 * (§3.1.2, Figures 3-5).  Plain arrays, no organism struct: the caller keeps
 * its per-cell and per-tet data and remaps them with the maps returned here.
 *
 * Conventions: positions x (3 per vertex), tets (4 per tet) positively
 * oriented, det[x1-x0, x2-x0, x3-x0] > 0.  Every editing operation rebuilds
 * the tet array as: the kept tets in their old order, then the new ones; and
 * returns tet_from[i] = the old index of tet i, or SESSILE_SDS_TOPO_NEW_TET for a
 * tet the operation created (its rest size must be computed afresh; the kept
 * tets keep their spring multipliers).  Adjacency is found by a scan of the
 * tets (O(nt) per operation: divisions and inversions are rare events).
 * docs/sds_topology.md has the algorithms and the decisions. */
#ifndef SESSILE_SDS_TOPO_H
#define SESSILE_SDS_TOPO_H

#include <stdint.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SESSILE_SDS_TOPO_NEW_TET UINT32_MAX

/* A growable complex: the operations may realloc x and tet (they own nothing
 * else).  A zeroed struct is valid and empty; sessile_sds_topo_complex_free
 * releases the arrays. */
typedef struct sessile_sds_topo_complex {
  uint32_t nv, nt;
  double *x;     /* 3 nv */
  uint32_t *tet; /* 4 nt */
} sessile_sds_topo_complex;
void sessile_sds_topo_complex_free(sessile_sds_topo_complex *c);

/* Signed volume (1/6 det[x1-x0, x2-x0, x3-x0]) of four points. */
double sessile_sds_topo_volume(const double *x0, const double *x1, const double *x2, const double *x3);

/* --- 1. validity ----------------------------------------------------------- */
typedef struct sessile_sds_topo_report {
  double volume;     /* sum of the tets' signed volumes */
  double min_volume; /* smallest tet volume */
  uint32_t min_tet;  /* its index */
  uint32_t n_interior_faces, n_boundary_faces;
  int boundary_euler; /* V - E + F of the boundary surface */
} sessile_sds_topo_report;

/* Checks: indices in range; every tet volume > min_volume; every face in one
 * or two tets, and in two with opposite orientations (the tets lie on both
 * sides); the boundary (faces in one tet, oriented outward) a closed,
 * consistently oriented 2-manifold, edge- and vertex-manifold (the boundary
 * faces around each boundary vertex form one fan); no duplicate tets; every
 * vertex in some tet.  report may be NULL.  Returns SESSILE_OK or
 * SESSILE_ERR_INTERNAL with a message naming the first violation. */
/* The check of a transformation's result cx, made from the complex (x0,
 * tet0 of nt0 tets) with tet_from[t] the origin of each tet of cx
 * (SESSILE_SDS_TOPO_NEW_TET: new): as sessile_sds_topo_check, but a tet
 * inverted both now and in its origin passes (a sliver elsewhere, left as
 * it was: the repair's business, not the transformation's fault); any other
 * tet of volume <= 0 fails.  SESSILE_OK or SESSILE_ERR_INTERNAL naming it. */
sessile_status sessile_sds_topo_check_kept(const double *x0, uint32_t nt0, const uint32_t *tet0,
                                           const sessile_sds_topo_complex *cx, const uint32_t *tet_from);
sessile_status sessile_sds_topo_check(uint32_t nv, const double *x, uint32_t nt, const uint32_t *tet, double min_volume,
                                      sessile_sds_topo_report *report);

/* --- 2. division (§3.1.1) -------------------------------------------------- */
typedef struct sessile_sds_topo_division {
  uint32_t a, b; /* daughters: a = the mother's index, b = the appended vertex */
  int surface;   /* the mother was on the boundary */
  int tangential; /* surface and split along the boundary: both daughters on it */
  double eps;    /* the offset used (a = c + eps d, b = c - eps d inside) */
  uint32_t n_removed, n_added;
  int fallback;       /* TetGen needed a Steiner point: the hull coned from a, b split in */
  uint32_t *tet_from; /* nt (new) entries, malloc'd: old index or SESSILE_SDS_TOPO_NEW_TET */
} sessile_sds_topo_division;

/* Divides cell c in direction d (need not be unit; must be non-zero).
 * Interior cell: the star T_c is removed and its closed hull F kept;
 * a = c + eps d, b = c - eps d with eps = min(eps_max, frac * the distance
 * from c to F along +d and -d) (frac = 0.5: strictly inside a star-shaped
 * hull); F ∪ {a, b} is tetrahedralised by TetGen keeping F's faces (-pY).
 * Surface cell, d within 45° of the tangent plane: a tangential split
 * (div->tangential): a = c + eps t + h n, b = c - eps t + h n with t the
 * unit projection of d on the tangent plane, n c's boundary normal, eps =
 * min(eps_max, 0.25 × the mean distance from c to its boundary ring) and h
 * such that the enclosed volume is unchanged; c's boundary fan is split
 * into two fans joined by the edge (a, b) (a vertex split, the wings chosen
 * for the best-shaped outward faces) and the open hull closed by it meshed by
 * TetGen; both daughters are on the boundary, which gains one vertex and two
 * faces.  When that fails (no outward fan, TetGen refuses), and for d nearer
 * the normal: the hull of T_c is closed by c's own boundary faces, which
 * are kept; daughter a stays at c on the boundary and b goes inside along
 * whichever of ±d enters the body (the inward normal when d is tangent), at
 * frac of the distance to the hull; the boundary is unchanged.  eps_max <= 0
 * means no cap.  The total volume is unchanged.  The daughters are neighbours
 * (share an edge): when TetGen's mesh keeps them apart, eps is halved and the
 * hull meshed again (up to 3 times).  When TetGen cannot mesh the hull
 * without a Steiner point, the hull is coned from a (an interior pair pulled
 * toward c until a sees every hull face) and the cone tet holding b split in
 * four (div->fallback = 1); SESSILE_ERR_NUMERIC (the complex untouched) only
 * if that fails too.  On success div->tet_from must be freed by the caller. */
sessile_status sessile_sds_topo_divide(sessile_sds_topo_complex *cx, uint32_t c, const double d[3], double eps_max,
                                       sessile_sds_topo_division *div);

/* --- 3. inversion time ----------------------------------------------------- */
/* Smallest s in [0, 1] with p(s) = c[0] + c[1] s + c[2] s^2 + c[3] s^3 = 0
 * where p changes sign or vanishes (any of the coefficients may be zero):
 * the interval is split at the real critical points and each monotone piece
 * with a sign change is bisected to the last bit.  Returns 1 and *s, or 0. */
int sessile_sds_topo_cubic_root(const double c[4], double *s);

typedef enum sessile_sds_topo_case {
  SESSILE_SDS_TOPO_NONE = 0,
  SESSILE_SDS_TOPO_VERTEX_FACE = 1, /* case 1: a vertex through the opposite face */
  SESSILE_SDS_TOPO_EDGE_EDGE = 2    /* case 2: two opposite edges cross */
} sessile_sds_topo_case;

typedef struct sessile_sds_topo_inversion {
  sessile_sds_topo_case kind;
  double u;       /* the inversion time in [u1, u2] */
  double s;       /* the same in the normalised parameter (u - u1) / (u2 - u1) */
  int vertex;     /* case 1: local index 0..3 of the vertex v (the face is the other three) */
  int edge[2][2]; /* case 2: local indices of e_u = edge[0] and e_l = edge[1] */
} sessile_sds_topo_inversion;

/* The first time in [u1, u2] at which the tet p (4 points at u1, 12 doubles)
 * moving linearly to q (at u2) has zero volume, and its case (Figure 3) from
 * the flat configuration at that time: case 1 when one vertex lies in the
 * triangle of the other three, else case 2 with the crossing pair of
 * opposite edges.  Returns 1 with *inv filled, or 0 when the volume keeps its
 * sign on [u1, u2]. */
int sessile_sds_topo_inversion_time(const double p[12], const double q[12], double u1, double u2,
                                    sessile_sds_topo_inversion *inv);

/* --- 4., 5. movement transformations (§3.1.2) ------------------------------ */
typedef struct sessile_sds_topo_transform {
  uint32_t n_removed, n_added;
  uint32_t *tet_from; /* as in sessile_sds_topo_division */
} sessile_sds_topo_transform;

/* Case 1 (Figure 4) at the inversion time: vertex v of tet t passes through
 * the opposite face f.  With t' the tet across f (apex v'), t and t' are
 * replaced by the three tets (v, v', each edge of f) (the 2-3 flip).  When f
 * is a boundary face (no t'), t is removed and nothing added: the boundary
 * passes under v (f leaves it, t's three faces around v join it).  Refused
 * with SESSILE_ERR_UNSUPPORTED when v and f are both on the boundary (the
 * paper's "infinitely thin section"), or when the flip would not be valid
 * (a new tet with volume <= 0, or the edge (v, v') already in another tet);
 * the complex is untouched then. */
sessile_status sessile_sds_topo_case1(sessile_sds_topo_complex *cx, uint32_t t, uint32_t v,
                                      sessile_sds_topo_transform *tr);

/* Case 2 (Figure 5) at the inversion time: the edges e_u = (eu0, eu1) and
 * e_l = (el0, el1) cross.  U ∪ L (the tets around either edge) is removed and
 * the hull re-tetrahedralised by TetGen keeping its faces (-pY, no Steiner
 * point).  A boundary edge that lies in the flat tet only (two of its faces
 * on the boundary) is flipped by removing that tet, nothing added (as case 1
 * on the boundary).  Another boundary edge is first covered by the tet
 * spanned by it and the two boundary faces through it, outside the body (the
 * boundary flips that edge; the volume grows by that tet's): possible where
 * the boundary is concave at the edge (a valley, what a boundary edge moving
 * into the body makes), refused with SESSILE_ERR_UNSUPPORTED at a ridge,
 * where that tet would overlap the body.  SESSILE_ERR_NUMERIC when TetGen
 * needs a Steiner point; the complex is untouched on every failure. */
sessile_status sessile_sds_topo_case2(sessile_sds_topo_complex *cx, uint32_t eu0, uint32_t eu1, uint32_t el0,
                                      uint32_t el1, sessile_sds_topo_transform *tr);

/* The transformation of inv's case (from sessile_sds_topo_inversion_time on tet
 * t, its local indices) applied to tet t: case 1 or case 2 above. */
sessile_status sessile_sds_topo_apply_inversion(sessile_sds_topo_complex *cx, uint32_t t,
                                                const sessile_sds_topo_inversion *inv, sessile_sds_topo_transform *tr);

/* --- 6. repair ------------------------------------------------------------- */
/* Re-tetrahedralises around the tets bad[0..nbad) (inverted ones no
 * transformation removed): every tet through one of their cells is removed
 * and the cavity's hull meshed by TetGen with the cells inside it as points
 * (-pY, no Steiner point, the hull's faces kept); when TetGen cannot mesh it
 * the cavity grows by a ring of cells (up to 3 rings).  The boundary and the
 * cells are unchanged; only the tets in the cavity change.  The caller checks
 * the result (sessile_sds_topo_check): a cavity whose hull is itself tangled
 * can mesh and still overlap.  SESSILE_ERR_NUMERIC, the complex untouched,
 * when no cavity meshes. */
sessile_status sessile_sds_topo_repair(sessile_sds_topo_complex *cx, const uint32_t *bad, uint32_t nbad,
                                       sessile_sds_topo_transform *tr);

#ifdef __cplusplus
}
#endif
#endif
