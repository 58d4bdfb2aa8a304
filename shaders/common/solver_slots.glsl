// Scalar slots of the Krylov solvers (host/la/solver_slots.h mirrors them).
#define S_RTOL2 6
// CG
#define CG_RZ 8
#define CG_PQ 9
#define CG_ALPHA 10
#define CG_BETA 11
#define CG_RZNEW 12
#define CG_RR 13
// BiCGSTAB
#define BI_RHO 8
#define BI_ALPHA 10
#define BI_OMEGA 11
#define BI_BETA 12
#define BI_R0V 13
#define BI_SS 14
#define BI_TS 15
#define BI_TT 16
#define BI_RR 17
#define BI_RHONEW 18
#define BI_HALF 19
// GMRES
#define GM_BETA 8
#define GM_INV 9
#define GM_K 10
#define GM_DONE 11
#define GM_EST 12
#define GM_BASE 128
// Breakdown reasons (S_REASON)
#define R_NOT_SPD 1.0
#define R_NONFINITE 2.0
#define R_RHO_ZERO 3.0
#define R_R0V_ZERO 4.0
#define R_T_ZERO 5.0
#define R_STAGNATION 6.0
