/* §3.6: a limb one cell thick grows only when an interior cell lies directly
 * below its growing tip (its divisions push the tip outward).  The paper adds
 * that cell by hand; this finds the tips that lack one and names the cell to
 * divide inward (docs/sds_rules.md, "A cell below each tip"). */
#include <math.h>
#include <stdlib.h>
#include "sessile/sds/sds_process.h"

sessile_status sessile_sds_tips_below(const sessile_morph_cells *cl, const uint8_t *surface, const double *normals,
                                      const double *state, int nstate, int tip_state, double min_cos,
                                      sessile_sds_tip_check **out, int *nout) {
  *out = NULL, *nout = 0;
  SESSILE_CHECK(tip_state >= 0 && tip_state < nstate, SESSILE_ERR_USAGE,
                "tips below: state index %d out of range (the model has %d state variables)", tip_state, nstate);
  SESSILE_CHECK(min_cos > -1 && min_cos <= 1, SESSILE_ERR_USAGE, "tips below: min_cos = %g outside (-1, 1]", min_cos);
  double ctr[3] = {0, 0, 0};
  for (int c = 0; c < cl->ncells; c++)
    for (int a = 0; a < 3; a++) ctr[a] += cl->pos[3 * c + a] / cl->ncells;
  int n = 0;
  for (int c = 0; c < cl->ncells; c++) n += surface[c] && state[(size_t)c * nstate + tip_state] >= 0.5;
  if (!n) return SESSILE_OK;
  sessile_sds_tip_check *t = calloc((size_t)n, sizeof *t);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory for %d tips", n);
  int i = 0;
  for (int c = 0; c < cl->ncells; c++) {
    if (!(surface[c] && state[(size_t)c * nstate + tip_state] >= 0.5)) continue;
    sessile_sds_tip_check *q = &t[i++];
    q->tip = c, q->below = -1, q->split = c, q->cosine = -2;
    double in[3], l = 0;
    for (int a = 0; a < 3; a++) {
      in[a] = normals ? -normals[3 * c + a] : ctr[a] - cl->pos[3 * c + a];
      l += in[a] * in[a];
    }
    l = sqrt(l);
    for (int a = 0; a < 3; a++) q->inward[a] = l > 0 ? in[a] / l : 0;
    double best_in = -2, best_any = -2, spacing = 0;
    int arg_in = -1;
    /* "directly below": within the cone and no farther than the tip's mean
     * distance to its neighbours.  A coarse body's interior cells lie deep
     * (0.5 u below the surface of the level-2 sphere, its surface spacing
     * 0.28): they receive no morphogen and push nothing. */
    for (uint32_t e = cl->nbr_off[c]; e < cl->nbr_off[c + 1]; e++) {
      double dl = 0;
      for (int a = 0; a < 3; a++) dl += pow(cl->pos[3 * cl->nbr[e] + a] - cl->pos[3 * c + a], 2);
      spacing += sqrt(dl) / (cl->nbr_off[c + 1] - cl->nbr_off[c]);
    }
    for (uint32_t e = cl->nbr_off[c]; e < cl->nbr_off[c + 1]; e++) {
      int nb = (int)cl->nbr[e];
      double d[3], dl = 0, cs = 0;
      for (int a = 0; a < 3; a++) d[a] = cl->pos[3 * nb + a] - cl->pos[3 * c + a], dl += d[a] * d[a];
      dl = sqrt(dl);
      if (!(dl > 0)) continue;
      for (int a = 0; a < 3; a++) cs += d[a] * q->inward[a] / dl;
      if (!surface[nb] && dl <= spacing && cs > best_in) best_in = cs, arg_in = nb;
      if (cs > best_any) best_any = cs;
    }
    if (arg_in >= 0 && best_in >= min_cos) {
      q->below = arg_in, q->split = -1, q->cosine = best_in;
    } else if (arg_in >= 0) {
      q->split = arg_in, q->cosine = best_in; /* divide it toward the tip */
    } else {
      q->split = c, q->cosine = best_any;     /* no interior neighbour: divide the tip inward */
    }
  }
  *out = t, *nout = n;
  return SESSILE_OK;
}
