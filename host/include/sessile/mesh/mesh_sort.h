/* sessile — the mesh layer's sorts (host/mesh/mesh_sort.c): radix sorts of
 * 64-bit keys and the stable order of triangle-like records, shared by the
 * surface code and the SDS complex (one sort, so both order alike). */
#ifndef SESSILE_MESH_SORT_H
#define SESSILE_MESH_SORT_H
#include <stddef.h>
#include <stdint.h>

/* Ascending LSD radix sort of n 64-bit keys; tmp has room for n keys. */
void mesh_sort_u64(uint64_t *keys, uint64_t *tmp, size_t n);
/* The same, stable, carrying a 32-bit payload per key (idx); ktmp and itmp
 * have room for n each.  Equal keys keep their order. */
void mesh_sort_u64_idx(uint64_t *keys, uint32_t *idx, uint64_t *ktmp, uint32_t *itmp, size_t n);
/* The key of an ascending triple whose entries are below 2^21 (0 if one is
 * not): sorting by it sorts by (a, b, c). */
int mesh_key3(uint32_t a, uint32_t b, uint32_t c, uint64_t *key);
/* The stable order of n records of `stride` words whose first three words
 * are an ascending triple below 2^21, sorted by the triple (order[i]: the
 * record at rank i; ties keep the records' order); 0 when a triple does not
 * fit the key or memory is short. */
int mesh_order3(const uint32_t *rec, size_t stride, size_t n, uint32_t *order);

#endif
