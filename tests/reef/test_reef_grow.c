/* Reef growth (docs/reef.md, "Growth"; Coralize §4.2): on a flat seabed
 * from two organisms, the occupied cells after k steps equal the cells
 * within Manhattan distance k of either (computed here independently); the
 * result does not depend on the organisms' order; on a ramp that crosses
 * the depth band nothing grows outside it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "reef_test_scene.h"

static double flat(double x, double y) { return -5 + 0 * x * y; }
static double ramp(double x, double y) { return -x + 0 * y; }

static const char *json =
    "{\"seabed\": {\"noise\": {\"extent\": [20, 20]}},"
    " \"pool\": [{\"name\": \"a\", \"generator\": \"g\", \"size\": [0.3, 0.3], \"depth\": [2, 8]},"
    "  {\"name\": \"b\", \"generator\": \"g\", \"size\": [0.3, 0.3], \"depth\": [2, 8]}],"
    " \"brushes\": [{\"points\": [[1, 1]]}], \"growth\": {\"steps\": 6, \"spacing\": 1}}";

static void two(sessile_reef_placements *pl, int swap) {
  pl->n = pl->cap = 2;
  pl->p = calloc(2, sizeof *pl->p);
  const double at[2][2] = {{5, 5}, {12, 9}};
  for (int k = 0; k < 2; k++) {
    sessile_reef_placement *p = &pl->p[swap ? 1 - k : k];
    p->entry = (uint32_t)k, p->seed = 1000 + (uint64_t)k, p->size = 0.3, p->pos[0] = at[k][0], p->pos[1] = at[k][1];
    p->pos[2] = -5, p->up[2] = 1, p->depth = 5;
  }
}

static int cmp_place(const void *pa, const void *pb) {
  const sessile_reef_placement *a = pa, *b = pb;
  if (a->pos[1] != b->pos[1]) return a->pos[1] < b->pos[1] ? -1 : 1;
  return a->pos[0] < b->pos[0] ? -1 : a->pos[0] > b->pos[0];
}

static void territories(void) {
  sessile_reef_scene s;
  sessile_reef_seabed b;
  rt_parse(json, &s);
  rt_seabed(&b, 21, 21, 20, 20, flat);
  sessile_reef_placements pl, sw;
  two(&pl, 0), two(&sw, 1);
  for (int k = 1; k <= 6; k++) {
    uint32_t added;
    t_must("grow", sessile_reef_grow_step(&s, &b, k, &pl, &added));
    t_must("grow swapped", sessile_reef_grow_step(&s, &b, k, &sw, &added));
    /* the rule, independently: lattice cells within distance k of a seed */
    int want = 0, wrong = 0, owner = 0;
    for (int y = 0; y <= 20; y++)
      for (int x = 0; x <= 20; x++) {
        int da = abs(x - 5) + abs(y - 5), db = abs(x - 12) + abs(y - 9), in = da <= k || db <= k, found = -1;
        want += in;
        for (uint32_t i = 0; i < pl.n; i++)
          if (pl.p[i].pos[0] == x && pl.p[i].pos[1] == y) found = (int)pl.p[i].entry;
        wrong += in != (found >= 0);
        if (found >= 0 && da != db) owner += found != (da < db ? 0 : 1);
      }
    printf("step %d: %u organisms, %d cells expected\n", k, pl.n, want);
    t_check("cells that differ from the cardinal-neighbour rule", wrong, 0);
    t_true("as many organisms as cells", (int)pl.n == want);
    t_check("cells nearer one seed owned by the other", owner, 0);
    qsort(pl.p, pl.n, sizeof *pl.p, cmp_place), qsort(sw.p, sw.n, sizeof *sw.p, cmp_place);
    t_true("the order of the organisms does not change the step",
           pl.n == sw.n && !memcmp(pl.p, sw.p, pl.n * sizeof *pl.p));
  }
  sessile_reef_placements_free(&pl), sessile_reef_placements_free(&sw);
  sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);
}

static void band(void) {
  sessile_reef_scene s;
  sessile_reef_seabed b;
  rt_parse(json, &s);
  rt_seabed(&b, 21, 21, 20, 20, ramp);
  sessile_reef_placements pl;
  two(&pl, 0);
  pl.n = 1, pl.p[0].pos[2] = -5; /* at x = 5 on z = -x: depth 5 */
  for (int k = 1; k <= 10; k++) {
    uint32_t added;
    t_must("grow", sessile_reef_grow_step(&s, &b, k, &pl, &added));
  }
  double out = 0;
  for (uint32_t i = 0; i < pl.n; i++) out += pl.p[i].depth < 2 || pl.p[i].depth > 8 || -pl.p[i].pos[2] != pl.p[i].depth;
  printf("ramp: %u organisms\n", pl.n);
  t_true("it grew", pl.n > 20);
  t_check("organisms outside the depth band [2, 8] m", out, 0);
  sessile_reef_placements_free(&pl), sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);
}

int main(void) {
  territories();
  band();
  return t_finish(NULL);
}
