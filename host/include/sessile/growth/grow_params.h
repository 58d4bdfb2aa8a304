/* sessile — the parameters of `sessile grow`: one table lists every
 * parameter once (name, type, default, range, unit, source); the struct, the
 * JSON/--set parsing, --print-config and the manifest all come from it.
 *
 * Defaults are O'Hagan et al.'s Table 1 (supplement) where the paper gives a
 * value; the rest are ours, each with its reason in docs/model.md.  Lengths
 * are in centimetres (the scene unit that reads Table 1's thresholds against
 * the 6 cm sponge). */
#ifndef SESSILE_GROW_PARAMS_H
#define SESSILE_GROW_PARAMS_H

#include <stdint.h>
#include <stdio.h>
#include "sessile/la/la.h"
#include "sessile/run/param_table.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* X(name, type, default, min, max, bounds, unit, source, description)
 * type: REAL (double), INT (int, range checked), BOOL (0/1), ENUM_* (names in
 * params.c); bounds: 0 (min and max allowed) or LO_OPEN (value > min). */
#define SESSILE_PARAMS(X)                                                                          \
  X(diffusion_limited, BOOL, 1, 0, 1, 0, "", "Table 1",                                               \
    "velocity set to 0 in the nutrient equation (Laplace); false: the flow advects it")           \
  X(advection_scheme, ENUM_ADV, 0, 0, 1, 0, "", "ours (docs/nutrient.md)",                           \
    "diffusion_limited = false: cut (the cut-cell surface and far field of the Laplace nutrient, "  \
    "exponentially fitted, multigrid-BiCGSTAB) or tet (P1+SUPG on the box's tetrahedra with the " \
    "staircase surface and the paper's walls, docs/advdiff.md; for comparison)")                 \
  X(probe, ENUM_PROBE, 0, 0, 1, 0, "", "ours (docs/model.md)",                                       \
    "what a vertex takes up: flux (the nutrient's normal derivative at the surface over the bare " \
    "substratum's, C of order 1) or paper (eq 6: attenuated samples of c along the normal)")      \
  X(probe_distance, REAL, 1.0, 0, 100, LO_OPEN, "cm", "ours (docs/model.md)",                         \
    "flux probe: samples at this distance and twice it along the normal (fixed in cm, not grid units)") \
  X(concentration_offset_distance, REAL, 0.1, 0, 100, 0, "cm", "Table 1",                             \
    "probe = paper: how far along the vertex normal the nutrient is probed")                       \
  X(probe_samples, INT, 8, 2, 256, 0, "", "ours",                                                     \
    "probe = paper: samples along the normal, at d = k/(S-1), k = 0..S-1 (eq 6)")                 \
  X(far_field, ENUM_FAR, 0, 0, 2, 0, "", "ours (docs/model.md)",                                     \
    "the nutrient's far field: height (c = 1 at far_field_height, zero flux through the side "    \
    "walls: the box size is a convergence parameter), walls (c = 1 on every wall but the "        \
    "substratum, the paper's box) or inlet (height, and c = 1 on the inlet wall x = 0 above the " \
    "substratum: fresh water arriving with the current)")                                          \
  X(far_field_height, REAL, -1, -1, 1e6, 0, "cm", "ours (docs/nutrient.md)",                        \
    "far_field = height or inlet: c = 1 at and above this height over the substratum (<= the box top); "  \
    "-1 = 4.8 sponge_radius (28.8 cm for the paper's 6 cm sponge), whatever the box (at most "    \
    "its top, at least two node spacings over the sponge)")                                         \
  X(nutrient_inflow, ENUM_INFLOW, 0, 0, 1, 0, "", "ours (docs/nutrient.md)",                          \
    "diffusion_limited = false and far_field = height: what the current brings through the inflow " \
    "wall x = 0: profile (the bare substratum's c = z / far_field_height, undisturbed by the "    \
    "sponge) or zero_flux (no diffusive flux there, the earlier model: the box then recirculates " \
    "the sponge's depletion, and the result depends on the box and the grid)")                   \
  X(nutrient_pc_type, ENUM_SOLVER, 0, 0, 1, 0, "", "ours (docs/nutrient.md)",                         \
    "mg (multigrid-preconditioned CG on the nested box levels) or jacobi (Jacobi-PCG, for comparison)") \
  X(box_resolution, INT, 2, 1, 6, 0, "", "Table 1",                                                   \
    "box mesh subdivisions: 1 = the base grid, each step halves the cell size")                    \
  X(box_base_cell, REAL, 1.2, 0.01, 1000, 0, "cm", "ours", "cube edge of the base grid (resolution 1)") \
  X(box_cells_x, INT, 32, 1, 4096, 0, "", "ours", "base-grid cubes along x (flow direction)")         \
  X(box_cells_y, INT, 32, 1, 4096, 0, "", "ours", "base-grid cubes along y")                          \
  X(box_cells_z, INT, 24, 1, 4096, 0, "", "ours", "base-grid cubes along z (z = 0: substratum)")      \
  X(sponge_resolution, INT, 4, 1, 7, 0, "", "Table 1",                                                \
    "icosphere level: 1 = icosahedron; 4 = 642 vertices, 1280 triangles")                         \
  X(sponge_radius, REAL, 6, 0.01, 1000, 0, "cm", "paper §4.1", "radius of the initial icosphere")     \
  X(sponge_x, REAL, -1, -1, 1e6, 0, "cm", "ours", "initial centre x; -1 = the box centre")            \
  X(sponge_y, REAL, -1, -1, 1e6, 0, "cm", "ours", "initial centre y; -1 = the box centre")            \
  X(sponge_z, REAL, 0, 0, 1e6, 0, "cm", "ours",                                                       \
    "initial centre height; the part below the substratum is flattened onto it (0: a dome)")     \
  X(position_jitter, REAL, 0, 0, 1e6, 0, "cm", "ours (§4.7)",                                         \
    "random x/y shift of the sponge, uniform in [-j, j] from the seed (crella: 4)")                \
  X(growth_rate, REAL, 5, 0, 1e6, 0, "", "Table 1", "Gr in the Chindapol growth function (eq 10)")    \
  X(l_max, REAL, 0.06, 0, 1e6, 0, "cm", "ours", "Lmax: Gr Lmax is the asymptotic growth per iteration (eq 10)")            \
  X(max_growth, REAL, 0.3, 0, 1e6, 0, "cm", "ours", "maxgrowth: clampMG's upper bound (eq 10)")       \
  X(kinetic_order, REAL, 1.4, 0, 100, LO_OPEN, "", "Table 1", "Chindapol kinetic order n (eq 10)")         \
  X(growth_constant, REAL, 1, 0, 1e6, LO_OPEN, "", "Table 1", "Chindapol characteristic growth constant K") \
  X(growth_threshold, REAL, 0, 0, 1e6, 0, "cm", "Table 1", "growth length a vertex needs to grow")    \
  X(nutrient_threshold, REAL, 0, 0, 1e6, 0, "", "ours", "Iroquois: grow only where translocated C exceeds it") \
  X(t_give, REAL, 0.05, 0, 1, 0, "", "ours", "translocation: share given to each neighbour (eqs 7-8)") \
  X(translocate_passes, INT, 1, 0, 100, 0, "", "ours", "translocation sweeps per iteration (0: off)") \
  X(translocate_mode, ENUM_TRANSLOCATE, 0, 0, 1, 0, "", "ours (docs/growth.md)",                     \
    "translocation sweep: parallel (every vertex at once, order-independent) or sequential (the " \
    "paper's vertex by vertex, in index order, on the host)")                                     \
  X(skeletal_growth, ENUM_SKELETON, 0, 0, 1, 0, "", "Table 1",                                        \
    "radiate (growth along the normal) or halichondrid (normal + random vector, eqs 1-2)")        \
  X(normal_offset_radius, REAL, 0.02, 0, 1e6, 0, "", "Table 1",                                       \
    "R: Halichondrid random vector uniform in [-R, R]^3 added to the unit normal")                \
  X(vertex_insertion_threshold, REAL, 0.6, 0, 1e6, 0, "cm", "Table 1", "split edges longer than this") \
  X(vertex_fusion_threshold, REAL, 0.5, 0, 1e6, 0, "cm", "Table 1", "fuse edges shorter than this")  \
  X(triangle_area_deletion_threshold, REAL, 0.1, 0, 1e6, 0, "cm^2", "Table 1",                        \
    "collapse triangles smaller than this (shortest edge)")                                        \
  X(domain, ENUM_DOMAIN, 0, 0, 1, 0, "", "ours (DESIGN)",                                            \
    "water mesh of the flow: immersed (the box, sponge as solid nodes; the paper's way) or "      \
    "conforming (TetGen, the sponge as a hole; falls back to immersed when TetGen fails)")       \
  X(fluid_resolution, INT, 1, 1, 6, 0, "", "ours",                                                    \
    "box level of the immersed flow (<= box_resolution; velocities interpolated to the box)")    \
  X(fluid_every_iteration, BOOL, 0, 0, 1, 0, "", "ours",                                              \
    "with diffusion_limited, solve the flow every iteration too (else only for snapshots)")      \
  X(fluid_at_snapshots, BOOL, 1, 0, 1, 0, "", "ours",                                                 \
    "with diffusion_limited, solve the flow at snapshots for their slices and fields (off: none)") \
  X(fluid_density, REAL, 1000, 0, 1e5, 0, "kg/m^3", "paper §4.2", "rho in the Navier-Stokes equations (eq 3)") \
  X(fluid_viscosity, REAL, 5.0e-2, 1e-9, 1e5, 0, "Pa s", "paper §4.2", "eta in the Navier-Stokes equations (eq 3)") \
  X(inlet_velocity, REAL, 0.05, 0, 100, 0, "m/s", "paper §4.2", "inflow at x-min, along +x")        \
  X(fluid_newton_max_it, INT, 100, 1, 10000, 0, "", "Table 1", "Newton iterations of the fluid solve at most") \
  X(fluid_max_seconds, REAL, 600, 0, 1e7, LO_OPEN, "s", "ours",                                   \
    "wall-clock bound of one flow solve: past it the solve fails with a message (docs/fluid.md)") \
  X(fluid_newton_rtol, REAL, 1e-3, 1e-12, 0.5, 0, "", "paper §4.2", "Newton stops at residual <= this times the rest state's residual") \
  X(fluid_ksp_type, ENUM_KSP, 0, 0, 1, 0, "", "ours (docs/fluid.md)",                              \
    "Krylov method of each Newton step's linear system: gmres (GMRES(fluid_ksp_restart)) or "     \
    "bicgstab")                                                                                    \
  X(fluid_pc_type, ENUM_PC, SESSILE_PC_MG, 0, 4, 0, "", "ours (docs/fluid.md)",                    \
    "la's preconditioner of the fluid's linear solves (sessile/la/pc.h): none, jacobi, ilu0 "    \
    "(Jacobi on a matrix stored in chunks), block_jacobi (each node's 4x4 block) or mg (block "  \
    "multigrid on the immersed box; ilu0 on the conforming mesh)")                               \
  X(fluid_ksp_rtol, REAL, 1e-6, 1e-14, 0.1, 0, "", "paper §4.2 (linear 1e-6)",                      \
    "true relative residual each Newton step's linear solve aims at")                             \
  X(fluid_newton_forcing, ENUM_FORCING, 1, 0, 1, 0, "", "ours (docs/fluid.md)",                       \
    "each Newton step's linear tolerance: ew (Eisenstat-Walker: loose while the residual falls "  \
    "slowly, tight near the solution, never below fluid_ksp_rtol; the same Newton stopping rule) " \
    "or fixed (fluid_ksp_rtol every step, the paper's)")                                         \
  X(fluid_ksp_max_it, INT, 100, 1, 1000000, 0, "", "paper §4.2 (linear 100)",                       \
    "Krylov iterations per Newton step at most (past it the step is taken as it is)")             \
  X(fluid_ksp_restart, INT, 50, 1, 64, 0, "", "ours (docs/fluid.md)",                               \
    "GMRES(m): basis vectors between restarts (la holds at most 64; unused by bicgstab)")         \
  X(fluid_nested, BOOL, 1, 0, 1, 0, "", "ours (docs/fluid.md)",                                      \
    "start a flow far from its solution from the solution on the box of twice the spacing "      \
    "(nested iteration; the same tolerance)")                                                     \
  X(fluid_mg_precision, INT, 32, 32, 64, 0, "", "ours (docs/fluid.md)",                         \
    "bits of the block multigrid cycle of fluid_pc_type=mg: 64, or 32 (the cycle in fp32 inside "  \
    "the fp64 GMRES: half its memory traffic; docs/fluid.md, \"Multigrid\")")                    \
  X(fluid_mg_cycle, ENUM_CYCLE, SESSILE_FLUID_CYCLE_W, 0, 2, 0, "", "ours (docs/fluid.md)",       \
    "coarse corrections of fluid_pc_type=mg's cycle: v (one per level), w (two per level) or vw " \
    "(one on the finest level, two below; docs/fluid.md, \"Multigrid\")")                         \
  X(fluid_mg_sweeps, INT, 3, 1, 8, 0, "", "ours (docs/fluid.md)",                                \
    "Gauss-Seidel sweeps of fluid_pc_type=mg's smoother before and after each coarse correction " \
    "(3: 8 GMRES iterations a Newton step at box levels 1 and 2 where 2 took 11 and 14; "       \
    "docs/fluid.md, \"Multigrid\")")                                                            \
  X(diffusion_coefficient, REAL, 1e-4, 1e-12, 10, 0, "m^2/s", "ours",                                 \
    "D in eq 5 (an eddy diffusivity; docs/advdiff.md); unused while diffusion_limited")           \
  X(conforming_quality, REAL, 1.5, 1.05, 10, 0, "", "ours", "TetGen radius-edge ratio bound (-q)")     \
  X(conforming_size_far, REAL, 2.4, 0.1, 100, 0, "cm", "ours", "TetGen target edge length far from the sponge") \
  X(nutrient_ksp_rtol, REAL, 1e-6, 1e-14, 0.1, 0, "", "paper (linear tolerance)",                           \
    "true relative residual the nutrient solve (diffusion limited: CG) must reach; the fluid's "  \
    "is fluid_ksp_rtol")                                        \
  X(nutrient_ksp_max_it, INT, 5000, 1, 1000000, 0, "", "ours", "iteration bound of the nutrient solve")

typedef enum { SESSILE_SKELETON_RADIATE = 0, SESSILE_SKELETON_HALICHONDRID = 1 } sessile_skeleton_type;
typedef enum { SESSILE_DOMAIN_IMMERSED = 0, SESSILE_DOMAIN_CONFORMING = 1 } sessile_domain;
typedef enum { SESSILE_PROBE_FLUX = 0, SESSILE_PROBE_PAPER = 1 } sessile_probe;
typedef enum { SESSILE_FAR_HEIGHT = 0, SESSILE_FAR_WALLS = 1, SESSILE_FAR_INLET = 2 } sessile_far;
/* nutrient_inflow: the inflow wall of the advected nutrient under far_field = height. */
typedef enum { SESSILE_INFLOW_PROFILE = 0, SESSILE_INFLOW_ZERO_FLUX = 1 } sessile_inflow;
typedef enum { SESSILE_SOLVER_MG = 0, SESSILE_SOLVER_JACOBI = 1 } sessile_solver;
typedef enum { SESSILE_TRANSLOCATE_PARALLEL = 0, SESSILE_TRANSLOCATE_SEQUENTIAL = 1 } sessile_translocate;
typedef enum { SESSILE_ADVECTION_CUT = 0, SESSILE_ADVECTION_TET = 1 } sessile_advection;
/* fluid_ksp_type's values; fluid_pc_type's value is la's sessile_pc_type
 * itself (its names are the pc registry's, in the enum's order). */
typedef enum { SESSILE_FLUID_KSP_GMRES = 0, SESSILE_FLUID_KSP_BICGSTAB = 1 } sessile_fluid_ksp;
/* fluid_mg_cycle's values: sessile_bmg_options.cycle minus one. */
typedef enum { SESSILE_FLUID_CYCLE_V = 0, SESSILE_FLUID_CYCLE_W = 1, SESSILE_FLUID_CYCLE_VW = 2 } sessile_fluid_cycle;

typedef struct sessile_grow_params {
#define SESSILE_PARAM_FIELD_REAL(n) double n;
#define SESSILE_PARAM_FIELD_INT(n) int n;
#define SESSILE_PARAM_FIELD_BOOL(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_SKELETON(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_DOMAIN(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_PROBE(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_FAR(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_INFLOW(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_SOLVER(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_TRANSLOCATE(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_ADV(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_KSP(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_PC(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_CYCLE(n) int n;
#define SESSILE_PARAM_FIELD_ENUM_FORCING(n) int n;
#define X(name, type, def, lo, hi, bounds, unit, src, desc) SESSILE_PARAM_FIELD_##type(name)
  SESSILE_PARAMS(X)
#undef X
} sessile_grow_params;

/* The table of `sessile grow` (sessile/run/param_table.h): the one source of
 * every default, range, unit and source. */
extern const sessile_param_table sessile_grow_param_table;

/* Table 1 as is (the `radiate` preset). */
void sessile_params_default(sessile_grow_params *p);
/* Applies a preset: "radiate" (Table 1 as is) or "crella" (Halichondrid +
 * randomised position).  SESSILE_ERR_USAGE for an unknown name. */
sessile_status sessile_params_preset(sessile_grow_params *p, const char *name);
/* Sets one parameter from text ("0.3", "true", "halichondrid"). */
sessile_status sessile_params_set(sessile_grow_params *p, const char *key, const char *value);
/* Every range and every cross-parameter check that needs no device (the
 * sponge inside the box with its wall margin, box sizes within 32-bit
 * indices and host memory, ...). */
sessile_status sessile_params_validate(const sessile_grow_params *p);
/* The far-field height in cm: far_field_height, or for -1 4.8 sponge_radius,
 * kept within [sponge top + 2 node spacings, box top] (docs/nutrient.md, "The
 * far-field height"). */
double sessile_params_far_field_height(const sessile_grow_params *p);

struct sessile_fluid_params;
/* The fluid's solver choices (fluid_ksp_*, fluid_pc_type, fluid_newton_rtol,
 * fluid_newton_max_it) into fp, its other fields left as they are: the one
 * mapping `sessile grow` and `sessile bench fluid` share. */
void sessile_params_fluid_solver(const sessile_grow_params *p, struct sessile_fluid_params *fp);

/* Bytes of device memory the growth loop needs at least (box vectors, the
 * nutrient operator, the flow at snapshots): the run refuses to start when
 * it exceeds the device's heap. */
double sessile_params_device_bytes(const sessile_grow_params *p);

#ifdef __cplusplus
}
#endif
#endif
