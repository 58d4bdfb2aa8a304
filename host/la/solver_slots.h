/* Scalar slots of the Krylov solvers; mirrors shaders/common/solver_slots.glsl. */
#ifndef SESSILE_SOLVER_SLOTS_H
#define SESSILE_SOLVER_SLOTS_H
enum {
  S_RTOL2 = 6,
  CG_RZ = 8, CG_PQ = 9, CG_ALPHA = 10, CG_BETA = 11, CG_RZNEW = 12, CG_RR = 13,
  BI_RHO = 8, BI_ALPHA = 10, BI_OMEGA = 11, BI_BETA = 12, BI_R0V = 13, BI_SS = 14, BI_TS = 15,
  BI_TT = 16, BI_RR = 17, BI_RHONEW = 18, BI_HALF = 19,
  GM_BETA = 8, GM_INV = 9, GM_K = 10, GM_DONE = 11, GM_EST = 12, GM_BASE = 128,
  GM_ZERO = 13, /* holds 0 (host-set): the fill coefficient of GMRES's ILU(0) update */
  S_TRUE = 63 /* true residual norm, written by la_true_residual */
};
#endif
