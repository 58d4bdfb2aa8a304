/* The fluid's solver choices in the grow table (fluid_ksp_*, fluid_pc_type,
 * the Newton tolerance and bound, the nested start, the multigrid cycle's precision, kind and
 * sweeps) mapped onto sessile_fluid_params: the one
 * place `sessile grow` and `sessile bench fluid` take them from. */
#include "sessile/fem/fluid.h"
#include "sessile/growth/grow_params.h"

_Static_assert(SESSILE_PC_NONE == 0 && SESSILE_PC_JACOBI == 1 && SESSILE_PC_ILU0 == 2 &&
                   SESSILE_PC_BLOCK_JACOBI == 3 && SESSILE_PC_MG == 4,
               "fluid_pc_type's names (params.c) follow sessile_pc_type's order");

_Static_assert(SESSILE_FLUID_FORCING_FIXED == 0 && SESSILE_FLUID_FORCING_EW == 1,
               "fluid_newton_forcing's names (params.c) follow sessile_fluid_forcing's order");

void sessile_params_fluid_solver(const sessile_grow_params *p, sessile_fluid_params *fp) {
  fp->ksp = p->fluid_ksp_type == SESSILE_FLUID_KSP_BICGSTAB ? SESSILE_KSP_BICGSTAB : SESSILE_KSP_GMRES;
  fp->pc = (sessile_pc_type)p->fluid_pc_type;
  fp->linear_rtol = p->fluid_ksp_rtol;
  fp->linear_max = p->fluid_ksp_max_it;
  fp->forcing = (sessile_fluid_forcing)p->fluid_newton_forcing; /* fixed, ew: the enum's order */
  fp->restart = p->fluid_ksp_restart;
  fp->newton_rtol = p->fluid_newton_rtol;
  fp->newton_max = p->fluid_newton_max_it;
  fp->nested = p->fluid_nested;
  fp->mg.precision = p->fluid_mg_precision;
  fp->mg.cycle = p->fluid_mg_cycle + 1; /* sessile_fluid_cycle: v, w, vw = bmg's 1, 2, 3 */
  fp->mg.pre = fp->mg.post = p->fluid_mg_sweeps;
}
