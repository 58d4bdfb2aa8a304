/* The particle sponge's state and one iteration (docs/sponge_particles.md):
 * spawn, fall, collide, feed (grow along normals with a Gaussian falloff),
 * guard the motion against self-intersection, remesh, carry the growth
 * counts over to the new vertices. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "particles_internal.h"
#include "sessile/mesh/intersect.h"
#include "sessile/rng.h"

/* Purpose of the particles' random stream (sessile_rng_stream). */
#define STREAM_SPAWN 0x5350574Eu

static sessile_status hemisphere(const sessile_sponge_particles_params *p, sessile_surface *s) {
  const double c[3] = {0, 0, 0};
  SESSILE_CALL(sessile_surface_icosphere(p->mesh_detail, p->radius, c, s));
  /* the lower half is flattened onto the substratum: a closed surface whose
   * base triangles face down (as `sessile grow` starts) */
  for (uint32_t v = 0; v < s->nv; v++)
    if (s->pos[3 * v + 2] < 0) s->pos[3 * v + 2] = 0;
  return SESSILE_OK;
}

void sessile_sponge_particles_destroy(sessile_sponge_particles *ps) {
  if (!ps) return;
  sessile_surface_free(&ps->surf);
  sessile_sponge_particles_gpu_destroy(ps->col);
  free(ps->counts);
  free(ps->ppos);
  free(ps->age);
  free(ps);
}

sessile_status sessile_sponge_particles_create(const sessile_sponge_particles_params *p, uint64_t seed, sessile_gpu *gpu,
                                      sessile_sponge_particles **out) {
  *out = NULL;
  SESSILE_CALL(sessile_params_check(&sessile_sponge_particles_param_table, p));
  sessile_sponge_particles *ps = calloc(1, sizeof *ps);
  SESSILE_CHECK(ps, SESSILE_ERR_NO_MEMORY, "out of host memory");
  ps->p = *p;
  ps->rng = sessile_rng_stream(seed, STREAM_SPAWN);
  sessile_status s = hemisphere(p, &ps->surf);
  if (s == SESSILE_OK) {
    ps->counts = calloc(ps->surf.nv, sizeof *ps->counts);
    if (!ps->counts) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  if (s == SESSILE_OK && p->collider == SESSILE_SPONGE_PARTICLES_COLLIDE_GPU) s = sessile_sponge_particles_gpu_create(gpu, &ps->col);
  if (s != SESSILE_OK) {
    sessile_sponge_particles_destroy(ps);
    return s;
  }
  *out = ps;
  return SESSILE_OK;
}

const sessile_surface *sessile_sponge_particles_surface(const sessile_sponge_particles *ps) { return &ps->surf; }
const uint32_t *sessile_sponge_particles_counts(const sessile_sponge_particles *ps) { return ps->counts; }
uint32_t sessile_sponge_particles_particles(const sessile_sponge_particles *ps) { return ps->np; }
int sessile_sponge_particles_iteration(const sessile_sponge_particles *ps) { return ps->iteration; }

sessile_status particles_reserve_particles(sessile_sponge_particles *ps, uint32_t n) {
  if (n <= ps->cap) return SESSILE_OK;
  uint32_t cap = n + n / 2 + 16;
  double *pp = realloc(ps->ppos, (size_t)cap * 3 * sizeof *pp);
  if (pp) ps->ppos = pp;
  uint32_t *ag = realloc(ps->age, (size_t)cap * sizeof *ag);
  if (ag) ps->age = ag;
  SESSILE_CHECK(pp && ag, SESSILE_ERR_NO_MEMORY, "out of host memory for %u particles", n);
  ps->cap = cap;
  return SESSILE_OK;
}

/* Spawn on the top face, fall (plus the current), age; the dead are dropped
 * keeping the others' order. */
static sessile_status move_particles(sessile_sponge_particles *ps, sessile_sponge_particles_iter_stats *st) {
  const sessile_sponge_particles_params *p = &ps->p;
  uint32_t n0 = ps->np, add = (uint32_t)p->nutrients_per_iteration;
  SESSILE_CALL(particles_reserve_particles(ps, n0 + add));
  double L = p->cube_size, half = L / 2;
  for (uint32_t i = n0; i < n0 + add; i++) {
    ps->ppos[3 * i] = sessile_rng_range(&ps->rng, -half, half);
    ps->ppos[3 * i + 1] = sessile_rng_range(&ps->rng, -half, half);
    ps->ppos[3 * i + 2] = L;
    ps->age[i] = 0;
  }
  const double v[3] = {p->current_x, p->current_y, p->current_z - p->fall_speed};
  uint32_t m = 0;
  for (uint32_t i = 0; i < n0 + add; i++) {
    double x[3];
    for (int a = 0; a < 3; a++) x[a] = ps->ppos[3 * i + a] + v[a];
    uint32_t age = ps->age[i] + 1;
    if (age > (uint32_t)p->nutrient_lifetime) {
      st->died_age++;
      continue;
    }
    if (!(x[0] >= -half && x[0] <= half && x[1] >= -half && x[1] <= half && x[2] >= 0 && x[2] <= L)) {
      st->died_outside++;
      continue;
    }
    memcpy(ps->ppos + 3 * m, x, sizeof x);
    ps->age[m++] = age;
  }
  ps->np = m;
  st->spawned = add;
  return SESSILE_OK;
}

/* hit/count for every live particle, by the chosen collider. */
static sessile_status collide(sessile_sponge_particles *ps, uint32_t **hit, uint32_t **count) {
  const sessile_sponge_particles_params *p = &ps->p;
  uint32_t np = ps->np, feed = (uint32_t)p->particle_feed;
  *hit = malloc(((size_t)np * feed + 1) * sizeof **hit);
  *count = malloc(((size_t)np + 1) * sizeof **count);
  float *part4 = malloc(((size_t)np * 4 + 4) * sizeof *part4);
  sessile_sponge_particles_grid g;
  sessile_status s = *hit && *count && part4 ? SESSILE_OK
                                             : sessile_error_set(SESSILE_ERR_NO_MEMORY,
                                                                 "out of host memory for %u particles", np);
  if (s == SESSILE_OK) {
    for (uint32_t i = 0; i < np; i++) {
      for (int a = 0; a < 3; a++) part4[4 * (size_t)i + a] = (float)ps->ppos[3 * (size_t)i + a];
      part4[4 * (size_t)i + 3] = 0;
    }
    s = sessile_sponge_particles_grid_build(ps->surf.pos, ps->surf.nv, p->nutrient_radius, &g);
  }
  if (s == SESSILE_OK) {
    float r = (float)p->nutrient_radius;
    if (ps->col) s = sessile_sponge_particles_gpu_collide(ps->col, &g, part4, np, r, feed, *hit, *count, NULL);
    else s = sessile_sponge_particles_collide_grid(&g, part4, np, r, feed, *hit, *count);
    sessile_sponge_particles_grid_free(&g);
  }
  free(part4);
  return s;
}

/* Mean length of the edges at each vertex. */
static void mean_edges(const sessile_surface *s, const uint32_t *off, const uint32_t *nbr, double *len) {
  for (uint32_t v = 0; v < s->nv; v++) {
    double sum = 0;
    for (uint32_t e = off[v]; e < off[v + 1]; e++) {
      const double *a = s->pos + 3 * v, *b = s->pos + 3 * nbr[e];
      sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    len[v] = off[v + 1] > off[v] ? sum / (off[v + 1] - off[v]) : 0;
  }
}

/* Feeds the hits in (particle, vertex) order: the fed vertex moves along its
 * normal by growth_fraction times its mean edge length, every vertex within
 * feeding_iterations rings by that times exp(-d^2 / (2 sigma^2)), d its
 * Euclidean distance to the fed vertex (all at the iteration's start). */
static sessile_status feed(sessile_sponge_particles *ps, const uint32_t *hit, const uint32_t *count, double *disp,
                           sessile_sponge_particles_iter_stats *st) {
  const sessile_sponge_particles_params *p = &ps->p;
  const sessile_surface *s = &ps->surf;
  uint32_t nv = s->nv, fd = (uint32_t)p->particle_feed, *off = NULL, *nbr = NULL;
  SESSILE_CALL(sessile_surface_vertex_neighbours(s, &off, &nbr));
  double *n = malloc((size_t)nv * 3 * sizeof *n), *len = malloc((size_t)nv * sizeof *len);
  uint32_t *stamp = calloc(nv, sizeof *stamp), *queue = malloc((size_t)nv * sizeof *queue);
  uint8_t *fed = calloc(nv, 1);
  sessile_status r = SESSILE_OK;
  if (!n || !len || !stamp || !queue || !fed) {
    r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv);
    goto done;
  }
  sessile_surface_normals(s, n);
  mean_edges(s, off, nbr, len);
  memset(disp, 0, (size_t)nv * 3 * sizeof *disp);
  double inv2s2 = 1 / (2 * p->falloff_sigma * p->falloff_sigma);
  uint32_t tag = 0;
  for (uint32_t i = 0; i < ps->np; i++) {
    uint32_t k_end = count[i] < fd ? count[i] : fd;
    for (uint32_t k = 0; k < k_end; k++) {
      uint32_t v = hit[(size_t)fd * i + k];
      double d0 = p->growth_fraction * len[v];
      const double *xv = s->pos + 3 * v;
      ps->counts[v]++;
      st->hits++;
      fed[v] = 1;
      /* breadth-first over the rings, neighbours ascending */
      tag++;
      uint32_t head = 0, tail = 0, ring_end;
      queue[tail++] = v;
      stamp[v] = tag;
      for (int ring = 0; ring <= p->feeding_iterations; ring++) {
        ring_end = tail;
        for (; head < ring_end; head++) {
          uint32_t u = queue[head];
          const double *xu = s->pos + 3 * u;
          double d2 = (xu[0] - xv[0]) * (xu[0] - xv[0]) + (xu[1] - xv[1]) * (xu[1] - xv[1]) +
                      (xu[2] - xv[2]) * (xu[2] - xv[2]);
          double g = d0 * exp(-d2 * inv2s2);
          for (int a = 0; a < 3; a++) disp[3 * u + a] += g * n[3 * u + a];
          if (ring == p->feeding_iterations) continue;
          for (uint32_t e = off[u]; e < off[u + 1]; e++)
            if (stamp[nbr[e]] != tag) stamp[nbr[e]] = tag, queue[tail++] = nbr[e];
        }
      }
    }
  }
  for (uint32_t v = 0; v < nv; v++) st->fed_vertices += fed[v];
done:
  free(off), free(nbr), free(n), free(len), free(stamp), free(queue), free(fed);
  return r;
}

/* Drops fed particles (they die on their first contact). */
static void consume(sessile_sponge_particles *ps, const uint32_t *count, sessile_sponge_particles_iter_stats *st) {
  uint32_t m = 0;
  for (uint32_t i = 0; i < ps->np; i++) {
    if (count[i]) {
      st->died_fed++;
      continue;
    }
    memcpy(ps->ppos + 3 * m, ps->ppos + 3 * i, 3 * sizeof *ps->ppos);
    ps->age[m++] = ps->age[i];
  }
  ps->np = m;
}

/* Proposed positions: base vertices (on z = 0) stay on it, moving in the
 * plane; everything stays in the cube. */
static void propose(const sessile_sponge_particles *ps, const double *disp, double *np_) {
  double half = ps->p.cube_size / 2, L = ps->p.cube_size;
  for (uint32_t v = 0; v < ps->surf.nv; v++) {
    const double *x = ps->surf.pos + 3 * v;
    double y[3] = {x[0] + disp[3 * v], x[1] + disp[3 * v + 1], x[2] + disp[3 * v + 2]};
    if (x[2] <= 0) y[2] = 0;
    for (int a = 0; a < 2; a++) y[a] = y[a] < -half ? -half : y[a] > half ? half : y[a];
    y[2] = y[2] < 0 ? 0 : y[2] > L ? L : y[2];
    memcpy(np_ + 3 * v, y, sizeof y);
  }
}

sessile_status sessile_sponge_particles_step(sessile_sponge_particles *ps, sessile_sponge_particles_iter_stats *st) {
  memset(st, 0, sizeof *st);
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(move_particles(ps, st));
  uint32_t *hit = NULL, *count = NULL;
  double *disp = NULL, *np_ = NULL;
  sessile_status s = collide(ps, &hit, &count);
  double t1 = sessile_wall_seconds();
  uint32_t nv = ps->surf.nv;
  if (s == SESSILE_OK) {
    disp = malloc((size_t)nv * 3 * sizeof *disp);
    np_ = malloc((size_t)nv * 3 * sizeof *np_);
    if (!disp || !np_) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv);
  }
  if (s == SESSILE_OK) s = feed(ps, hit, count, disp, st);
  if (s == SESSILE_OK) {
    consume(ps, count, st);
    propose(ps, disp, np_);
    sessile_guard_stats gs;
    s = sessile_surface_guard_motion(&ps->surf, np_, 1, &gs);
    st->held_back = gs.held_back;
  }
  if (s == SESSILE_OK) memcpy(ps->surf.pos, np_, (size_t)nv * 3 * sizeof *np_);
  double t2 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = particles_remesh(ps, &st->remesh_refused);
  free(hit), free(count), free(disp), free(np_);
  SESSILE_CALL(s);
  ps->iteration++;
  st->alive = ps->np;
  st->nv = ps->surf.nv;
  st->nf = ps->surf.nf;
  st->collide_s = t1 - t0;
  st->grow_s = t2 - t1;
  st->remesh_s = sessile_wall_seconds() - t2;
  SESSILE_CHECK(ps->surf.nv <= (uint32_t)ps->p.max_vertices, SESSILE_ERR_TOO_LARGE,
                "iteration %d: the sponge has %u vertices, more than max_vertices = %d; raise it or "
                "the splitting_threshold", ps->iteration, ps->surf.nv, ps->p.max_vertices);
  return SESSILE_OK;
}
