/* SDS process model (Porter & McCormack §3.3): morphogens that diffuse and
 * decay between adjacent cells, and rules that turn a cell's state into
 * actions (set a morphogen or state, produce a morphogen, grow the radius,
 * divide toward a morphogen gradient).
 *
 * Everything here works on raw arrays so the organism (sds.h) can call it:
 *   pos[3c..3c+2]          cell positions
 *   radius[c]              cell radii (vol(c) = 4/3 pi r^3)
 *   nbr_off[c]..nbr_off[c+1]-1 index nbr[]: the cells adjacent to c (CSR,
 *                          symmetric: n in N(c) iff c in N(n))
 *   phi[c*nmorph + k]      amount of morphogen k in cell c
 *   state[c*nstate + k]    state variable k of cell c
 * Formulas and decisions: docs/sds_morphogens.md, docs/sds_rules.md. */
#ifndef SESSILE_SDS_PROCESS_H
#define SESSILE_SDS_PROCESS_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/gpu/gpu.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- morphogens (host/sds/morph.c, morph_gpu.c) --------------------------- */
typedef struct sessile_morph_cells {
  int ncells;
  const double *pos;       /* 3 per cell */
  const double *radius;    /* 1 per cell */
  const uint32_t *nbr_off; /* ncells + 1 */
  const uint32_t *nbr;     /* nbr_off[ncells] */
  const uint8_t *surface;  /* 1 per cell, 1 on the boundary (the rules' `surface`); NULL: all 0 */
} sessile_morph_cells;

typedef struct sessile_morph_coef {
  int nmorph;
  const double *diffusion; /* D_k >= 0 */
  const double *decay;     /* C_k >= 0 */
  const int *capped;       /* 1: amount bounded by vol(c) (the paper); 0: by 0 only (timers); NULL: all 1 */
} sessile_morph_coef;

/* vol(c) = 4/3 pi r^3 (§3.3). */
double sessile_morph_vol(double r);

/* The paper's discrete Laplacian of morphogen k at cell c:
 *   sum_{n in N(c)} (min(n_phi, vol(c)) - min(c_phi, vol(n))) / |c_x - n_x|. */
double sessile_morph_laplacian(const sessile_morph_cells *cells, int nmorph, const double *phi, int c, int k);

/* The largest explicit Euler step that keeps the update monotone (so amounts
 * stay in [0, vol] without clamping, see docs/sds_morphogens.md):
 *   dt_max = min_{c,k} 1 / (D_k sum_{n in N(c)} 1/|c_x - n_x| + C_k)
 * (infinity when every D_k and C_k is 0).  0 when two adjacent cells coincide. */
double sessile_morph_dt_max(const sessile_morph_cells *cells, const sessile_morph_coef *coef);

/* One explicit Euler step of every morphogen (plain-C reference of the GPU
 * kernel): phi_out = clamp(phi + dt (D lap - C phi + src), 0, cap) where
 * cap = vol(c) for capped morphogens, +inf otherwise.  src (rates, amount per
 * time, ncells*nmorph) may be NULL.  phi_out must not alias phi.  Refuses
 * (SESSILE_ERR_USAGE) dt > dt_max (1e-12 relative slack) or dt <= 0.
 * *clamped (may be NULL) receives how many values the clamp changed. */
sessile_status sessile_morph_step(const sessile_morph_cells *cells, const sessile_morph_coef *coef,
                                  const double *phi, const double *src, double dt, double *phi_out,
                                  size_t *clamped);

/* The sum of morphogen k over all cells. */
double sessile_morph_total(int ncells, int nmorph, const double *phi, int k);

/* Least-squares gradient of morphogen k at cell c over its neighbours:
 * g minimising sum_n (g . (x_n - x_c) - (phi_n - phi_c))^2 (exact for a
 * linear field when the neighbour offsets span 3-D).  When they do not span
 * (fewer than 3 independent offsets), falls back to sum_n dphi d/|d|^2.
 * Returns 1 with grad filled, 0 when the gradient is zero (grad = 0). */
int sessile_morph_gradient(const sessile_morph_cells *cells, int nmorph, const double *phi, int c, int k,
                           double grad[3]);

/* The kernel on the GPU: buffers kept between steps.  Positions and radii
 * change with the physics: call set_cells again after they move (or bind the
 * physics' buffers once the organism owns them: sessile_morph_gpu_buffer). */
typedef struct sessile_morph_gpu sessile_morph_gpu;
sessile_status sessile_morph_gpu_create(sessile_gpu *g, sessile_morph_gpu **out);
void sessile_morph_gpu_destroy(sessile_morph_gpu *m);
/* Uploads cells and coefficients (grows the buffers as needed). */
sessile_status sessile_morph_gpu_set_cells(sessile_morph_gpu *m, const sessile_morph_cells *cells,
                                           const sessile_morph_coef *coef);
/* As set_cells when the cells' neighbour lists and the coefficients are
 * those of the last set_cells (between topology changes): the positions and
 * radii alone go up, with the next step's submission (as set_phi's amounts;
 * get_phi or set_cells runs uploads left without a step), and the step
 * bound is recomputed.  Refuses another cell count. */
sessile_status sessile_morph_gpu_move_cells(sessile_morph_gpu *m, const sessile_morph_cells *cells,
                                            const sessile_morph_coef *coef);
/* Uploads amounts and source rates (src NULL: zero). */
sessile_status sessile_morph_gpu_set_phi(sessile_morph_gpu *m, const double *phi, const double *src);
/* nsteps steps of size dt in one submission (ping-pong buffers); refuses
 * dt > dt_max of the cells last set. */
sessile_status sessile_morph_gpu_step(sessile_morph_gpu *m, double dt, int nsteps);
sessile_status sessile_morph_gpu_get_phi(sessile_morph_gpu *m, double *phi);
/* storage = 1: the step reads through storage buffers even where texel views
 * fit (default 0: uniform texel buffers where they fit, the same bits, vector
 * loads on lavapipe).  For the tests that compare the two. */
void sessile_morph_gpu_set_reads(sessile_morph_gpu *m, int storage);
/* The explicit Euler bound of the cells last set (sessile_morph_dt_max). */
double sessile_morph_gpu_dt_max(const sessile_morph_gpu *m);

/* --- rules (host/sds/rules_*.c) ------------------------------------------- */
#define SESSILE_SDS_NAME 32
#define SESSILE_SDS_MAX_VALUES 16

typedef enum sessile_sds_action_kind {
  SESSILE_SDS_SET_MORPH = 0, /* set morphogen `target` to value */
  SESSILE_SDS_SET_STATE = 1, /* set state variable `target` to value */
  SESSILE_SDS_PRODUCE = 2,   /* source rate of morphogen `target` (amount per time) */
  SESSILE_SDS_GROW = 3,      /* dr/dt */
  SESSILE_SDS_DIVIDE = 4,    /* divide toward grad of morphogen `target` */
  SESSILE_SDS_RESET = 5      /* timer `target` back to its start value */
} sessile_sds_action_kind;

/* A physics or scene parameter line `name = v1 v2 ...` (owned by the
 * organism; the rule layer keeps them verbatim) or `name = "text"`. */
typedef struct sessile_sds_param {
  char name[SESSILE_SDS_NAME];
  int nvalues;
  double values[SESSILE_SDS_MAX_VALUES];
  char text[256]; /* for a quoted value (a file name) */
  int line;
} sessile_sds_param;

typedef struct sessile_sds_model sessile_sds_model;

/* Parses a model text (docs/sds_rules.md).  `file` names it in messages.
 * Bad input: SESSILE_ERR_USAGE with "file:line:column: message". */
sessile_status sessile_sds_model_parse(const char *text, const char *file, sessile_sds_model **out);
/* Reads and parses a file. */
sessile_status sessile_sds_model_load(const char *path, sessile_sds_model **out);
void sessile_sds_model_destroy(sessile_sds_model *m);

int sessile_sds_model_nmorph(const sessile_sds_model *m);
int sessile_sds_model_nstate(const sessile_sds_model *m);
int sessile_sds_model_nrules(const sessile_sds_model *m);
/* The morphogen declared `axis=1` (its gradient is the tissue's axis for the
 * axial stiffness, docs/sds.md), -1 if none. */
int sessile_sds_model_axis(const sessile_sds_model *m);
const char *sessile_sds_model_morph_name(const sessile_sds_model *m, int k);
const char *sessile_sds_model_state_name(const sessile_sds_model *m, int k);
/* Index of a morphogen / state variable by name, -1 if none. */
int sessile_sds_model_morph_index(const sessile_sds_model *m, const char *name);
int sessile_sds_model_state_index(const sessile_sds_model *m, const char *name);
/* Per-morphogen coefficients (arrays owned by the model). */
sessile_morph_coef sessile_sds_model_coef(const sessile_sds_model *m);
/* Start value of morphogen k (a timer's `start`; 0 otherwise) and of state k. */
double sessile_sds_model_morph_start(const sessile_sds_model *m, int k);
double sessile_sds_model_state_start(const sessile_sds_model *m, int k);
/* Physics/scene parameters, in file order. */
int sessile_sds_model_nparams(const sessile_sds_model *m);
const sessile_sds_param *sessile_sds_model_param(const sessile_sds_model *m, int i);
const sessile_sds_param *sessile_sds_model_param_find(const sessile_sds_model *m, const char *name);
/* Growing-tip directions (`tip x y z` lines, unit vectors): the loader marks
 * the surface cell nearest each direction from the centroid as state tip = 1. */
int sessile_sds_model_ntips(const sessile_sds_model *m);
const double *sessile_sds_model_tip(const sessile_sds_model *m, int i);

/* The actions of one evaluation.  Conditions and values read the state at
 * the start of the step (synchronous update): rule order only matters among
 * sets of one target (the later rule wins), never for conditions. */
typedef struct sessile_sds_set {
  int cell, kind, target; /* kind SET_MORPH, SET_STATE or RESET */
  double value;
} sessile_sds_set;
typedef struct sessile_sds_divide {
  int cell, rule;
  double dir[3]; /* unit, or 0 when the gradient vanishes (the caller draws one) */
} sessile_sds_divide;
typedef struct sessile_sds_actions {
  int ncells, nmorph;
  double *grow;      /* dr/dt per cell: the sum over firing grow rules */
  double *produce;   /* source rates, ncells*nmorph: the sum over firing produce rules */
  sessile_sds_set *sets;
  size_t nsets, cap_sets;
  sessile_sds_divide *divides; /* at most one per cell (the first firing divide rule) */
  size_t ndivides, cap_divides;
  size_t fired;      /* rule firings in all */
} sessile_sds_actions;
void sessile_sds_actions_free(sessile_sds_actions *a);

/* Evaluates every rule on every cell in ascending cell index, rules in file
 * order.  state may be NULL when the model has no state variables. */
sessile_status sessile_sds_rules_eval(const sessile_sds_model *m, const sessile_morph_cells *cells,
                                      const double *phi, const double *state, double time,
                                      sessile_sds_actions *out);

/* The same through the rules' bytecode (docs/sds_rules.md, "Bytecode"),
 * compiled at load: the same actions, bit for bit.  SESSILE_ERR_USAGE when
 * the model's rules did not compile (sessile_sds_model_bytecode_refusal). */
sessile_status sessile_sds_rules_eval_vm(const sessile_sds_model *m, const sessile_morph_cells *cells,
                                         const double *phi, const double *state, double time,
                                         sessile_sds_actions *out);
/* NULL when the rules compiled to bytecode (device = 1: and every operation
 * has a device version); else why not, "file:line: rule NAME: ...". */
const char *sessile_sds_model_bytecode_refusal(const sessile_sds_model *m, int device);
/* The rules' generated kernel (docs/sds_rules.md, "Generated kernel")
 * compiled to SPIR-V without a device, for tests and the fuzzer: *words
 * malloc'ed (*n of them); with morphogens the batch's rules_morph kernel is
 * compiled too (and must compile), its words not returned.  A model the device refuses is SESSILE_ERR_USAGE
 * with the refusal; anything else that fails is ours (SESSILE_ERR_INTERNAL). */
sessile_status sessile_sds_model_rules_spirv(const sessile_sds_model *m, uint32_t **words, size_t *n);

/* Applies sets (values clamped to [0, vol] for capped morphogens, >= 0 for
 * timers) and radius growth r += dt * grow.  Sources go to the morphogen
 * step, divisions to the organism. */
void sessile_sds_actions_apply(const sessile_sds_model *m, const sessile_sds_actions *a, double dt,
                               double *radius, double *phi, double *state);

/* --- §3.6: a cell below each growing tip (host/sds/rules_tips.c) ---------- */
typedef struct sessile_sds_tip_check {
  int tip;         /* the tip cell */
  int below;       /* an interior neighbour within the cone, or -1 */
  int split;       /* when below < 0: the neighbour to divide inward (most inward interior neighbour, else the tip) */
  double inward[3];/* the unit inward direction used */
  double cosine;   /* cos of the angle between inward and (below or split) - tip */
} sessile_sds_tip_check;

/* For every tip (state tip_state >= 0.5) on the surface (surface[c] != 0),
 * looks for an interior neighbour n with cos(angle(x_n - x_c, inward)) >=
 * min_cos; inward is -normal when normals (3 per cell, outward) are given,
 * else toward the centroid of all cells.  Returns every tip checked (in cell
 * order) in *out (malloc'd, *n entries); the caller inserts a cell for each
 * with below < 0 (docs/sds_rules.md, "A cell below each tip"). */
sessile_status sessile_sds_tips_below(const sessile_morph_cells *cells, const uint8_t *surface,
                                      const double *normals, const double *state, int nstate,
                                      int tip_state, double min_cos, sessile_sds_tip_check **out, int *n);

#ifdef __cplusplus
}
#endif
#endif
