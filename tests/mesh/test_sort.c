/* The radix sorts (host/mesh/mesh_sort.c) against qsort: keys ascending, the
 * same multiset, and for the payload version equal keys in their input
 * order (stability, which the SDS face sorts rely on to order ties by tet),
 * and mesh_order3, the ranking of records led by a triple that they use.
 * Keys drawn from small and full ranges, so that passes are skipped and
 * taken.  Pure C: no GPU. */
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"
#include "sessile/rng.h"
#include "testutil.h"

typedef struct {
  uint64_t k;
  uint32_t i;
} pair;

static int pair_cmp(const void *a, const void *b) {
  const pair *p = a, *q = b;
  if (p->k != q->k) return p->k < q->k ? -1 : 1;
  return (p->i > q->i) - (p->i < q->i);
}

static void one(const char *name, size_t n, uint64_t mask, uint64_t seed) {
  uint64_t rng = seed;
  uint64_t *k = t_xalloc(2 * n * sizeof *k), *plain = t_xalloc(2 * n * sizeof *plain);
  uint32_t *ix = t_xalloc(2 * n * sizeof *ix);
  pair *ref = t_xalloc(n * sizeof *ref);
  for (size_t j = 0; j < n; j++) {
    uint64_t v = sessile_rng_next(&rng) & mask;
    k[j] = plain[j] = v, ix[j] = (uint32_t)j;
    ref[j] = (pair){v, (uint32_t)j};
  }
  qsort(ref, n, sizeof *ref, pair_cmp); /* (key, input position): the stable order */
  mesh_sort_u64_idx(k, ix, k + n, ix + n, n);
  mesh_sort_u64(plain, plain + n, n);
  size_t bad = 0, bad_plain = 0, ties = 0;
  for (size_t j = 0; j < n; j++) {
    bad += k[j] != ref[j].k || ix[j] != ref[j].i;
    bad_plain += plain[j] != ref[j].k;
    ties += j > 0 && ref[j].k == ref[j - 1].k;
  }
  char what[160];
  snprintf(what, sizeof what, "%s: %zu keys (%zu ties) with payload in qsort's (key, position) order", name, n, ties);
  t_true(what, bad == 0);
  snprintf(what, sizeof what, "%s: keys alone ascending, the same multiset", name);
  t_true(what, bad_plain == 0);
  free(k), free(plain), free(ix), free(ref);
}

int main(void) {
  one("many ties (keys < 64)", 5000, 63, 1);
  one("one byte (a pass per digit skipped)", 5000, 0xff00, 2);
  one("full 64-bit keys", 20000, ~(uint64_t)0, 3);
  one("one key", 1, ~(uint64_t)0, 4);
  /* mesh_order3: records of 5 words led by an ascending triple, ranked as
   * qsort ranks (triple, position); a triple past 2^21 refuses */
  {
    enum { N = 3000, W = 5 };
    uint32_t *rec = t_xalloc(N * W * sizeof *rec), *order = t_xalloc(N * sizeof *order);
    pair *ref = t_xalloc(N * sizeof *ref);
    uint64_t st = 9;
    for (uint32_t i = 0; i < N; i++) {
      uint32_t t[3];
      for (int q = 0; q < 3; q++) t[q] = (uint32_t)(sessile_rng_next(&st) % 40);
      for (int q = 0; q < 3; q++) /* ascending */
        for (int r = q + 1; r < 3; r++)
          if (t[r] < t[q]) { uint32_t x = t[q]; t[q] = t[r]; t[r] = x; }
      memcpy(rec + W * i, t, sizeof t);
      rec[W * i + 3] = rec[W * i + 4] = 0xdeadbeef; /* payload words: not part of the key */
      uint64_t k = 0;
      mesh_key3(t[0], t[1], t[2], &k);
      ref[i] = (pair){k, i};
    }
    qsort(ref, N, sizeof *ref, pair_cmp);
    int ok = mesh_order3(rec, W, N, order);
    size_t bad = 0;
    for (uint32_t i = 0; ok && i < N; i++) bad += order[i] != ref[i].i;
    t_true("order3: 3000 records of 5 words (triples < 40: many ties) in qsort's (triple, position) order",
           ok && bad == 0);
    rec[W * 7 + 2] = 2097152;
    t_true("order3 refuses a record whose triple reaches 2^21", !mesh_order3(rec, W, N, order));
    free(rec), free(order), free(ref);
  }
  /* mesh_key3: its order is the triples' lexicographic order; a cell index
   * of 2^21 or more has no key */
  uint64_t a, b, c;
  t_true("key3 (1, 2, 3) < (1, 3, 0) < (2, 0, 0)",
         mesh_key3(1, 2, 3, &a) && mesh_key3(1, 3, 0, &b) && mesh_key3(2, 0, 0, &c) && a < b && b < c);
  t_true("key3 of the largest indices that fit orders below (2^21-1, 2^21-1, 2^21-1)",
         mesh_key3(2097150, 2097151, 2097151, &a) && mesh_key3(2097151, 2097151, 2097151, &b) && a < b);
  t_true("key3 refuses an index of 2^21", !mesh_key3(0, 1, 2097152, &a));
  return t_finish(NULL);
}
