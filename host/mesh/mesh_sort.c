/* Radix sorts of 64-bit keys (O(n), no comparator calls): the edge tables of
 * the surface check (a 100k-triangle check sorts 300k half-edge keys) and
 * the SDS complex's faces after each division (mesh_order3). */
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"

/* The counts of every byte digit of the keys. */
static void histograms(const uint64_t *keys, size_t n, size_t count[8][256]) {
  memset(count, 0, 8 * 256 * sizeof(size_t));
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < 8; d++) count[d][(keys[i] >> (8 * d)) & 255]++;
}

/* The counts of one digit into its start offsets; 0 when every key shares
 * the digit (its pass would change nothing: skipped). */
static int offsets(size_t c[256], size_t n) {
  for (int b = 0; b < 256; b++)
    if (c[b] == n) return 0;
  size_t sum = 0;
  for (int b = 0; b < 256; b++) {
    size_t k = c[b];
    c[b] = sum;
    sum += k;
  }
  return 1;
}

void mesh_sort_u64(uint64_t *keys, uint64_t *tmp, size_t n) {
  size_t count[8][256];
  histograms(keys, n, count);
  uint64_t *src = keys, *dst = tmp;
  for (int d = 0; d < 8; d++) {
    if (!offsets(count[d], n)) continue;
    for (size_t i = 0; i < n; i++) dst[count[d][(src[i] >> (8 * d)) & 255]++] = src[i];
    uint64_t *t = src;
    src = dst;
    dst = t;
  }
  if (src != keys) memcpy(keys, src, n * sizeof *keys);
}

void mesh_sort_u64_idx(uint64_t *keys, uint32_t *idx, uint64_t *ktmp, uint32_t *itmp, size_t n) {
  size_t count[8][256];
  histograms(keys, n, count);
  uint64_t *ks = keys, *kd = ktmp;
  uint32_t *is = idx, *id = itmp;
  for (int d = 0; d < 8; d++) {
    if (!offsets(count[d], n)) continue;
    for (size_t i = 0; i < n; i++) {
      size_t at = count[d][(ks[i] >> (8 * d)) & 255]++;
      kd[at] = ks[i], id[at] = is[i];
    }
    uint64_t *kt = ks;
    ks = kd, kd = kt;
    uint32_t *it = is;
    is = id, id = it;
  }
  if (ks != keys) memcpy(keys, ks, n * sizeof *keys), memcpy(idx, is, n * sizeof *idx);
}

int mesh_key3(uint32_t a, uint32_t b, uint32_t c, uint64_t *key) {
  if ((a | b | c) >> 21) return 0;
  *key = (uint64_t)a << 42 | (uint64_t)b << 21 | c;
  return 1;
}

int mesh_order3(const uint32_t *rec, size_t stride, size_t n, uint32_t *order) {
  if (n >= UINT32_MAX) return 0;
  uint64_t *k = malloc((2 * n + 1) * sizeof *k);
  uint32_t *tmp = malloc((n + 1) * sizeof *tmp);
  int ok = k && tmp;
  for (size_t i = 0; ok && i < n; i++) {
    const uint32_t *r = rec + i * stride;
    ok = mesh_key3(r[0], r[1], r[2], k + i);
    order[i] = (uint32_t)i;
  }
  if (ok) mesh_sort_u64_idx(k, order, k + n, tmp, n);
  free(k), free(tmp);
  return ok;
}
