/* sessile — SDS, the Simplicial Developmental System (Porter & McCormack):
 * the organism (a tetrahedral complex whose vertices are the cells) and its
 * physics (scale-free edge and volume springs, damping, gravity, a box,
 * obstacles, attraction points), on the host (the reference) and on the GPU
 * (gather kernels, shaders/sds).  docs/sds.md, "Organism" and "Physics".
 *
 * Ownership: a sessile_sds owns every array in it; sessile_sds_free releases
 * them (a zeroed struct is valid and empty).  Arrays are plain and public so
 * that the topology, morphogen and rule code can work on them directly; after
 * changing x/tet (topology) call sessile_sds_rebuild, which recomputes the
 * derived arrays (marked "derived" below).
 *
 * Units (docs/sds.md): lengths in model units u (an imported icosphere of
 * radius 1 is 1 u across its radius), time in model seconds, mass in
 * density x u^3 (density 1 by default), so gravity 10 is 10 u/s^2. */
#ifndef SESSILE_SDS_H
#define SESSILE_SDS_H

#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include "sessile/gpu/gpu.h"
#include "sessile/status.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- the organism (§3.1, §3.2.1) ------------------------------------------ */
typedef struct sessile_sds {
  /* cells: one per vertex of the complex */
  uint32_t ncells, cap_cells;
  uint32_t nmorph, nstate; /* morphogens and state variables per cell */
  double *x;       /* 3 ncells: positions, u */
  double *v;       /* 3 ncells: velocities, u/s */
  double *r;       /* ncells: radius, u (§3.2.1: mean half edge length at import) */
  double *m;       /* ncells: mass = density 4/3 pi r^3 */
  double *phi;     /* ncells nmorph: morphogen k of cell c at phi[c nmorph + k] */
  double *state;   /* ncells nstate: state variable k of cell c at state[c nstate + k] */
  int32_t *attract; /* ncells: index of the attraction point pulling the cell, -1 none */
  uint8_t *surface; /* derived, ncells: 1 if the cell is a vertex of a boundary face */

  /* tetrahedra: positively oriented, det[x1-x0, x2-x0, x3-x0] > 0 */
  uint32_t ntets, cap_tets;
  uint32_t *tet;   /* 4 ntets */
  double *tet_sm;  /* ntets: spring multiplier s_m (R' = s_m R); <= 0 marks a new tet for rebuild */
  uint8_t *tet_surface; /* derived, ntets: 1 if one of its faces is a boundary face */

  /* derived: unique edges (a < b), sorted by (a, b) */
  uint32_t nedges;
  uint32_t *edge;  /* 2 nedges */
  double *edge_sm; /* nedges: spring multiplier s_m */
  /* nedges: the spring's stiffness on the surface over surface_mult (1;
   * the axial stiffness gives a spring its value at birth, docs/sds.md
   * "Axial stiffness"); an interior spring does not use it */
  double *edge_k;
  int edge_k_defer; /* 1: rebuild leaves a new edge's edge_k 0, for the caller to set (else 1) */
  uint8_t *edge_surface; /* nedges: 1 if the edge is a side of a boundary face */

  /* derived: boundary faces (faces in exactly one tet), counter-clockwise
   * seen from outside, sorted by their smallest-index rotation */
  uint32_t nfaces;
  uint32_t *face;  /* 3 nfaces */

  /* derived: CSR incidence for the gathers, ascending element index */
  uint32_t *cell_edge_off; /* ncells + 1 */
  uint32_t *cell_edge;     /* 2 nedges: edges incident to cell c at [off[c], off[c+1]) */
  uint32_t *cell_tet_off;  /* ncells + 1 */
  uint32_t *cell_tet;      /* 4 ntets */
} sessile_sds;

void sessile_sds_free(sessile_sds *o);
/* Allocates ncells cells and ntets tets (x, v, r, m, phi, state zeroed,
 * attract -1, tet_sm 0), the derived arrays empty.  o is freed first. */
sessile_status sessile_sds_alloc(sessile_sds *o, uint32_t ncells, uint32_t ntets, uint32_t nmorph,
                                 uint32_t nstate);
/* Makes room for ncells cells and ntets tets (keeps contents; new cells are
 * zeroed with attract -1).  Does not change ncells/ntets. */
sessile_status sessile_sds_reserve(sessile_sds *o, uint32_t ncells, uint32_t ntets);
/* Deep copy (dst is freed first). */
sessile_status sessile_sds_copy(const sessile_sds *src, sessile_sds *dst);

/* How rebuild treats a tet or edge that has no spring multiplier yet (a tet
 * with tet_sm <= 0, an edge not in the previous edge list). */
typedef enum sessile_sds_new_sm {
  SESSILE_SDS_NEW_UNIT = 0,   /* s_m = 1: rest size from the radii (§3.1.1, after division) */
  SESSILE_SDS_NEW_RELAXED = 1 /* s_m = V / R: born without stress (§3.2.1, import) */
} sessile_sds_new_sm;

/* Recomputes the derived data from (x, tet) after a topology change: orients
 * every tet positively (swapping two vertices of a negative one; a zero-volume
 * tet is an error), the unique sorted edges, boundary faces (closed check:
 * every interior face in exactly two tets), surface flags, CSR incidence.
 * Edges present in the previous edge list (matched by their cell indices:
 * keep cell indices stable across a topology change) keep their s_m and
 * edge_k; new edges and tets with tet_sm <= 0 get s_m by `new_sm`, new
 * edges edge_k 1 (0 with edge_k_defer).  Radii and masses are
 * not touched. */
sessile_status sessile_sds_rebuild(sessile_sds *o, sessile_sds_new_sm new_sm);
/* As sessile_sds_rebuild, but the tets' orientation is taken as given: for a
 * complex a transformation made and the topology check passed, which may
 * keep slivers inverted before it (sessile_sds_topo_check_kept).  Orienting
 * those by their volume would turn them against their neighbours. */
sessile_status sessile_sds_rebuild_oriented(sessile_sds *o, sessile_sds_new_sm new_sm);

/* Builds an organism from cells x (3 n) and tets (4 nt, either orientation):
 * radii by §3.2.1, mass = density 4/3 pi r^3, s_m = V/R for every edge and
 * tet (zero energy at import), velocities zero. */
sessile_status sessile_sds_from_tets(const double *x, uint32_t n, const uint32_t *tet, uint32_t nt,
                                     uint32_t nmorph, uint32_t nstate, double density,
                                     sessile_sds *out);

/* TetGen switches used when none are given: p (the surface is a PLC), q1.4
 * (radius-edge ratio bound 1.4: no slivers, few Steiner points), Y (keep the
 * surface triangles as they are: every surface vertex is a cell), Q (quiet).
 * Append a<vol> for a volume bound (sessile_sds_from_surface's max_volume). */
#define SESSILE_SDS_TETGEN_SWITCHES "pq1.4YQ"

/* Tetrahedralises the closed, outward-oriented surface s with TetGen
 * (switches NULL: SESSILE_SDS_TETGEN_SWITCHES, plus a<max_volume> when
 * max_volume > 0) and imports it with sessile_sds_from_tets.  A surface that
 * TetGen rejects is SESSILE_ERR_USAGE with TetGen's reason. */
sessile_status sessile_sds_from_surface(const sessile_surface *s, const char *switches,
                                        double max_volume, uint32_t nmorph, uint32_t nstate,
                                        double density, sessile_sds *out);
/* An icosphere (sessile_surface_icosphere: level, radius, center) through
 * sessile_sds_from_surface. */
sessile_status sessile_sds_from_icosphere(int level, double radius, const double center[3],
                                          double max_volume, uint32_t nmorph, uint32_t nstate,
                                          double density, sessile_sds *out);

/* A ball with the mirror symmetry of nfold (2..12) tips round its equator
 * (the dihedral group D_nfold about the z axis through center): the wedge
 * 0 <= phi <= pi / nfold meshed by TetGen (SESSILE_SDS_TETGEN_SWITCHES) inside
 * a boundary of edges about h long, and its 2 nfold mirror images; cells at
 * phi = 2 pi j / nfold on the equator.  Imported as sessile_sds_from_tets. */
sessile_status sessile_sds_symmetric_ball(int nfold, double radius, double h, const double center[3],
                                          uint32_t nmorph, uint32_t nstate, double density, sessile_sds *out);
/* That ball's cells (3 ncells, its surface cells exactly on the sphere) and
 * tets (4 ntets, either orientation) before the import, for a realisation
 * that moves its cells; the caller frees x and tet. */
sessile_status sessile_sds_symmetric_ball_tets(int nfold, double radius, double h, const double center[3],
                                               double **x, uint32_t *ncells, uint32_t **tet, uint32_t *ntets);
/* The sphere of that ball (its surface triangles, outward): a symmetric
 * obstacle (the rock); out is overwritten (zero it first or free it). */
sessile_status sessile_sds_symmetric_sphere(int nfold, double radius, double h, const double center[3],
                                           sessile_surface *out);

/* §3.2.1: r_c = mean over neighbours c' of |x_c - x_c'| / 2 (over the edge
 * list); m = density 4/3 pi r^3.  A cell without edges keeps its radius. */
void sessile_sds_radii_from_edges(sessile_sds *o, double density);
/* A cell's mass after growth, density 4/3 pi r^3 with r^3 rounded once (the
 * exact products of r r and (r r) r: the rules kernel's cube, so that the
 * host's and the device's masses are the same bits; glibc's pow(r, 3) is an
 * ulp off for about one radius in 1 200). */
double sessile_sds_mass(double density, double r);
/* Signed volume of tet t, eq 1: (x1-x0).((x2-x0)x(x3-x0)) / 6. */
double sessile_sds_tet_volume(const sessile_sds *o, uint32_t t);
/* Appendix A: rest volume of a tet whose edge lengths are the sums of its
 * cells' radii (Heron's formula for tetrahedra). */
double sessile_sds_tet_rest(double ra, double rb, double rc, double rd);
/* Rest sizes without the multiplier: R(e) = r_a + r_b, R(t) by Appendix A. */
double sessile_sds_edge_rest_of(const sessile_sds *o, uint32_t e);
double sessile_sds_tet_rest_of(const sessile_sds *o, uint32_t t);
/* Sets s_m = V/R for every edge and tet (§3.2.1). */
void sessile_sds_relax_multipliers(sessile_sds *o);

/* --- physics (§3.2) ------------------------------------------------------- */
/* A static obstacle: a closed triangle mesh (outward, counter-clockwise),
 * not owned.  A cell within its contact distance of the mesh is pushed out
 * along its nearest triangle (docs/sds.md, "Collisions"). */
typedef struct sessile_sds_obstacle {
  uint32_t nv, nf;
  const double *pos;   /* 3 nv */
  const uint32_t *tri; /* 3 nf */
} sessile_sds_obstacle;

typedef struct sessile_sds_params {
  double k_edge;       /* edge stiffness (prototype: 1) */
  double k_vol;        /* volume stiffness (prototype: 2) */
  double surface_mult; /* stiffness multiplier of surface edges and tets (prototype: 1) */
  double damp_visc;    /* viscous damping c: force -c m v, 1/s (the prototype's 1 % per step at dt 0.01: 1) */
  double damp_vol;     /* volume-spring damping on dV/dt (the prototype's damping, 0.001) */
  double gravity;      /* u/s^2 along -z (prototype: 10) */
  int box;             /* 1: confine the cells to [box_lo, box_hi] */
  double box_lo[3], box_hi[3];
  double k_wall;       /* box and obstacle penalty: acceleration per unit depth, 1/s^2 */
  /* contacts (docs/sds.md, "Collisions"): a cell closer than contact_scale x
   * its radius to its nearest obstacle triangle (penalty k_wall) or, for a
   * surface cell, to its nearest boundary face with no corner at the cell or
   * a neighbour (penalty k_contact) is pushed out along that triangle */
  int self_collide;    /* 1: surface self-collision on (default) */
  double contact_scale; /* contact distance / cell radius (1) */
  double k_contact;    /* self-contact penalty: acceleration per unit depth, 1/s^2 (1000) */
  sessile_sds_obstacle obstacle; /* nf 0: none */
  /* sticking to the obstacle (docs/sds.md, "Adhesion and friction"): a cell
   * between one and two contact distances from its nearest obstacle
   * triangle is pulled toward it, A tent((s - delta) / delta) with the peak
   * A at 1.5 delta; a cell within reach of the obstacle's force (delta, or
   * 2 delta with adhesion) has its velocity along the triangle relaxed
   * implicitly in the step, v_t / (1 + friction dt) */
  double adhesion;     /* A, u/s^2 (0: none) */
  double friction;     /* 1/s (0: frictionless) */
  uint32_t nattract;
  const double *attract_pos; /* 3 nattract, not owned */
  double k_attract;    /* attraction: acceleration toward the point, u/s^2 */
  /* step control of sessile_sds_advance (docs/sds.md, "Integrator") */
  double dt;           /* first step, s */
  double dt_min, dt_max;
  double max_move;     /* largest step move of a cell, as a fraction of its radius */
  double stable_safety; /* steps stay below this fraction of sessile_sds_stable_dt (0.5) */
  /* 1: the paper's "same stiffnesses throughout" (§3.2): s_k = k_edge, k_vol
   * (an energy) for every spring and the tets' damping unscaled; 0 (default):
   * the prototype's per-spring scaling (docs/sds.md, "Physics") */
  int uniform_stiffness;
  /* selective mass scaling (docs/sds.md, "Mass scaling"): in a step whose
   * stable bound is computed (the loop's), a cell whose own bound is below
   * this step gets the inertia alpha m (alpha > 1) that lifts its bound to
   * it; every force, drag and gravity included, keeps the cell's mass m, so
   * a state at rest and the overdamped motion are unchanged.  0: none */
  double mass_scaling_dt;
} sessile_sds_params;

/* The prototype's values above; no box, no obstacle, no attraction;
 * self-collision on (contact_scale 1, k_contact 1000); dt 1e-3,
 * dt_min 1e-7, dt_max 0.05, max_move 0.05, stable_safety 0.8. */
void sessile_sds_params_default(sessile_sds_params *p);

/* Energies (host): elastic (edge + volume springs), potential (gravity, box
 * penalty, attraction, contact penalties), kinetic.  The contact energy of a
 * cell is a potential in its own position (its triangle held fixed): the
 * contact force acts on the cell only (a gather), so -grad E equals the
 * force only where no contact is active or per cell (test_sds_collide). */
typedef struct sessile_sds_energy {
  double edge, vol, potential, kinetic;
} sessile_sds_energy;
void sessile_sds_energy_of(const sessile_sds *o, const sessile_sds_params *p, sessile_sds_energy *e);
double sessile_sds_energy_total(const sessile_sds_energy *e);

/* The host reference of the GPU force kernels: f (3 ncells) = -dE/dx plus the
 * damping forces at velocities v, gathered per cell over its incident edges
 * and tets in CSR order (the GPU's order).  with_damping 0 leaves damping out
 * (f is then exactly -grad E). */
void sessile_sds_forces_ref(const sessile_sds *o, const sessile_sds_params *p, int with_damping,
                            double *f);
/* The contacts of a cell (docs/sds.md, "Collisions"). */
typedef struct sessile_sds_contact {
  int32_t tri;  /* nearest boundary face (index into face) closer than the contact distance, without
                   a corner at the cell or a neighbour of it; -1 none (or not a surface cell) */
  int32_t obs;  /* nearest obstacle triangle closer than the contact distance (twice it with adhesion), -1 none */
  double s, s_obs; /* their signed distances from the cell (negative behind the triangle) */
} sessile_sds_contact;
/* The reference: cell c placed at xc (3) against every triangle (brute force). */
void sessile_sds_contact_brute(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, const double *xc,
                               sessile_sds_contact *ct);
/* Every cell at its position (ct: ncells) through a host spatial hash; the
 * same triangles as the brute force (ties go to the lower index). */
sessile_status sessile_sds_contacts(const sessile_sds *o, const sessile_sds_params *p, sessile_sds_contact *ct);
/* Adds the contact acceleration of cell c at xc for contacts ct to acc (3):
 * k (delta - s) along the triangle's outward direction, delta = contact_scale r_c,
 * and the obstacle's adhesion beyond delta; returns the contact energy per
 * unit mass, k/2 (delta - s)^2 summed, plus the adhesion's potential. */
double sessile_sds_contact_accel(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, const double *xc,
                                 const sessile_sds_contact *ct, double *acc);
/* The obstacle's reach: the distance within which the obstacle's force (and
 * friction) acts on a cell of contact distance delta, delta or 2 delta with
 * an obstacle's adhesion. */
double sessile_sds_obstacle_reach(const sessile_sds_params *p, double delta);
/* The friction's direction for a cell at xc with contacts ct: 1 and the unit
 * normal n (3) of its nearest obstacle triangle when friction acts on it,
 * else 0. */
int sessile_sds_friction_normal(const sessile_sds_params *p, const double *xc, const sessile_sds_contact *ct,
                                double *n);

/* One step of the integrator on the host (semi-implicit Euler = leapfrog
 * Verlet): v += dt f/m, the obstacle's friction on v's part along the
 * triangle (v_t / (1 + friction dt)), x += dt v.  With mass scaling the
 * cells' inertia is sessile_sds_inertia's alpha m.  Returns max over cells of
 * |dt v| / r (NaN when out of memory). */
double sessile_sds_step_ref(sessile_sds *o, const sessile_sds_params *p, double dt);
/* The stable step bound of the integrator at the current state (omega dt < 2
 * for the fastest mode, by Gershgorin at rest; docs/sds.md, "Integrator").
 * sessile_sds_gpu_advance never steps above stable_safety times it.  0 when
 * out of host memory.  With mass scaling (mass_scaling_dt H > 0) a cell's
 * bound below H counts as H: its inertia is lifted (sessile_sds_inertia). */
double sessile_sds_stable_dt(const sessile_sds *o, const sessile_sds_params *p);
/* The inertia factor of each cell under mass scaling into alpha (ncells): 1
 * where the cell's own bound is at least mass_scaling_dt (or scaling is off),
 * else (w2 H^2 + 2 gam H) / 4 > 1, whose bound is H (docs/sds.md, "Mass
 * scaling").  The device's stable kernel computes the same operations. */
sessile_status sessile_sds_inertia(const sessile_sds *o, const sessile_sds_params *p, double *alpha);
/* The critical step of that scheme at the current state, undamped (2 /
 * sqrt of M^-1 K's largest eigenvalue, K by finite differences of the
 * forces), by `iters` steps of power iteration; *residual (may be NULL) gets
 * the last iterate's relative residual.  A host reference for tests and the
 * benchmark: it checks how far below the critical step the bound lies. */
double sessile_sds_critical_dt(const sessile_sds *o, const sessile_sds_params *p, int iters, double *residual);
/* Tets with signed volume <= 0, ascending (malloc'd into *list, n into *n). */
sessile_status sessile_sds_inverted_ref(const sessile_sds *o, uint32_t **list, uint32_t *n);

/* --- the GPU side (shaders/sds) ------------------------------------------- */
typedef struct sessile_sds_gpu sessile_sds_gpu;

/* Buffers and kernels for organism o (its sizes; upload copies the state). */
sessile_status sessile_sds_gpu_create(sessile_gpu *g, const sessile_sds *o, const sessile_sds_params *p,
                                      sessile_sds_gpu **out);
void sessile_sds_gpu_destroy(sessile_sds_gpu *s);
/* Uploads everything of o (after a topology change: grows the buffers). */
sessile_status sessile_sds_gpu_upload(sessile_sds_gpu *s, const sessile_sds *o);
/* After growth alone (the same complex as the last upload, and the device's
 * x and v those of o: a step downloaded them): uploads r and m and refreshes
 * what depends on them (the contact lists' staleness).
 * The same device state as sessile_sds_gpu_upload, without the topology. */
sessile_status sessile_sds_gpu_update_radii(sessile_sds_gpu *s, const sessile_sds *o);
/* After the edges' s_m changed (and nothing else of the topology). */
sessile_status sessile_sds_gpu_update_edge_sm(sessile_sds_gpu *s, const sessile_sds *o);
/* The edges' s_m into o (the device's oriented growth moved them). */
sessile_status sessile_sds_gpu_download_edge_sm(sessile_sds_gpu *s, sessile_sds *o);
/* Downloads x, v, r, m into o (same sizes as uploaded; phi and state stay
 * on the host until the morphogen kernels exist). */
sessile_status sessile_sds_gpu_download(sessile_sds_gpu *s, sessile_sds *o);
/* Changes the parameters (obstacle and attraction points re-uploaded). */
sessile_status sessile_sds_gpu_set_params(sessile_sds_gpu *s, const sessile_sds_params *p);
/* Forces at the uploaded state into f (3 ncells), as sessile_sds_forces_ref. */
sessile_status sessile_sds_gpu_forces(sessile_sds_gpu *s, int with_damping, double *f);
/* One integrator step of fixed dt; *max_move (may be NULL) receives the
 * largest |dt v| / r.  It computes no bound, so mass scaling does not act
 * in it (sessile_sds_gpu_advance and the batches: it does). */
sessile_status sessile_sds_gpu_step(sessile_sds_gpu *s, double dt, double *max_move);
/* `steps` (1..1024) steps of fixed dt in one submission, without the move
 * check: for runs that check every K steps (the bench, inversion checks). */
sessile_status sessile_sds_gpu_steps(sessile_sds_gpu *s, uint32_t steps, double dt);
/* The stable step bound of the device's state (shaders/sds/stable.glsl, the
 * kernels of every advance step), as sessile_sds_stable_dt computes it on the
 * host: the test's handle on the kernels. */
sessile_status sessile_sds_gpu_stable_dt(sessile_sds_gpu *s, double *bound);
/* Advances by `steps` accepted steps with step control (docs/sds.md): each
 * step stays below stable_safety x the stable bound of the state it starts
 * from (computed on the device in the step's submission); a step
 * whose largest move exceeds max_move is undone and retried at half dt; after
 * an accepted step the next aims the largest move at 0.8 max_move (the move
 * taken as proportional to the step), growing by at most 1.25, up to dt_max.
 * *dt is the step to try first and receives the next one; *elapsed (may be
 * NULL) is increased by the simulated time.  Fails with SESSILE_ERR_NUMERIC
 * when a step would fall below dt_min or on a non-finite state. */
sessile_status sessile_sds_gpu_advance(sessile_sds_gpu *s, uint32_t steps, double *dt, double *elapsed);
/* The surface hash table of the last build of the contact lists (uint32: counts T,
 * offsets T + 1, cursors T, entries F, rho bits; docs/sds.md "Collisions"),
 * malloc'd into *table, its length into *n: for the determinism test. */
sessile_status sessile_sds_gpu_hash_table(sessile_sds_gpu *s, uint32_t **table, size_t *n);
/* The contact lists' builds so far: all of them, and of those the partial
 * ones (after a topology change that kept the boundary, only the cells it
 * touched; docs/sds.md "Collisions"). */
void sessile_sds_gpu_list_builds(const sessile_sds_gpu *s, uint64_t *all, uint64_t *partial);
/* Times `reps` force evaluations (forces only) with and without the contacts
 * (their lists built) into ms_all, ms_nocontact, and `reps` builds of the
 * contact lists (surface hash and list kernel) into ms_build (0 without
 * contacts): the benchmark's contact columns. */
sessile_status sessile_sds_gpu_time_contacts(sessile_sds_gpu *s, int reps, double *ms_all, double *ms_nocontact,
                                             double *ms_build);
/* storage = 1: the force, flag and list kernels read through storage buffers
 * even where texel views fit (the default, 0, reads through uniform texel
 * buffers where every view fits maxTexelBufferElements: the same bits, vector
 * loads on lavapipe).  For the tests that compare the two. */
void sessile_sds_gpu_set_reads(sessile_sds_gpu *s, int storage);
/* Tets with signed volume <= 0 at the uploaded state, ascending. */
sessile_status sessile_sds_gpu_inverted(sessile_sds_gpu *s, uint32_t **list, uint32_t *n);

#ifdef __cplusplus
}
#endif
#endif
