/* `sessile sponge particles` on the run framework: configuration for
 * resume, checkpoint sections, records, snapshots and the final meshes
 * (sessile/sponge/particles.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "particles_internal.h"
#include "sessile/run/generator.h"
#include "sessile/mesh/intersect.h"
#include "sessile/io/io.h"

/* The generator's state: the sponge and what writes it. */
typedef struct particles_gen {
  sessile_sponge_particles *ps;
  sessile_run *run;
  int check; /* --check: the invariants every iteration */
} particles_gen;

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  const sessile_sponge_particles *ps = ((particles_gen *)state)->ps;
  const sessile_surface *s = &ps->surf;
  sec[0] = (sessile_ckpt_section){"rng", &ps->rng, sizeof ps->rng};
  sec[1] = (sessile_ckpt_section){"positions", s->pos, (size_t)3 * s->nv * sizeof *s->pos};
  sec[2] = (sessile_ckpt_section){"triangles", s->tri, (size_t)3 * s->nf * sizeof *s->tri};
  sec[3] = (sessile_ckpt_section){"growth_counts", ps->counts, (size_t)s->nv * sizeof *ps->counts};
  sec[4] = (sessile_ckpt_section){"particles", ps->ppos, (size_t)3 * ps->np * sizeof *ps->ppos};
  sec[5] = (sessile_ckpt_section){"ages", ps->age, (size_t)ps->np * sizeof *ps->age};
  *n = 6;
  return SESSILE_OK;
}

sessile_status sessile_sponge_particles_restore(sessile_sponge_particles *ps, const sessile_ckpt *ck) {
  size_t nr = 0, npos = 0, ntri = 0, ncnt = 0, npart = 0, nage = 0;
  const void *r = sessile_ckpt_get(ck, "rng", &nr), *pos = sessile_ckpt_get(ck, "positions", &npos);
  const void *tri = sessile_ckpt_get(ck, "triangles", &ntri), *cnt = sessile_ckpt_get(ck, "growth_counts", &ncnt);
  const void *part = sessile_ckpt_get(ck, "particles", &npart), *age = sessile_ckpt_get(ck, "ages", &nage);
  size_t nv = npos / (3 * sizeof(double)), nf = ntri / (3 * sizeof(uint32_t)), np = npart / (3 * sizeof(double));
  SESSILE_CHECK(r && pos && tri && cnt && part && age && nr == sizeof ps->rng && npos % 24 == 0 &&
                    ntri % 12 == 0 && npart % 24 == 0 && ncnt == nv * 4 && nage == np * 4 &&
                    nv <= UINT32_MAX && nf <= UINT32_MAX && np <= UINT32_MAX,
                SESSILE_ERR_IO, "the checkpoint's particle-sponge sections are damaged");
  sessile_surface s = {0};
  SESSILE_CALL(sessile_surface_reserve(&s, (uint32_t)nv, (uint32_t)nf));
  s.nv = (uint32_t)nv, s.nf = (uint32_t)nf;
  memcpy(s.pos, pos, npos);
  memcpy(s.tri, tri, ntri);
  sessile_status st = sessile_surface_check(&s, 2, 0.0);
  uint32_t *counts = st == SESSILE_OK ? malloc(ncnt + 4) : NULL;
  if (st == SESSILE_OK && !counts) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (st == SESSILE_OK) st = particles_reserve_particles(ps, (uint32_t)np);
  if (st != SESSILE_OK) {
    sessile_surface_free(&s);
    free(counts);
    return sessile_error_set(st, "the checkpoint's surface: %s", sessile_error_message());
  }
  memcpy(counts, cnt, ncnt);
  sessile_surface_free(&ps->surf);
  ps->surf = s;
  free(ps->counts);
  ps->counts = counts;
  memcpy(ps->ppos, part, npart);
  memcpy(ps->age, age, nage);
  ps->np = (uint32_t)np;
  memcpy(&ps->rng, r, nr);
  ps->iteration = sessile_ckpt_iteration(ck);
  return SESSILE_OK;
}

/* PLY with the per-vertex growth count, or OBJ, by rel's suffix. */
static sessile_status write_mesh(const particles_gen *g, const char *rel) {
  const sessile_sponge_particles *ps = g->ps;
  double *c = malloc(((size_t)ps->surf.nv + 1) * sizeof *c);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t v = 0; v < ps->surf.nv; v++) c[v] = ps->counts[v];
  const char *names[1] = {"growth_count"};
  const double *extra[1] = {c};
  sessile_status st = sessile_run_write_surface(g->run, rel, &ps->surf, 1, names, extra);
  free(c);
  return st;
}

/* The invariants, when asked for: closed oriented 2-manifold, no self-intersection. */
static sessile_status check(const sessile_sponge_particles *ps, cJSON *rec) {
  sessile_status cs = sessile_surface_check(&ps->surf, 2, 0.0);
  if (cs == SESSILE_ERR_NO_MEMORY) return cs; /* no memory to check is no broken surface */
  SESSILE_CHECK(cs == SESSILE_OK, SESSILE_ERR_INTERNAL,
                "iteration %d: the surface is broken (%s): a bug", ps->iteration, sessile_error_message());
  uint64_t n = 0;
  SESSILE_CALL(sessile_surface_self_intersections(&ps->surf, 0, NULL, &n));
  cJSON_AddNumberToObject(rec, "self_intersections", (double)n);
  SESSILE_CHECK(n == 0, SESSILE_ERR_INTERNAL,
                "iteration %d: the surface intersects itself (%llu triangle pairs) although every step "
                "is guarded: a bug", ps->iteration, (unsigned long long)n);
  return SESSILE_OK;
}

static sessile_status step(void *state, int it, cJSON *rec) {
  particles_gen *g = state;
  const sessile_sponge_particles *ps = g->ps;
  sessile_sponge_particles_iter_stats st;
  SESSILE_CALL(sessile_sponge_particles_step(g->ps, &st));
  cJSON_AddNumberToObject(rec, "vertices", st.nv);
  cJSON_AddNumberToObject(rec, "triangles", st.nf);
  cJSON_AddNumberToObject(rec, "particles_alive", st.alive);
  cJSON_AddNumberToObject(rec, "spawned", st.spawned);
  cJSON_AddNumberToObject(rec, "hits", st.hits);
  cJSON_AddNumberToObject(rec, "fed_vertices", st.fed_vertices);
  cJSON_AddNumberToObject(rec, "died_fed", st.died_fed);
  cJSON_AddNumberToObject(rec, "died_age", st.died_age);
  cJSON_AddNumberToObject(rec, "died_outside", st.died_outside);
  cJSON_AddNumberToObject(rec, "held_back", st.held_back);
  cJSON_AddNumberToObject(rec, "remesh_refused", st.remesh_refused);
  cJSON_AddNumberToObject(rec, "collide_s", st.collide_s);
  cJSON_AddNumberToObject(rec, "grow_s", st.grow_s);
  cJSON_AddNumberToObject(rec, "remesh_s", st.remesh_s);
  return g->check ? check(ps, rec) : SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  return sessile_sponge_particles_restore(((particles_gen *)state)->ps, ck);
}

static sessile_status snapshot(void *state, const char *rel) { return write_mesh(state, rel); }

static sessile_status finish(void *state) {
  SESSILE_CALL(write_mesh(state, "sponge/final.ply"));
  return write_mesh(state, "sponge/final.obj");
}

static void destroy(void *state) {
  particles_gen *g = state;
  if (g) sessile_sponge_particles_destroy(g->ps);
  free(g);
}

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  particles_gen *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  g->run = su->run, g->check = su->flags & 1u;
  *state = g;
  return sessile_sponge_particles_create(params, su->seed, su->gpu, &g->ps);
}

static int needs_device(const void *params) {
  return ((const sessile_sponge_particles_params *)params)->collider == SESSILE_SPONGE_PARTICLES_COLLIDE_GPU;
}

static const sessile_gen_flag flags[] = {
    {"--check", "check", "check every iteration: closed 2-manifold, no self-intersection"}};

const sessile_generator sessile_gen_sponge_particles = {
    .name = "sponge particles",
    .summary = "Coralize's particle-fed sponge (Section 3.3)",
    .about = "Sponges after Liapis et al., Coralize (Section 3.3; docs/sponge_particles.md):\n"
    "a closed hemisphere on the substratum inside a cube; every iteration\n"
    "nutrient particles spawn on the cube's top face and fall (plus a current);\n"
    "a vertex a particle touches grows along its normal, its neighbours by a\n"
    "Gaussian falloff; the surface is remeshed (splitting and collapse\n"
    "thresholds) and never crosses itself.  Collisions: a GPU kernel over a\n"
    "uniform grid.  Writes sponge/iter_NNNN.ply every K iterations and at the\n"
    "last, sponge/final.ply (per-vertex growth_count) and sponge/final.obj,\n"
    "manifest.json, records.jsonl and a checkpoint at each snapshot.",
    .seed_help = "the particles",
    .out_default = "runs/sponge",
    .snapshot_name = "sponge/iter_%04d.ply",
    .preview = "sponge/final.ply",
    .table = &sessile_sponge_particles_param_table,
    .iterations = 50,
    .every = 10,
    .flags = flags,
    .nflags = 1,
    .needs_device = needs_device,
    SESSILE_GEN_CALLBACKS,
};
