/* Radix sort for the edge tables of the surface check (O(n), no comparator
 * calls: a 100k-triangle check sorts 300k half-edge keys). */
#include <string.h>
#include "mesh/mesh_internal.h"

void mesh_sort_u64(uint64_t *keys, uint64_t *tmp, size_t n) {
  size_t count[8][256];
  memset(count, 0, sizeof count);
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < 8; d++) count[d][(keys[i] >> (8 * d)) & 255]++;
  uint64_t *src = keys, *dst = tmp;
  for (int d = 0; d < 8; d++) {
    /* A digit every key shares changes nothing: skip its pass. */
    int skip = 0;
    for (int b = 0; b < 256; b++)
      if (count[d][b] == n) skip = 1;
    if (skip) continue;
    size_t sum = 0;
    for (int b = 0; b < 256; b++) {
      size_t c = count[d][b];
      count[d][b] = sum;
      sum += c;
    }
    for (size_t i = 0; i < n; i++) dst[count[d][(src[i] >> (8 * d)) & 255]++] = src[i];
    uint64_t *t = src;
    src = dst;
    dst = t;
  }
  if (src != keys) memcpy(keys, src, n * sizeof *keys);
}

void mesh_sort_u64_idx(uint64_t *keys, uint32_t *idx, uint64_t *ktmp, uint32_t *itmp, size_t n) {
  size_t count[8][256];
  memset(count, 0, sizeof count);
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < 8; d++) count[d][(keys[i] >> (8 * d)) & 255]++;
  uint64_t *ks = keys, *kd = ktmp;
  uint32_t *is = idx, *id = itmp;
  for (int d = 0; d < 8; d++) {
    int skip = 0;
    for (int b = 0; b < 256; b++)
      if (count[d][b] == n) skip = 1;
    if (skip) continue;
    size_t sum = 0;
    for (int b = 0; b < 256; b++) {
      size_t c = count[d][b];
      count[d][b] = sum;
      sum += c;
    }
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
