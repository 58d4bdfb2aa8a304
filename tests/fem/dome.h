/* The nutrient tests' shared pieces: a random stream, a vector from host
 * values, and the dome below.
 *
 * A dome (an icosphere flattened onto the substratum) centred in a
 * 16 x 16 x 12-cell box of 1.2 cm at resolution 2, c = 1 at the box top,
 * classified on every level of a cut-cell nutrient: the sponge's start, for
 * the nutrient tests. */
#ifndef SESSILE_TEST_DOME_H
#define SESSILE_TEST_DOME_H

#include "sessile/growth/growth_gpu.h"
#include "sessile/fem/nutrient_cut.h"
#include "testutil.h"

static uint64_t rng = 88172645463325252ull;
static inline double urand(void) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return (double)(rng >> 11) / 9007199254740992.0;
}

static inline sessile_vec *t_vec_of(sessile_la *la, const double *x, uint32_t n) {
  sessile_vec *v;
  t_must("vec", sessile_vec_create(la, n, &v));
  t_must("upload", sessile_vec_upload(v, x));
  return v;
}

typedef struct {
  sessile_box b;
  sessile_cut_nutrient *nt;
  sessile_growth_gpu *gg;
  sessile_surface s;
} t_dome;

static inline const char *t_far_name(sessile_far_field ff) {
  return ff == SESSILE_FAR_FIELD_WALLS     ? "walls"
         : ff == SESSILE_FAR_FIELD_INLET   ? "inlet"
         : ff == SESSILE_FAR_FIELD_PROFILE ? "profile"
                                           : "height";
}

static inline void t_dome_make_far(sessile_la *la, double radius, sessile_far_field ff, t_dome *d) {
  const double o[3] = {0, 0, 0}, c0[3] = {9.6, 9.6, 0};
  const uint32_t cells[3] = {16, 16, 12};
  t_must("box", sessile_box_make(o, 1.2, cells, 2, &d->b));
  sessile_cut_bc bc;
  sessile_cut_bc_default(&bc);
  bc.far_field = ff;
  bc.height = 1.2 * 12;
  t_must("create", sessile_cut_nutrient_create(la, &d->b, &bc, 12, &d->nt));
  t_must("growth", sessile_growth_gpu_create(la, &d->gg));
  d->s = (sessile_surface){0};
  t_must("icosphere", sessile_surface_icosphere(4, radius, c0, &d->s));
  for (uint32_t v = 0; v < d->s.nv; v++)
    if (d->s.pos[3 * v + 2] < 0) d->s.pos[3 * v + 2] = 0;
  t_must("surface", sessile_growth_gpu_set_surface(d->gg, &d->s));
  for (int l = 0; l < sessile_cut_nutrient_levels(d->nt); l++) {
    sessile_box lb;
    sessile_buffer *sb, *tb;
    sessile_cut_nutrient_level(d->nt, l, &lb, &sb, &tb);
    t_must("cut", sessile_growth_gpu_cut(d->gg, &lb, sb, tb));
  }
}

static inline void t_dome_make(sessile_la *la, double radius, t_dome *d) {
  t_dome_make_far(la, radius, SESSILE_FAR_FIELD_HEIGHT, d);
}

static inline void t_dome_free(t_dome *d) {
  sessile_surface_free(&d->s);
  sessile_growth_gpu_destroy(d->gg);
  sessile_cut_nutrient_destroy(d->nt);
}

#endif
