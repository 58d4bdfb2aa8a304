/* Self-intersection and contact inhibition (docs/intersection.md): the pair
 * test on hand-made cases (shared vertices and edges, coplanar, touching)
 * and against an independent separating-axis test on random pairs;
 * icospheres have no pairs; two overlapping icospheres in one surface give
 * the pairs a brute-force O(n^2) loop gives, and every triangle that surely
 * crosses the other sphere is in one; seeded random perturbations, the
 * hierarchy against brute force; the motion guard on a pancake whose top is
 * pushed through its bottom; the triangle grid's query; the remesher's guards
 * on a collapse and on splits built to cross; 60 rounds of two spheres
 * growing into each other, guarded.  Pure C. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sessile/mesh/intersect.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"

static const double ORIGIN[3] = {0, 0, 0};

static double now(void) { /* CPU time of this process: the machine is shared */
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static uint64_t rng_state;
static double urand(void) { /* splitmix64 -> [0, 1) */
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

static void corners(const sessile_surface *s, uint32_t f, double out[9]) {
  for (int i = 0; i < 3; i++) memcpy(out + 3 * i, s->pos + 3 * s->tri[3 * f + i], 3 * sizeof *out);
}

static uint64_t count_pairs(const sessile_surface *s) {
  uint64_t n = 0;
  t_ok("self-intersections", sessile_surface_self_intersections(s, 0, NULL, &n));
  return n;
}

/* Every pair by brute force, (f, g) with f < g in order; returns the count. */
static uint64_t brute_pairs(const sessile_surface *s, uint32_t *out, uint64_t cap) {
  uint64_t n = 0;
  for (uint32_t f = 0; f < s->nf; f++) {
    double a[9], b[9];
    corners(s, f, a);
    for (uint32_t g = f + 1; g < s->nf; g++) {
      corners(s, g, b);
      if (sessile_triangles_intersect(a, s->tri + 3 * f, b, s->tri + 3 * g)) {
        if (n < cap) out[2 * n] = f, out[2 * n + 1] = g;
        n++;
      }
    }
  }
  return n;
}

/* Appends b's vertices and triangles to a (one surface of two pieces). */
static void append(sessile_surface *a, const sessile_surface *b) {
  t_ok("reserve", sessile_surface_reserve(a, a->nv + b->nv, a->nf + b->nf));
  memcpy(a->pos + 3 * a->nv, b->pos, (size_t)b->nv * 3 * sizeof *a->pos);
  for (uint32_t k = 0; k < 3 * b->nf; k++) a->tri[3 * a->nf + k] = b->tri[k] + a->nv;
  a->nv += b->nv, a->nf += b->nf;
}

/* --- the pair test ------------------------------------------------------ */

static int tt(const double *a, const uint32_t *va, const double *b, const uint32_t *vb) {
  return sessile_triangles_intersect(a, va, b, vb);
}

static void hand_cases(void) {
  const uint32_t i012[3] = {0, 1, 2}, i345[3] = {3, 4, 5};
  const double base[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  /* A vertical triangle through the base's interior, and one beside it. */
  const double cross[9] = {0.2, 0.2, -1, 0.3, 0.2, 1, 0.2, 0.3, 1};
  const double beside[9] = {2, 0, -1, 2, 1, 1, 3, 0, 1};
  t_true("pair: a triangle piercing another intersects", tt(base, i012, cross, i345));
  t_true("pair: a triangle beside another does not", !tt(base, i012, beside, i345));
  const double touch_v[9] = {1, 0, 0, 2, 0, 1, 2, 1, -1}; /* a corner on a corner */
  t_true("pair: touching at a point (no shared id) intersects", tt(base, i012, touch_v, i345));
  const double above[9] = {0, 0, 1e-9, 1, 0, 1e-9, 0, 1, 1e-9};
  t_true("pair: parallel 1e-9 apart does not", !tt(base, i012, above, i345));
  const double cop_ov[9] = {0.5, 0.5, 0, -0.5, 0.2, 0, 0.2, -0.5, 0};
  const double cop_far[9] = {1, 1, 0, 2, 1, 0, 1, 2, 0};
  const double cop_edge[9] = {1, 0, 0, 0, 1, 0, 1, 1, 0}; /* shares the hypotenuse, other ids */
  t_true("pair: coplanar overlapping intersects", tt(base, i012, cop_ov, i345));
  t_true("pair: coplanar apart does not", !tt(base, i012, cop_far, i345));
  t_true("pair: coplanar touching along an edge (other ids) intersects",
         tt(base, i012, cop_edge, i345));
  /* Shared edge 1-2 (ids 1, 2): folded open, coplanar flat, coplanar folded. */
  const uint32_t e12[3] = {2, 1, 7};
  const double open[9] = {0, 1, 0, 1, 0, 0, 1, 1, 1};
  const double flat[9] = {0, 1, 0, 1, 0, 0, 1, 1, 0};
  const double fold[9] = {0, 1, 0, 1, 0, 0, 0.2, 0.2, 0};
  t_true("pair: shared edge, bent: no intersection", !tt(base, i012, open, e12));
  t_true("pair: shared edge, coplanar on both sides: none", !tt(base, i012, flat, e12));
  t_true("pair: shared edge, coplanar fold onto each other: intersects",
         tt(base, i012, fold, e12));
  t_true("pair: the fold without shared ids is a plain overlap", tt(base, i012, fold, i345));
  /* Shared vertex 0 (id 0): a neighbour in the fan, one piercing the base,
   * a coplanar one in another sector, a coplanar one overlapping. */
  const uint32_t v0[3] = {0, 8, 9};
  const double fan[9] = {0, 0, 0, 0, -1, 0.3, -1, 0, 0.2};
  const double pierce[9] = {0, 0, 0, 0.4, 0.4, -1, 0.4, 0.3, 1};
  const double sector[9] = {0, 0, 0, -1, 0, 0, 0, -1, 0};
  const double overlap[9] = {0, 0, 0, 2, 0.5, 0, 0.5, 2, 0};
  t_true("pair: shared vertex, fan neighbour: none", !tt(base, i012, fan, v0));
  t_true("pair: shared vertex, the other crosses the base: intersects", tt(base, i012, pierce, v0));
  t_true("pair: shared vertex, coplanar in another sector: none", !tt(base, i012, sector, v0));
  t_true("pair: shared vertex, coplanar overlapping sectors: intersects",
         tt(base, i012, overlap, v0));
  t_true("pair: the same triangle twice intersects", tt(base, i012, base, i012));
}

/* Independent reference for triangles in general position: the separating
 * axis test (the two normals and the nine edge-edge cross products). */
static int sat_intersect(const double *a, const double *b) {
  double ea[3][3], eb[3][3], axes[11][3];
  int n = 0;
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      ea[i][k] = a[3 * ((i + 1) % 3) + k] - a[3 * i + k];
      eb[i][k] = b[3 * ((i + 1) % 3) + k] - b[3 * i + k];
    }
#define CROSS(o, u, v)                                                                             \
  (o)[0] = (u)[1] * (v)[2] - (u)[2] * (v)[1], (o)[1] = (u)[2] * (v)[0] - (u)[0] * (v)[2],         \
  (o)[2] = (u)[0] * (v)[1] - (u)[1] * (v)[0]
  CROSS(axes[n], ea[0], ea[1]), n++;
  CROSS(axes[n], eb[0], eb[1]), n++;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) CROSS(axes[n], ea[i], eb[j]), n++;
#undef CROSS
  for (int x = 0; x < n; x++) {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int t = 0; t < 2; t++)
      for (int i = 0; i < 3; i++) {
        const double *p = (t ? b : a) + 3 * i;
        double d = p[0] * axes[x][0] + p[1] * axes[x][1] + p[2] * axes[x][2];
        lo[t] = fmin(lo[t], d), hi[t] = fmax(hi[t], d);
      }
    if (hi[0] < lo[1] || hi[1] < lo[0]) return 0;
  }
  return 1;
}

static void random_pairs(void) {
  rng_state = 0x1234;
  int n = 200000, disagree = 0, hits = 0;
  for (int i = 0; i < n; i++) {
    double a[9], b[9];
    for (int k = 0; k < 9; k++) a[k] = urand(), b[k] = 0.6 * urand() + 0.3;
    int x = sessile_triangles_intersect(a, NULL, b, NULL), y = sat_intersect(a, b);
    hits += x;
    if (x != y && disagree++ < 3) printf("     disagreement on pair %d: %d vs SAT %d\n", i, x, y);
  }
  printf("     %d random pairs, %d intersecting\n", n, hits);
  t_check("pair test vs separating axes, random pairs (disagreements)", disagree, 0);
  t_true("random pairs: both outcomes occur", hits > n / 10 && hits < n - n / 10);
}

/* --- surfaces --------------------------------------------------------------- */

static void spheres_clean(void) {
  uint64_t worst = 0;
  for (int level = 1; level <= 5; level++) {
    sessile_surface s = {0};
    t_ok("icosphere", sessile_surface_icosphere(level, 1.0 + level, ORIGIN, &s));
    uint64_t n = count_pairs(&s);
    worst = n > worst ? n : worst;
    sessile_surface_free(&s);
  }
  t_check("icospheres, levels 1-5: intersecting pairs", (double)worst, 0);
  /* The growth loop's start: the part below the floor flattened onto it
   * (exactly coplanar triangles around shared vertices and edges). */
  sessile_surface s = {0};
  const double c[3] = {0, 0, 1.0};
  t_ok("icosphere", sessile_surface_icosphere(4, 2.0, c, &s));
  for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + 2] = fmax(s.pos[3 * v + 2], 0.0);
  t_check("icosphere flattened on a floor: intersecting pairs", (double)count_pairs(&s), 0);
  sessile_surface_free(&s);
}

static void two_spheres(void) {
  const double R = 1.0, ca[3] = {0, 0, 0}, cb[3] = {1.3, 0.2, 0.1};
  sessile_surface s = {0}, b = {0};
  t_ok("icosphere a", sessile_surface_icosphere(4, R, ca, &s));
  t_ok("icosphere b", sessile_surface_icosphere(4, R, cb, &b));
  uint32_t na = s.nf;
  append(&s, &b);
  uint64_t n = 0;
  uint32_t *p = malloc((size_t)s.nf * 8 * sizeof *p), *q = malloc((size_t)s.nf * 8 * sizeof *q);
  double t0 = now();
  t_ok("self-intersections", sessile_surface_self_intersections(&s, s.nf * 4, p, &n));
  double t1 = now();
  uint64_t m = brute_pairs(&s, q, (uint64_t)s.nf * 4);
  double t2 = now();
  printf("     %u triangles: %llu pairs; hierarchy %.2f ms, brute force %.0f ms (CPU)\n", s.nf,
         (unsigned long long)n, 1e3 * (t1 - t0), 1e3 * (t2 - t1));
  t_true("two spheres: pairs found", n > 0);
  t_true("two spheres: hierarchy count == brute-force count", n == m);
  t_true("two spheres: the same pairs in the same order",
         n == m && !memcmp(p, q, (size_t)n * 2 * sizeof *p));
  int cross = 1;
  for (uint64_t i = 0; i < n; i++) cross &= (p[2 * i] < na) != (p[2 * i + 1] < na);
  t_true("two spheres: every pair has one triangle of each sphere", cross);
  /* A triangle of a with a corner surely inside b's polyhedron (within its
   * inscribed ball) and one surely outside (beyond radius R) crosses b. */
  uint8_t *in_pair = calloc(s.nf, 1);
  for (uint64_t i = 0; i < n; i++) in_pair[p[2 * i]] = in_pair[p[2 * i + 1]] = 1;
  sessile_surface_stats st;
  sessile_surface_stats_of(&b, &st);
  double r_in = R * cos(asin(st.edge_max / (2 * R))) * cos(asin(st.edge_max / (2 * R)));
  uint32_t expected = 0, missed = 0;
  for (uint32_t f = 0; f < na; f++) {
    int inside = 0, outside = 0;
    for (int k = 0; k < 3; k++) {
      const double *x = s.pos + 3 * s.tri[3 * f + k];
      double d = sqrt((x[0] - cb[0]) * (x[0] - cb[0]) + (x[1] - cb[1]) * (x[1] - cb[1]) +
                      (x[2] - cb[2]) * (x[2] - cb[2]));
      inside |= d < r_in, outside |= d > R;
    }
    if (inside && outside) expected++, missed += !in_pair[f];
  }
  printf("     %u triangles of a surely cross b\n", expected);
  t_true("two spheres: some triangles surely cross", expected > 10);
  t_check("two spheres: sure crossings not in a pair", missed, 0);
  free(in_pair), free(p), free(q);
  sessile_surface_free(&s), sessile_surface_free(&b);
}

static void fuzz(void) {
  int bad = 0, total_pairs = 0;
  for (int seed = 1; seed <= 12; seed++) {
    rng_state = 0xF00Du * seed;
    sessile_surface s = {0};
    t_ok("icosphere", sessile_surface_icosphere(3, 1.0, ORIGIN, &s));
    double amp = 0.05 * seed; /* edges ~0.3: from a few pairs to many */
    for (uint32_t i = 0; i < 3 * s.nv; i++) s.pos[i] += amp * (urand() - 0.5);
    /* now and then exact coincidences: a vertex onto another, a coordinate onto a plane */
    if (seed % 3 == 0) memcpy(s.pos + 3 * 5, s.pos + 3 * 77, 3 * sizeof *s.pos);
    if (seed % 4 == 0)
      for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + 2] = fmax(s.pos[3 * v + 2], 0.1);
    uint64_t n = count_pairs(&s), m = brute_pairs(&s, NULL, 0);
    total_pairs += (int)n;
    if (n != m && bad++ < 3) printf("     seed %d: hierarchy %llu, brute force %llu\n", seed,
                                    (unsigned long long)n, (unsigned long long)m);
    sessile_surface_free(&s);
  }
  printf("     12 perturbed level-3 spheres: %d pairs in all\n", total_pairs);
  t_check("fuzz: perturbed spheres where the hierarchy count != brute force", bad, 0);
  t_true("fuzz: pairs occurred", total_pairs > 100);
}

static void timing(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(7, 30.0, ORIGIN, &s));
  double t0 = now();
  uint64_t n = count_pairs(&s);
  printf("     TIME self-intersections of %u triangles: %.1f ms CPU (%llu pairs)\n", s.nf,
         1e3 * (now() - t0), (unsigned long long)n);
  sessile_surface_free(&s);
}

/* --- the motion guard --------------------------------------------------- */

/* A pancake (a level-4 sphere of radius 3 flattened to 0.6 cm): everything
 * grows 0.02 cm along its normal, and the top's middle sinks by up to 0.9 cm,
 * through the bottom.  The guard must keep it clean, holding back only near
 * where top and bottom would meet. */
static void guard_pancake(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(4, 3.0, ORIGIN, &s));
  for (uint32_t v = 0; v < s.nv; v++) s.pos[3 * v + 2] *= 0.1;
  t_true("pancake: clean to start", count_pairs(&s) == 0);
  double *n = malloc((size_t)s.nv * 3 * sizeof *n), *np = malloc((size_t)s.nv * 3 * sizeof *np);
  double *np2 = malloc((size_t)s.nv * 3 * sizeof *np2);
  sessile_surface_normals(&s, n);
  const double rho = 1.2;
  for (uint32_t v = 0; v < s.nv; v++) {
    const double *x = s.pos + 3 * v;
    double r = hypot(x[0], x[1]), sink = x[2] > 0 && r < rho ? 0.9 * (1 - (r / rho) * (r / rho)) : 0;
    for (int k = 0; k < 3; k++) np[3 * v + k] = x[k] + 0.02 * n[3 * v + k];
    np[3 * v + 2] -= sink;
  }
  sessile_surface moved = {0};
  t_ok("copy", sessile_surface_copy(&s, &moved));
  memcpy(moved.pos, np, (size_t)s.nv * 3 * sizeof *np);
  uint64_t before = count_pairs(&moved);
  printf("     the unguarded motion: %llu intersecting pairs\n", (unsigned long long)before);
  t_true("pancake: the unguarded motion crosses", before > 0);
  for (int halfway = 0; halfway <= 1; halfway++) {
    memcpy(np2, np, (size_t)s.nv * 3 * sizeof *np);
    sessile_guard_stats st;
    double t0 = now();
    t_ok("guard", sessile_surface_guard_motion(&s, np2, halfway, &st));
    double t1 = now();
    memcpy(moved.pos, np2, (size_t)s.nv * 3 * sizeof *np2);
    /* How far from the contact is a held-back vertex?  Contact: where the
     * sunk top would pass z = -0.3 * sqrt(1 - r^2/9) (the bottom). */
    double far = 0;
    for (uint32_t v = 0; v < s.nv; v++) {
      if (np2[3 * v] == np[3 * v] && np2[3 * v + 1] == np[3 * v + 1] && np2[3 * v + 2] == np[3 * v + 2])
        continue;
      far = fmax(far, hypot(s.pos[3 * v], s.pos[3 * v + 1]));
    }
    printf("     halfway %d: %u moved, %u held back, %u halfway, %u rounds, kept %.1f of %.1f cm, "
           "%.1f ms CPU; farthest held-back vertex at r = %.2f\n",
           halfway, st.moved, st.held_back, st.halfway, st.rounds, st.kept_cm, st.proposed_cm,
           1e3 * (t1 - t0), far);
    t_check("pancake: pairs after the guard", (double)count_pairs(&moved), 0);
    t_true("pancake: some vertices held back", st.held_back + st.halfway > 0);
    /* The contact lies where the sink exceeds the gap: r < ~0.9; one ring of
     * triangles (edges ~0.45 cm) around it may be pulled in. */
    t_check("pancake: held back only near the contact (r of the farthest, cm)", far, 0.95 + 2 * 0.45);
    t_true("pancake: most of the growth kept (> 80% of the vertices)",
           st.held_back + st.halfway < st.moved / 5);
    t_ok("pancake: invariants after the guard", sessile_surface_check(&moved, 2, 0));
    double *again = malloc((size_t)s.nv * 3 * sizeof *again);
    memcpy(again, np, (size_t)s.nv * 3 * sizeof *np);
    t_ok("guard again", sessile_surface_guard_motion(&s, again, halfway, NULL));
    t_true("pancake: same input, same output (bit for bit)",
           !memcmp(again, np2, (size_t)s.nv * 3 * sizeof *np2));
    free(again);
  }
  free(n), free(np), free(np2);
  sessile_surface_free(&s), sessile_surface_free(&moved);
}

/* Two overlapping spheres moved at random: the pairs they had stay (the
 * guard cannot undo them), no new one appears. */
static void guard_preexisting(void) {
  const double cb[3] = {1.3, 0.2, 0.1};
  sessile_surface s = {0}, b = {0}, m = {0};
  t_ok("icosphere a", sessile_surface_icosphere(3, 1.0, ORIGIN, &s));
  t_ok("icosphere b", sessile_surface_icosphere(3, 1.0, cb, &b));
  append(&s, &b);
  uint64_t n0 = count_pairs(&s);
  uint32_t *p0 = malloc((size_t)n0 * 2 * sizeof *p0 + 8), *p1 = malloc((size_t)s.nf * 8 * sizeof *p1);
  t_ok("pairs", sessile_surface_self_intersections(&s, (uint32_t)n0, p0, &n0));
  t_ok("copy", sessile_surface_copy(&s, &m));
  rng_state = 99;
  for (uint32_t i = 0; i < 3 * m.nv; i++) m.pos[i] += 0.3 * (urand() - 0.5);
  sessile_guard_stats st;
  t_ok("guard", sessile_surface_guard_motion(&s, m.pos, 1, &st));
  uint64_t n1 = 0;
  t_ok("pairs after", sessile_surface_self_intersections(&m, s.nf * 4, p1, &n1));
  uint64_t fresh = 0;
  for (uint64_t i = 0, j = 0; i < n1; i++) { /* both lists sorted */
    while (j < n0 && ((uint64_t)p0[2 * j] << 32 | p0[2 * j + 1]) < ((uint64_t)p1[2 * i] << 32 | p1[2 * i + 1])) j++;
    fresh += !(j < n0 && p0[2 * j] == p1[2 * i] && p0[2 * j + 1] == p1[2 * i + 1]);
  }
  printf("     %llu pairs before, %llu after (%llu left alone), %u of %u vertices held back, %u halfway\n",
         (unsigned long long)n0, (unsigned long long)n1, (unsigned long long)st.preexisting,
         st.held_back, st.moved, st.halfway);
  t_check("pre-existing pairs: new pairs after the guard", (double)fresh, 0);
  t_true("pre-existing pairs: reported", st.preexisting > 0);
  free(p0), free(p1);
  sessile_surface_free(&s), sessile_surface_free(&b), sessile_surface_free(&m);
}

/* --- the grid query ---------------------------------------------------- */

static void grid_query(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(4, 2.0, ORIGIN, &s));
  sessile_tri_grid *g = NULL;
  t_ok("grid", sessile_tri_grid_create(&s, &g));
  double p[9], c[3] = {0, 0, 0}, q[9];
  corners(&s, 0, p);
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) c[k] += p[3 * i + k] / 3;
  const uint32_t fresh[3] = {s.nv, s.nv + 1, s.nv + 2};
  /* Triangle 0 scaled by 0.999 about the centre: inside the sphere. */
  for (int i = 0; i < 9; i++) q[i] = 0.999 * p[i];
  t_true("grid: triangle 0 scaled into the sphere hits nothing",
         !sessile_tri_grid_hits(g, &s, NULL, 1, fresh, q, NULL, 0));
  /* A radial sliver through triangle 0's centroid. */
  double perp[3] = {c[1], -c[0], 0}, lp = hypot(c[0], c[1]);
  for (int k = 0; k < 3; k++) {
    q[k] = 0.9 * c[k];
    q[3 + k] = 1.1 * c[k] + 0.01 * perp[k] / lp;
    q[6 + k] = 1.1 * c[k] - 0.01 * perp[k] / lp;
  }
  t_true("grid: a triangle through the surface hits",
         sessile_tri_grid_hits(g, &s, NULL, 1, fresh, q, NULL, 0));
  uint8_t *alive = calloc(s.nf, 1);
  t_true("grid: dead triangles are skipped",
         !sessile_tri_grid_hits(g, &s, alive, 1, fresh, q, NULL, 0));
  free(alive);
  /* Triangle 0 itself: with other ids it touches itself and its neighbours;
   * with those excluded nothing; with its own ids only itself. */
  uint32_t ex[32], nex = 0;
  for (uint32_t f = 0; f < s.nf && nex < 32; f++) {
    const uint32_t *t = s.tri + 3 * f;
    int near = 0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) near |= t[i] == s.tri[j];
    if (near) ex[nex++] = f;
  }
  t_true("grid: triangle 0 with other ids hits", sessile_tri_grid_hits(g, &s, NULL, 1, fresh, p, NULL, 0));
  t_true("grid: ... not with triangle 0 and its neighbours excluded",
         !sessile_tri_grid_hits(g, &s, NULL, 1, fresh, p, ex, nex));
  t_true("grid: triangle 0 with its own ids hits itself",
         sessile_tri_grid_hits(g, &s, NULL, 1, s.tri, p, NULL, 0));
  t_true("grid: ... and nothing else", !sessile_tri_grid_hits(g, &s, NULL, 1, s.tri, p, ex, 1));
  /* Two candidates crossing each other. */
  double two[18];
  memcpy(two, q, sizeof q);
  for (int i = 0; i < 9; i++) two[9 + i] = 0.5 * q[i] + 0.5 * q[(i + 3) % 9];
  two[9 + 2] += 0.3, two[12 + 2] -= 0.3;
  const uint32_t ids2[6] = {s.nv, s.nv + 1, s.nv + 2, s.nv + 3, s.nv + 4, s.nv + 5};
  t_true("grid: candidates crossing each other hit",
         sessile_tri_grid_hits(g, &s, NULL, 2, ids2, two, NULL, 0));
  sessile_tri_grid_destroy(g);
  sessile_surface_free(&s);
}

/* --- the remesher's guards ------------------------------------------------ */

/* One surface of two pieces: a level-3 sphere with a pit (its top vertex
 * pushed 0.45 cm in, a neighbour drawn towards it so their edge is the only
 * short one) and a thin tetrahedron (never collapsed: its vertices have
 * valence 3) that pierces where the pit's fan will be after the collapse. */
static void remesh_collapse_guard(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(3, 2.0, ORIGIN, &s));
  uint32_t top = 0;
  for (uint32_t v = 1; v < s.nv; v++)
    if (s.pos[3 * v + 2] > s.pos[3 * top + 2]) top = v;
  uint32_t nb = UINT32_MAX;
  for (uint32_t f = 0; f < s.nf && nb == UINT32_MAX; f++)
    for (int k = 0; k < 3; k++)
      if (s.tri[3 * f + k] == top) nb = s.tri[3 * f + (k + 1) % 3];
  double *T = s.pos + 3 * top, *N = s.pos + 3 * nb;
  for (int k = 0; k < 3; k++) T[k] *= (2.0 - 0.45) / 2.0;
  for (int k = 0; k < 3; k++) N[k] = T[k] + 0.6 * (N[k] - T[k]);
  double tn = sqrt((T[0] - N[0]) * (T[0] - N[0]) + (T[1] - N[1]) * (T[1] - N[1]) + (T[2] - N[2]) * (T[2] - N[2]));
  sessile_surface_stats st0;
  sessile_surface_stats_of(&s, &st0);
  printf("     the short edge %.3f cm, the others from %.3f\n", tn, st0.edge_min);
  int nshort = 0;
  for (uint32_t f = 0; f < s.nf; f++)
    for (int k = 0; k < 3; k++) {
      const double *x = s.pos + 3 * s.tri[3 * f + k], *y = s.pos + 3 * s.tri[3 * f + (k + 1) % 3];
      nshort += sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                     (x[2] - y[2]) * (x[2] - y[2])) < 1.01 * tn;
    }
  t_true("collapse guard: the pit's edge is the only short one", nshort == 2); /* both directions */
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  o.insert_len = 10, o.fuse_len = 1.01 * tn, o.min_area = 0, o.max_turn_deg = 179;
  /* Where the pit's fan goes: collapse a copy without the guard. */
  sessile_surface c = {0};
  sessile_remesh_stats rs;
  t_ok("copy", sessile_surface_copy(&s, &c));
  o.guard_intersections = 0;
  t_ok("remesh (unguarded)", sessile_remesh(&c, NULL, &o, &rs));
  t_true("collapse guard: unguarded, the edge is fused", rs.fusions == 1);
  /* The fan triangle that moved farthest from its old plane (triangles keep
   * their order and, but for the two deleted, their corners' order). */
  uint32_t lo = top < nb ? top : nb;
  double best = 0, at[3] = {0}, dir[3] = {0};
  for (uint32_t f = 0, g = 0; f < s.nf; f++) {
    const uint32_t *t = s.tri + 3 * f;
    int has_t = t[0] == top || t[1] == top || t[2] == top, has_n = t[0] == nb || t[1] == nb || t[2] == nb;
    if (has_t && has_n) continue; /* deleted by the collapse */
    uint32_t gi = g++;
    if (!has_t && !has_n) continue;
    double a[9], b[9], u[3], w[3], nn[3], cen[3] = {0, 0, 0}, cold[3] = {0, 0, 0};
    corners(&s, f, a);
    corners(&c, gi, b);
    for (int k = 0; k < 3; k++) u[k] = a[3 + k] - a[k], w[k] = a[6 + k] - a[k];
    nn[0] = u[1] * w[2] - u[2] * w[1], nn[1] = u[2] * w[0] - u[0] * w[2], nn[2] = u[0] * w[1] - u[1] * w[0];
    double ln = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    for (int k = 0; k < 3; k++) {
      nn[k] /= ln;
      for (int i = 0; i < 3; i++) cen[k] += b[3 * i + k] / 3, cold[k] += a[3 * i + k] / 3;
    }
    double d = fabs((cen[0] - cold[0]) * nn[0] + (cen[1] - cold[1]) * nn[1] + (cen[2] - cold[2]) * nn[2]);
    if (d > best) best = d, memcpy(at, cen, sizeof at), memcpy(dir, nn, sizeof dir);
  }
  (void)lo;
  printf("     a fan triangle moves %.3f cm off its old plane\n", best);
  t_true("collapse guard: the collapse moves a fan triangle off its plane", best > 0.02);
  /* The needle: from 0.4 best below the new centroid to 0.4 best above,
   * 0.004 cm thick, oriented outwards. */
  double h = 0.4 * best, e1[3], e2[3];
  e1[0] = -dir[1], e1[1] = dir[0], e1[2] = 0;
  double l1 = hypot(e1[0], e1[1]);
  if (l1 < 1e-9) e1[0] = 1, e1[1] = 0, l1 = 1;
  e1[0] /= l1, e1[1] /= l1;
  e2[0] = dir[1] * e1[2] - dir[2] * e1[1], e2[1] = dir[2] * e1[0] - dir[0] * e1[2];
  e2[2] = dir[0] * e1[1] - dir[1] * e1[0];
  sessile_surface needle = {0};
  t_ok("reserve", sessile_surface_reserve(&needle, 4, 4));
  for (int k = 0; k < 3; k++) {
    needle.pos[k] = at[k] - h * dir[k];
    needle.pos[3 + k] = at[k] + h * dir[k] + 0.004 * e1[k];
    needle.pos[6 + k] = at[k] + h * dir[k] - 0.002 * e1[k] + 0.0035 * e2[k];
    needle.pos[9 + k] = at[k] + h * dir[k] - 0.002 * e1[k] - 0.0035 * e2[k];
  }
  const uint32_t tet[12] = {0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3};
  memcpy(needle.tri, tet, sizeof tet);
  needle.nv = needle.nf = 4;
  sessile_surface_stats ns;
  sessile_surface_stats_of(&needle, &ns);
  if (ns.volume < 0)
    for (int f = 0; f < 4; f++) {
      uint32_t x = needle.tri[3 * f + 1];
      needle.tri[3 * f + 1] = needle.tri[3 * f + 2], needle.tri[3 * f + 2] = x;
    }
  append(&s, &needle);
  append(&c, &needle);
  t_true("collapse guard: clean before the remesh", count_pairs(&s) == 0);
  t_true("collapse guard: the unguarded collapse would cross the needle", count_pairs(&c) > 0);
  sessile_surface u = {0};
  t_ok("copy", sessile_surface_copy(&s, &u));
  t_ok("remesh (unguarded, with the needle)", sessile_remesh(&u, NULL, &o, &rs));
  printf("     unguarded: %u fusions, %llu pairs after\n", rs.fusions,
         (unsigned long long)count_pairs(&u));
  t_true("collapse guard: unguarded, the surface crosses itself", count_pairs(&u) > 0);
  o.guard_intersections = 1;
  t_ok("remesh (guarded)", sessile_remesh(&s, NULL, &o, &rs));
  printf("     guarded: %u fusions, %u contact refusals, %u left\n", rs.fusions,
         rs.contact_refusals, rs.rejected);
  t_true("collapse guard: the collapse is refused", rs.fusions == 0 && rs.contact_refusals >= 1);
  t_check("collapse guard: pairs after the guarded remesh", (double)count_pairs(&s), 0);
  t_ok("collapse guard: invariants", sessile_surface_check(&s, 4, 0));
  sessile_surface_free(&s), sessile_surface_free(&c), sessile_surface_free(&u);
  sessile_surface_free(&needle);
}

/* Splits: two level-3 spheres of radius 3 (edges ~0.75 cm, all above
 * insert_len), turned so that a triangle's centre faces the other sphere,
 * 0.04 cm apart; normals from a point 0.45 cm under each facing triangle,
 * so they diverge more than the sphere's and curve points bulge ~0.08 cm
 * out of the facing triangles.  Unguarded the pieces cross; guarded not. */
static void remesh_split_guard(void) {
  const double R = 3.0, gap = 0.04;
  sessile_surface s = {0}, b = {0};
  t_ok("icosphere a", sessile_surface_icosphere(3, R, ORIGIN, &s));
  /* Rodrigues: the rotation taking triangle 0's centre direction u to +x. */
  double u[3] = {0, 0, 0}, x[3] = {1, 0, 0}, w[3], rot[9];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) u[k] += s.pos[3 * s.tri[i] + k];
  double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int k = 0; k < 3; k++) u[k] /= lu;
  w[0] = u[1] * x[2] - u[2] * x[1], w[1] = u[2] * x[0] - u[0] * x[2], w[2] = u[0] * x[1] - u[1] * x[0];
  double sn = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), cs = u[0];
  for (int k = 0; k < 3; k++) w[k] /= sn;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double kx[3][3] = {{0, -w[2], w[1]}, {w[2], 0, -w[0]}, {-w[1], w[0], 0}};
      double k2 = 0;
      for (int m = 0; m < 3; m++) k2 += kx[i][m] * kx[m][j];
      rot[3 * i + j] = (i == j) + sn * kx[i][j] + (1 - cs) * k2;
    }
  for (uint32_t v = 0; v < s.nv; v++) {
    double p[3];
    for (int i = 0; i < 3; i++)
      p[i] = rot[3 * i] * s.pos[3 * v] + rot[3 * i + 1] * s.pos[3 * v + 1] + rot[3 * i + 2] * s.pos[3 * v + 2];
    memcpy(s.pos + 3 * v, p, sizeof p);
  }
  /* b: a turned half a turn about z (facing -x), moved beside a. */
  double xf = 0;
  for (int i = 0; i < 3; i++) xf += s.pos[3 * s.tri[i]] / 3;
  t_ok("copy", sessile_surface_copy(&s, &b));
  for (uint32_t v = 0; v < b.nv; v++) {
    b.pos[3 * v] = 2 * xf + gap - b.pos[3 * v];
    b.pos[3 * v + 1] = -b.pos[3 * v + 1];
  }
  uint32_t na = s.nv;
  append(&s, &b);
  t_true("split guard: clean to start", count_pairs(&s) == 0);
  double *n = malloc((size_t)s.nv * 3 * sizeof *n);
  for (uint32_t v = 0; v < s.nv; v++) {
    double q[3] = {v < na ? xf - 0.45 : xf + gap + 0.45, 0, 0}, l = 0;
    for (int k = 0; k < 3; k++) n[3 * v + k] = s.pos[3 * v + k] - q[k], l += n[3 * v + k] * n[3 * v + k];
    for (int k = 0; k < 3; k++) n[3 * v + k] /= sqrt(l);
  }
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  o.insert_len = 0.6, o.fuse_len = 0, o.min_area = 0;
  sessile_remesh_stats rs;
  sessile_surface u2 = {0};
  t_ok("copy", sessile_surface_copy(&s, &u2));
  o.guard_intersections = 0;
  t_ok("remesh (unguarded)", sessile_remesh(&u2, n, &o, &rs));
  uint64_t pu = count_pairs(&u2);
  printf("     unguarded: %u splits, %llu pairs\n", rs.splits, (unsigned long long)pu);
  t_true("split guard: unguarded, the curve points cross", pu > 0);
  o.guard_intersections = 1;
  t_ok("remesh (guarded)", sessile_remesh(&s, n, &o, &rs));
  printf("     guarded: %u splits, %u on the chord\n", rs.splits, rs.chord_splits);
  t_true("split guard: some points put on the chord", rs.chord_splits > 0 && rs.chord_splits < rs.splits);
  t_check("split guard: pairs after the guarded remesh", (double)count_pairs(&s), 0);
  t_ok("split guard: invariants", sessile_surface_check(&s, 4, 0));
  free(n);
  sessile_surface_free(&s), sessile_surface_free(&b), sessile_surface_free(&u2);
}

/* The growth loop's pattern on the host: two spheres 0.05 cm apart grow
 * into each other (0.03-0.07 cm along the normals per round, noise 0.01),
 * the motion guard holding them back, then a guarded remesh; 60 rounds.
 * Every round must end without a crossing, with a remesh output that is a
 * fixed point (refusals by the contact guard are re-examined when their
 * surroundings change) and the same for the same input. */
static void contact_rounds(void) {
  const double cb[3] = {3.05, 0.2, -0.1};
  sessile_surface s = {0}, b = {0}, c = {0};
  t_ok("icosphere a", sessile_surface_icosphere(4, 1.5, ORIGIN, &s));
  t_ok("icosphere b", sessile_surface_icosphere(4, 1.5, cb, &b));
  append(&s, &b);
  sessile_remesh_options o;
  sessile_remesh_options_default(&o);
  rng_state = 777;
  int bad_pairs = 0, bad_fixed = 0, bad_same = 0, bad_inv = 0;
  uint64_t held = 0, half = 0, refusals = 0, chord = 0, fusions = 0;
  double *n = NULL, *np = NULL;
  for (int round = 0; round < 60; round++) {
    n = realloc(n, (size_t)s.nv * 3 * sizeof *n);
    np = realloc(np, (size_t)s.nv * 3 * sizeof *np);
    sessile_surface_normals(&s, n);
    double g = 0.03 + 0.04 * urand();
    for (uint32_t v = 0; v < s.nv; v++)
      for (int k = 0; k < 3; k++)
        np[3 * v + k] = s.pos[3 * v + k] + g * n[3 * v + k] + 0.01 * (urand() - 0.5);
    sessile_guard_stats gs;
    t_ok("guard", sessile_surface_guard_motion(&s, np, 1, &gs));
    held += gs.held_back, half += gs.halfway;
    memcpy(s.pos, np, (size_t)s.nv * 3 * sizeof *np);
    sessile_surface_normals(&s, n);
    sessile_remesh_stats rs, r2;
    t_ok("copy", sessile_surface_copy(&s, &c));
    t_ok("remesh", sessile_remesh(&s, n, &o, &rs));
    refusals += rs.contact_refusals, chord += rs.chord_splits, fusions += rs.fusions;
    t_ok("remesh the copy", sessile_remesh(&c, n, &o, &r2));
    bad_same += !(c.nv == s.nv && c.nf == s.nf &&
                  !memcmp(c.pos, s.pos, (size_t)s.nv * 3 * sizeof *s.pos) &&
                  !memcmp(c.tri, s.tri, (size_t)s.nf * 3 * sizeof *s.tri));
    t_ok("remesh the output", sessile_remesh(&c, NULL, &o, &r2));
    bad_fixed += !(r2.splits == 0 && r2.fusions == 0 && r2.area_collapses == 0 && c.nv == s.nv &&
                   !memcmp(c.pos, s.pos, (size_t)s.nv * 3 * sizeof *s.pos));
    bad_pairs += count_pairs(&s) > 0;
    bad_inv += sessile_surface_check(&s, 4, 0) != SESSILE_OK;
  }
  printf("     60 rounds: %llu vertices held back, %llu halfway; remesh %llu fusions, %llu contact "
         "refusals, %llu splits on the chord; final %u triangles\n", (unsigned long long)held,
         (unsigned long long)half, (unsigned long long)fusions, (unsigned long long)refusals,
         (unsigned long long)chord, s.nf);
  t_true("contact rounds: the spheres met (vertices held back)", held + half > 0);
  t_true("contact rounds: the remesh refused collapses at the contact", refusals > 0);
  t_check("contact rounds: rounds ending with a crossing", bad_pairs, 0);
  t_check("contact rounds: rounds breaking an invariant", bad_inv, 0);
  t_check("contact rounds: rounds whose remesh is not a fixed point", bad_fixed, 0);
  t_check("contact rounds: rounds whose remesh differs for the same input", bad_same, 0);
  free(n), free(np);
  sessile_surface_free(&s), sessile_surface_free(&b), sessile_surface_free(&c);
}

static void errors(void) {
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(2, 1.0, ORIGIN, &s));
  double *np = malloc((size_t)s.nv * 3 * sizeof *np);
  memcpy(np, s.pos, (size_t)s.nv * 3 * sizeof *np);
  np[7] = NAN;
  t_true("guard rejects a NaN position",
         sessile_surface_guard_motion(&s, np, 0, NULL) == SESSILE_ERR_NUMERIC);
  printf("     %s\n", sessile_error_message());
  s.tri[4] = s.nv;
  uint64_t n;
  t_true("self-intersections reject an index out of range",
         sessile_surface_self_intersections(&s, 0, NULL, &n) == SESSILE_ERR_USAGE);
  free(np);
  sessile_surface_free(&s);
}

int main(void) {
  hand_cases();
  random_pairs();
  spheres_clean();
  two_spheres();
  fuzz();
  timing();
  guard_pancake();
  guard_preexisting();
  grid_query();
  remesh_collapse_guard();
  remesh_split_guard();
  contact_rounds();
  errors();
  return t_finish(NULL);
}
