/* Many divisions in a row (random cells and directions from a fixed seed):
 * every one succeeds (no Steiner point needed), the complex stays valid with
 * its volume; prints the time per division and per check against the size.
 * Arguments (optional): icosphere level, divisions, TetGen volume cap. */
#include "sessile/rng.h"
#include "test_topo_fixture.h"

int main(int argc, char **argv) {
  int level = argc > 1 ? atoi(argv[1]) : 2, ndiv = argc > 2 ? atoi(argv[2]) : 1000;
  double cap = argc > 3 ? atof(argv[3]) : 0.02;
  sessile_sds_topo_complex cx = {0};
  fx_ball(level, cap, &cx);
  double v0 = fx_volume(&cx);
  printf("ball level %d, volume cap %g: %u vertices, %u tets\n", level, cap, cx.nv, cx.nt);
  uint64_t rng = sessile_rng_stream(7, 3);
  int refused = 0, invalid = 0, fallback = 0, apart = 0;
  double tdiv = 0, tchk = 0, worst = 0;
  for (int k = 0; k < ndiv && !invalid; k++) {
    uint32_t c = (uint32_t)(sessile_rng_uniform(&rng) * cx.nv) % cx.nv;
    double d[3] = {sessile_rng_normal(&rng), sessile_rng_normal(&rng), sessile_rng_normal(&rng)};
    sessile_sds_topo_division div;
    double t0 = fx_now();
    sessile_status st = sessile_sds_topo_divide(&cx, c, d, 0, &div);
    tdiv += fx_now() - t0;
    if (st != SESSILE_OK) {
      refused++;
      printf("  division %d of cell %u refused: %s\n", k, c, sessile_error_message());
      continue;
    }
    fallback += div.fallback;
    int adjacent = 0;
    for (uint32_t t = 0; t < cx.nt && !adjacent; t++) {
      const uint32_t *v = cx.tet + 4 * t;
      adjacent = (v[0] == div.a || v[1] == div.a || v[2] == div.a || v[3] == div.a) &&
                 (v[0] == div.b || v[1] == div.b || v[2] == div.b || v[3] == div.b);
    }
    apart += !adjacent;
    free(div.tet_from);
    sessile_sds_topo_report rep;
    t0 = fx_now();
    st = sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0, &rep);
    tchk += fx_now() - t0;
    if (st != SESSILE_OK) printf("  invalid after division %d: %s\n", k, sessile_error_message()), invalid = 1;
    worst = fmax(worst, fabs(rep.volume - v0) / v0);
  }
  printf(
      "%d divisions: %d daughters apart, %d refused, %d by the cone fallback; %.3f ms per division, %.3f ms per check; "
      "now %u vertices, %u tets\n",
      ndiv, apart, refused, fallback, 1e3 * tdiv / ndiv, 1e3 * tchk / ndiv, cx.nv, cx.nt);
  t_true("every division valid", !invalid);
  t_true("no division refused", refused == 0);
  t_true("the daughters are neighbours after every division", apart == 0);
  t_check("volume after every division (rel)", worst, 1e-12);
  sessile_sds_topo_complex_free(&cx);
  return t_finish(NULL);
}
