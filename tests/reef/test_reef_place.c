/* Placement (docs/reef.md, "Placement"; Coralize §4.1): no overlaps, bases
 * on the seabed, depths in band, up axis = terrain normal, the random bias
 * by a chi-square test, the same seed the same placements. */
#include <math.h>
#include <stdio.h>
#include "reef_test_scene.h"

static const char *scene_json =
    "{\"seabed\": {\"noise\": {\"seed\": 3, \"resolution\": [65, 49], \"extent\": [40, 30], \"height_scale\": 4,"
    " \"base\": -8, \"wavelength\": 9, \"octaves\": 3}}, \"sea_level\": 0,"
    " \"pool\": [{\"name\": \"a\", \"generator\": \"sphere\", \"bias\": 30, \"size\": [0.2, 0.5], \"depth\": [5, 9]},"
    "  {\"name\": \"b\", \"generator\": \"sphere\", \"bias\": 70, \"size\": [0.3, 0.4], \"follow_terrain\": false,"
    "   \"rotate\": [\"x\", \"z\"]}],"
    " \"brushes\": [{\"points\": [[5, 5], [35, 25], [35, 5]], \"size\": 4, \"density\": 2, \"density_unit\": \"per_m2\"}]}";

static void geometry(void) {
  sessile_reef_scene s;
  sessile_reef_seabed b;
  sessile_reef_placements pl, again;
  rt_parse(scene_json, &s);
  t_must("seabed", sessile_reef_seabed_make(&s, &b));
  t_must("place", sessile_reef_place(&s, &b, 42, &pl));
  t_true("placed a few hundred organisms", pl.n > 200);
  double overlap = 0, herr = 0, band = 0, angle = 0, upright = 0;
  for (uint32_t i = 0; i < pl.n; i++) {
    const sessile_reef_placement *p = &pl.p[i];
    const sessile_reef_entry *e = &s.entries[p->entry];
    for (uint32_t j = i + 1; j < pl.n; j++) {
      double d = hypot(p->pos[0] - pl.p[j].pos[0], p->pos[1] - pl.p[j].pos[1]);
      overlap = fmax(overlap, p->size + pl.p[j].size - d);
    }
    herr = fmax(herr, fabs(p->pos[2] - rt_height(&b, p->pos[0], p->pos[1])));
    double depth = s.sea_level - p->pos[2];
    if (depth < e->depth[0] || depth > e->depth[1] || fabs(depth - p->depth) > 1e-12) band++;
    double eps = 1e-6, x = p->pos[0], y = p->pos[1];
    double zx = (rt_height(&b, x + eps, y) - rt_height(&b, x - eps, y)) / (2 * eps);
    double zy = (rt_height(&b, x, y + eps) - rt_height(&b, x, y - eps)) / (2 * eps);
    double l = sqrt(zx * zx + zy * zy + 1), n[3] = {-zx / l, -zy / l, 1 / l};
    double c = p->up[0] * n[0] + p->up[1] * n[1] + p->up[2] * n[2];
    if (e->follow_terrain) angle = fmax(angle, acos(fmin(1, c)) * 180 / 3.141592653589793);
    else upright = fmax(upright, fabs(p->up[2] - 1) + fabs(p->up[0]) + fabs(p->up[1]));
    if (!e->rotate[1] && p->angle[1] != 0) upright = 1;
  }
  t_true("no two footprints overlap", overlap <= 0);
  t_check("base height error (m)", herr, 1e-4);
  t_check("placements outside their depth band", band, 0);
  t_check("terrain-following up axis vs normal (degrees)", angle, 1);
  t_check("upright entries: up = +z, unrotated axes stay 0", upright, 0);
  t_must("place again", sessile_reef_place(&s, &b, 42, &again));
  t_true("same seed, same placements", again.n == pl.n && !memcmp(again.p, pl.p, pl.n * sizeof *pl.p));
  sessile_reef_placements_free(&again);
  t_must("another seed", sessile_reef_place(&s, &b, 43, &again));
  t_true("another seed, other placements", again.n != pl.n || memcmp(again.p, pl.p, pl.n * sizeof *pl.p));
  sessile_reef_placements_free(&again), sessile_reef_placements_free(&pl);
  sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);
}

/* 10 000 candidates on a flat seabed, tiny footprints: the entries' counts
 * against the bias weights 20 : 30 : 50 (chi-square, 2 degrees of freedom,
 * 13.8 is the 0.999 quantile). */
static void bias(void) {
  const char *json =
      "{\"seabed\": {\"noise\": {\"resolution\": [3, 3], \"extent\": [100, 100], \"height_scale\": 0, \"base\": -5}},"
      " \"pool\": [{\"name\": \"a\", \"generator\": \"g\", \"bias\": 20, \"size\": [0.001, 0.001]},"
      "  {\"name\": \"b\", \"generator\": \"g\", \"bias\": 30, \"size\": [0.001, 0.001]},"
      "  {\"name\": \"c\", \"generator\": \"g\", \"bias\": 50, \"size\": [0.001, 0.001]}],"
      " \"brushes\": [{\"points\": [[50, 50]], \"size\": 49, \"density\": 10000}]}";
  sessile_reef_scene s;
  sessile_reef_seabed b;
  sessile_reef_placements pl;
  rt_parse(json, &s);
  t_must("seabed", sessile_reef_seabed_make(&s, &b));
  t_must("place", sessile_reef_place(&s, &b, 7, &pl));
  double count[3] = {0}, w[3] = {0.2, 0.3, 0.5}, chi2 = 0;
  for (uint32_t i = 0; i < pl.n; i++) count[pl.p[i].entry]++;
  for (int k = 0; k < 3; k++) chi2 += (count[k] - pl.n * w[k]) * (count[k] - pl.n * w[k]) / (pl.n * w[k]);
  printf("bias: %u placed, counts %.0f %.0f %.0f, chi2 %.3f\n", pl.n, count[0], count[1], count[2], chi2);
  t_true("nearly all 10 000 candidates placed", pl.n >= 9990);
  t_check("chi-square of the random bias (2 dof, p = 0.001)", chi2, 13.8);
  sessile_reef_placements_free(&pl), sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);
}

int main(void) {
  geometry();
  bias();
  return t_finish(NULL);
}
