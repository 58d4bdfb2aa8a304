/* The particle sponge's iterations: after every one of 100 (small mesh
 * detail, GPU collisions) the surface is a closed, consistently oriented
 * 2-manifold (sessile_surface_check, Euler characteristic 2) without
 * self-intersection (sessile_surface_self_intersections); it grew (volume,
 * height) and stayed on the substratum and in the cube; the same seed gives
 * the same bytes, another seed others, and the host collider the GPU's bytes.
 * --fine (label slow): the 100 checked iterations at the default mesh
 * detail with thresholds 0.12 / 0.05 cm (about 30 s here). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/intersect.h"
#include "sessile/sponge/particles.h"
#include "testutil.h"

static int fine;

static void params(sessile_sponge_particles_params *p, int collider) {
  sessile_params_defaults(&sessile_sponge_particles_param_table, p);
  if (fine) {
    p->splitting_threshold = 0.12;
    p->collapse_threshold = 0.05;
  } else {
    p->mesh_detail = 3;
    p->nutrients_per_iteration = 150;
  }
  p->collider = collider;
}

/* Runs n iterations; checks the invariants after each when check is set. */
static sessile_sponge_particles *run(sessile_gpu *gpu, int collider, uint64_t seed, int n, int check) {
  sessile_sponge_particles_params p;
  params(&p, collider);
  sessile_sponge_particles *ps = NULL;
  t_must("create", sessile_sponge_particles_create(&p, seed, gpu, &ps));
  int broken = 0, crossing = 0, outside = 0, first_bad = 0;
  uint64_t hits = 0;
  for (int it = 1; it <= n; it++) {
    sessile_sponge_particles_iter_stats st;
    t_must("step", sessile_sponge_particles_step(ps, &st));
    hits += st.hits;
    if (!check) continue;
    const sessile_surface *s = sessile_sponge_particles_surface(ps);
    if (sessile_surface_check(s, 2, 0.0) != SESSILE_OK) {
      if (!broken++) printf("iteration %d: %s\n", it, sessile_error_message());
      first_bad = first_bad ? first_bad : it;
    }
    uint64_t x = 0;
    t_must("self-intersections", sessile_surface_self_intersections(s, 0, NULL, &x));
    if (x) crossing++, first_bad = first_bad ? first_bad : it;
    for (uint32_t v = 0; v < s->nv; v++) {
      const double *q = s->pos + 3 * v;
      outside += q[2] < 0 || q[2] > p.cube_size || fabs(q[0]) > p.cube_size / 2 || fabs(q[1]) > p.cube_size / 2;
    }
  }
  if (check) {
    char what[160];
    snprintf(what, sizeof what, "%d iterations (%llu feedings): iterations whose surface fails the closed "
             "2-manifold check (first bad %d)", n, (unsigned long long)hits, first_bad);
    t_check(what, broken, 0);
    t_check("... iterations with self-intersecting triangle pairs", crossing, 0);
    t_check("... vertices below the substratum or outside the cube (summed over iterations)", outside, 0);
    t_true("... particles fed the sponge", hits > 1000);
  }
  return ps;
}

static int same_surface(const sessile_sponge_particles *a, const sessile_sponge_particles *b) {
  const sessile_surface *s = sessile_sponge_particles_surface(a), *t = sessile_sponge_particles_surface(b);
  return s->nv == t->nv && s->nf == t->nf && !memcmp(s->pos, t->pos, (size_t)24 * s->nv) &&
         !memcmp(s->tri, t->tri, (size_t)12 * s->nf) &&
         !memcmp(sessile_sponge_particles_counts(a), sessile_sponge_particles_counts(b), (size_t)4 * s->nv);
}

int main(int argc, char **argv) {
  fine = argc > 1 && !strcmp(argv[1], "--fine");
  sessile_gpu *gpu = t_gpu(0);
  if (fine) {
    sessile_sponge_particles_destroy(run(gpu, SESSILE_SPONGE_PARTICLES_COLLIDE_GPU, 3, 100, 1));
    return t_finish(gpu);
  }
  sessile_sponge_particles_params p;
  params(&p, 0);
  sessile_sponge_particles *start = NULL;
  t_must("create", sessile_sponge_particles_create(&p, 1, gpu, &start));
  sessile_surface_stats s0, s1;
  sessile_surface_stats_of(sessile_sponge_particles_surface(start), &s0);
  /* a hemisphere of radius 1 from an icosphere: volume near 2 pi / 3 */
  t_check("the starting hemisphere's volume against 2 pi / 3 (relative)", fabs(s0.volume / (2.0943951023931957) - 1), 0.1);
  t_true("... a closed 2-manifold", sessile_surface_check(sessile_sponge_particles_surface(start), 2, 0.0) == SESSILE_OK);
  sessile_sponge_particles_destroy(start);

  sessile_sponge_particles *a = run(gpu, SESSILE_SPONGE_PARTICLES_COLLIDE_GPU, 7, 100, 1);
  sessile_surface_stats_of(sessile_sponge_particles_surface(a), &s1);
  printf("after 100 iterations: %u vertices, volume %.3f cm^3 (from %.3f), height %.3f cm\n", s1.nv, s1.volume,
         s0.volume, s1.bbox_max[2]);
  t_true("the sponge grew: volume and height up by over 20 %", s1.volume > 1.2 * s0.volume && s1.bbox_max[2] > 1.2);
  uint64_t fed = 0;
  for (uint32_t v = 0; v < s1.nv; v++) fed += sessile_sponge_particles_counts(a)[v];
  t_true("... and its vertices carry growth counts", fed > 0);

  sessile_sponge_particles *b = run(gpu, SESSILE_SPONGE_PARTICLES_COLLIDE_GPU, 7, 40, 0);
  sessile_sponge_particles *c = run(gpu, SESSILE_SPONGE_PARTICLES_COLLIDE_GPU, 7, 40, 0);
  sessile_sponge_particles *d = run(gpu, SESSILE_SPONGE_PARTICLES_COLLIDE_GPU, 8, 40, 0);
  sessile_sponge_particles *e = run(NULL, SESSILE_SPONGE_PARTICLES_COLLIDE_HOST, 7, 40, 0);
  t_true("the same seed gives the same bytes (positions, triangles, counts)", same_surface(b, c));
  t_true("another seed gives another sponge", !same_surface(b, d));
  t_true("the host collider gives the GPU's bytes", same_surface(b, e));
  sessile_sponge_particles_destroy(a), sessile_sponge_particles_destroy(b), sessile_sponge_particles_destroy(c);
  sessile_sponge_particles_destroy(d), sessile_sponge_particles_destroy(e);
  return t_finish(gpu);
}
