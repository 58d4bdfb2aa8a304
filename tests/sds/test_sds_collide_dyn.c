/* SDS contacts in motion (docs/sds.md, "Collisions"): two bodies thrown at
 * each other do not interpenetrate (no surface self-intersection, checked
 * every 100 steps; with self-collision off the same throw does, so the
 * check can fail), the same run twice gives the same bytes; a ball dropped
 * under gravity onto three rocks (one obstacle mesh) comes to rest on them
 * with no cell inside a rock and the contact forces carrying its weight. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "collide_scenes.h"
#include "sessile/mesh/intersect.h"
#include "sessile/sds/sds.h"
#include "testutil.h"

static uint64_t intersections(const sessile_sds *o) {
  sessile_surface s = {.nv = o->ncells, .nf = o->nfaces, .pos = o->x, .tri = o->face};
  uint64_t n = 0;
  t_must("self-intersections", sessile_surface_self_intersections(&s, 0, NULL, &n));
  return n;
}

/* Throws two level-2 spheres at each other (1.5 u/s each) for `checks` x 20
 * steps; returns the most intersecting surface pairs seen at a check, the
 * final state in *o. */
static uint64_t throw_bodies(sessile_gpu *g, int self_collide, int checks, sessile_sds *o) {
  const double c0[3] = {-1.2, 0, 0}, c1[3] = {1.2, 0.05, 0.02};
  two_bodies(2, c0, c1, o);
  for (uint32_t c = 0; c < o->ncells; c++) o->v[3 * c] = o->x[3 * c] < 0 ? 1.5 : -1.5;
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.k_edge = 300, p.k_vol = 600, p.damp_visc = 0.5, p.gravity = 0; /* stiff bodies: docs/sds.md */
  p.self_collide = self_collide;
  sessile_sds_gpu *s = NULL;
  t_must("gpu", sessile_sds_gpu_create(g, o, &p, &s));
  double dt = p.dt, t = 0, gap = INFINITY; /* closest pair of cells across the two bodies, over the checks */
  uint64_t worst = 0;
  uint32_t half = o->ncells / 2;
  for (int k = 0; k < checks; k++) {
    t_must("advance", sessile_sds_gpu_advance(s, 20, &dt, &t));
    t_must("download", sessile_sds_gpu_download(s, o));
    uint64_t n = intersections(o);
    if (n > worst) worst = n;
    for (uint32_t a = 0; a < half; a++)
      for (uint32_t b = half; b < o->ncells; b++) {
        double d = 0;
        for (int i = 0; i < 3; i++) d += (o->x[3 * a + i] - o->x[3 * b + i]) * (o->x[3 * a + i] - o->x[3 * b + i]);
        gap = fmin(gap, sqrt(d));
      }
  }
  printf(
      "self_collide %d: %.3f s simulated, most intersecting pairs at a check %llu, closest cells across %.4f u "
      "(radius %.3f)\n",
      self_collide, t, (unsigned long long)worst, gap, o->r[0]);
  sessile_sds_gpu_destroy(s);
  return worst;
}

static void bodies(sessile_gpu *g) {
  sessile_sds a = {0}, b = {0}, c = {0};
  t_true("two bodies thrown together (self-collision on): 0 surface self-intersections at every check (every 20 steps)",
         throw_bodies(g, 1, 30, &a) == 0);
  throw_bodies(g, 1, 30, &b);
  t_true("the same run twice: identical bytes (x, v)",
         !memcmp(a.x, b.x, 3 * (size_t)a.ncells * 8) && !memcmp(a.v, b.v, 3 * (size_t)a.ncells * 8));
  t_true("control, self-collision off: the same throw interpenetrates", throw_bodies(g, 0, 30, &c) > 0);
  sessile_sds_free(&a), sessile_sds_free(&b), sessile_sds_free(&c);
}

/* A ball (level 2, radius 0.5) dropped into the pocket between three
 * rocks (icospheres of radius 1.5, centres 1.8 from the axis at z = -1.5):
 * without friction a ball on a single hump rolls off, here it settles. */
static void ball_on_rocks(sessile_gpu *g) {
  sessile_sds o = {0};
  sessile_surface rocks[3] = {{0}}, all = {0};
  const double ctr[3] = {0.01, 0.02, 0.8};
  t_must("ball", sessile_sds_from_icosphere(2, 0.5, ctr, 0, 0, 0, 1.0, &o));
  for (int k = 0; k < 3; k++) {
    const double rc[3] = {1.8 * cos(2.0944 * k), 1.8 * sin(2.0944 * k), -1.5};
    t_must("rock", sessile_surface_icosphere(3, 1.5, rc, &rocks[k]));
  }
  t_must("rocks", sessile_surface_reserve(&all, 3 * rocks[0].nv, 3 * rocks[0].nf));
  for (int k = 0; k < 3; k++) {
    memcpy(all.pos + 3 * (size_t)all.nv, rocks[k].pos, 3 * (size_t)rocks[k].nv * sizeof *all.pos);
    for (uint32_t i = 0; i < 3 * rocks[k].nf; i++) all.tri[3 * (size_t)all.nf + i] = rocks[k].tri[i] + all.nv;
    all.nv += rocks[k].nv, all.nf += rocks[k].nf;
  }
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.k_edge = 300, p.k_vol = 600, p.damp_visc = 4, p.damp_vol = 0.01, p.k_wall = 3000;
  p.obstacle.nv = all.nv, p.obstacle.nf = all.nf, p.obstacle.pos = all.pos, p.obstacle.tri = all.tri;
  sessile_sds_gpu *s = NULL;
  t_must("gpu", sessile_sds_gpu_create(g, &o, &p, &s));
  double dt = p.dt, t = 0;
  int inside = 0;
  for (int k = 0; k < 30; k++) {
    t_must("advance", sessile_sds_gpu_advance(s, 100, &dt, &t));
    t_must("download", sessile_sds_gpu_download(s, &o));
    for (uint32_t c = 0; c < o.ncells; c++)
      for (int r = 0; r < 3; r++) inside += inside_convex(&rocks[r], o.x + 3 * c);
  }
  double vmax = 0, zmin = INFINITY, support = 0, weight = 0;
  sessile_sds_params po = p;
  po.self_collide = 0;
  sessile_sds_contact *ct = t_xalloc(o.ncells * sizeof *ct);
  t_must("contacts", sessile_sds_contacts(&o, &po, ct));
  int touching = 0;
  for (uint32_t c = 0; c < o.ncells; c++) {
    const double *v = o.v + 3 * c;
    vmax = fmax(vmax, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    zmin = fmin(zmin, o.x[3 * c + 2]);
    double acc[3] = {0, 0, 0};
    sessile_sds_contact_accel(&o, &po, c, o.x + 3 * c, &ct[c], acc);
    support += o.m[c] * acc[2], weight += o.m[c] * p.gravity;
    touching += ct[c].obs >= 0;
  }
  printf("ball after %.3f s: lowest cell z %.4f, %d cells touching the rocks, fastest %.3g u/s\n", t, zmin, touching,
         vmax);
  t_true("no cell inside a rock at any check (every 100 steps)", inside == 0);
  /* undeformed, touching at the contact distance r: centre 1.5 + 0.5 + r from
   * each rock centre, lowest cell near z = -0.83; the ball squashes a little */
  t_true("the ball came down into the pocket: lowest cell z in (-1.3, -0.6)", zmin > -1.3 && zmin < -0.6);
  t_true("it touches all three rocks: at least 3 cells in contact", touching >= 3);
  t_check("at rest on them: vertical contact support = weight (rel)", fabs(support - weight) / weight, 1e-2);
  t_check("at rest: fastest cell speed, u/s", vmax, 1e-2);
  free(ct);
  sessile_sds_gpu_destroy(s);
  sessile_sds_free(&o);
  for (int k = 0; k < 3; k++) sessile_surface_free(&rocks[k]);
  sessile_surface_free(&all);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  bodies(g);
  ball_on_rocks(g);
  return t_finish(g);
}
