/* The host's polygonisation passes (marching tetrahedra on the Kuhn
 * decomposition) as shaders/mesh/weld_count/rowscan/vert/tri.comp, and the
 * scan of the per-row counts that both paths use (docs/weld.md). */
#include "weld_internal.h"

/* As weld_tables.glsl. */
static const uint32_t KUHN[24] = {0, 1, 3, 7, 0, 2, 6, 7, 0, 4, 5, 7, 0, 1, 7, 5, 0, 2, 7, 3, 0, 4, 7, 6};
static const uint32_t EVEN_LONE[16] = {0, 1, 2, 3, 1, 0, 3, 2, 2, 0, 1, 3, 3, 0, 2, 1};
static const uint32_t EVEN_PAIR[64] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3, 0, 0, 0, 0, 0, 2,
                                       3, 1, 1, 2, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 1, 2, 1, 3, 2, 0,
                                       0, 0, 0, 0, 2, 3, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};

static uint32_t tet_tris(uint32_t n) { return n == 2 ? 2 : (n & 1); }

static uint32_t cube_triangles(uint32_t cube) {
  uint32_t t = 0;
  for (uint32_t k = 0; k < 6; k++) {
    uint32_t n = 0;
    for (uint32_t j = 0; j < 4; j++) n += (cube >> KUHN[4 * k + j]) & 1;
    t += tet_tris(n);
  }
  return t;
}

uint32_t weld_count_node(const weld_grid *g, const double *field, size_t i) {
  uint32_t nx = g->n[0], ny = g->n[1], nz = g->n[2];
  uint32_t x = (uint32_t)(i % nx), y = (uint32_t)(i / nx % ny), z = (uint32_t)(i / nx / ny);
  int in0 = field[i] < 0.0;
  uint32_t cube = 0, valid = 0;
  for (uint32_t c = 0; c < 8; c++) {
    uint32_t x1 = x + (c & 1), y1 = y + ((c >> 1) & 1), z1 = z + (c >> 2);
    if (x1 < nx && y1 < ny && z1 < nz) {
      valid |= 1u << c;
      if (field[x1 + (size_t)nx * (y1 + (size_t)ny * z1)] < 0.0) cube |= 1u << c;
    }
  }
  uint32_t w = in0 ? WP_INSIDE : 0;
  uint32_t diff = (cube ^ (in0 ? 255u : 0u)) & valid;
  w |= (diff >> 1) & 127u;
  uint32_t t = valid == 255u ? cube_triangles(cube) : 0;
  return w | t << WP_TRI_SHIFT;
}

void weld_rowscan_row(const weld_grid *g, const uint32_t *packed, uint32_t r, const uint32_t base[3], uint32_t *vbase,
                      uint32_t *vnode, uint32_t *clist, uint32_t *ctri) {
  uint32_t v = base[0], t = base[1], c = base[2];
  for (uint32_t x = 0; x < g->n[0]; x++) {
    size_t i = x + (size_t)g->n[0] * r;
    uint32_t w = packed[i], n = (uint32_t)__builtin_popcount(w & 127u);
    if (n) {
      vbase[i] = v;
      for (uint32_t k = 0; k < n; k++) vnode[v + k] = (uint32_t)i;
      v += n;
    }
    uint32_t nt = (w >> WP_TRI_SHIFT) & 15u;
    if (nt) clist[c] = (uint32_t)i, ctri[c] = t, c++, t += nt;
  }
}

void weld_vertex(const weld_grid *g, const double *field, const uint32_t *nnear, const uint32_t *packed,
                 const uint32_t *vbase, const uint32_t *vnode, uint32_t v, double *pos, uint32_t *nearest) {
  uint32_t nx = g->n[0], ny = g->n[1];
  size_t i = vnode[v];
  uint32_t w = packed[i] & 127u, k = v - vbase[i];
  for (uint32_t j = 0; j < k; j++) w &= w - 1;
  uint32_t e = (uint32_t)__builtin_ctz(w) + 1;
  uint32_t x = (uint32_t)(i % nx), y = (uint32_t)(i / nx % ny), z = (uint32_t)(i / nx / ny);
  double h = g->h, f0 = field[i];
  double px = g->lo[0] + h * (double)x, py = g->lo[1] + h * (double)y, pz = g->lo[2] + h * (double)z;
  uint32_t dx = e & 1, dy = (e >> 1) & 1, dz = e >> 2;
  double f1 = field[i + dx + (size_t)nx * (dy + (size_t)ny * dz)];
  double t = f0 / (f0 - f1);
  t = weld_min(weld_max(t, WELD_TMIN), 1.0 - WELD_TMIN);
  double qx = px + t * (h * (double)dx), qy = py + t * (h * (double)dy), qz = pz + t * (h * (double)dz);
  uint32_t c0 = nnear[i], c1 = nnear[i + dx + (size_t)nx * (dy + (size_t)ny * dz)];
  if (c1 < c0) {
    uint32_t tmp = c0;
    c0 = c1, c1 = tmp;
  }
  uint32_t best = c0;
  if (c1 != UINT32_MAX && c1 != c0 &&
      weld_capsule_sdf(g->cap + (size_t)c1 * WC_STRIDE, qx, qy, qz) <
          weld_capsule_sdf(g->cap + (size_t)c0 * WC_STRIDE, qx, qy, qz) - 0x1p-30 * g->h)
    best = c1;
  pos[3 * (size_t)v] = qx, pos[3 * (size_t)v + 1] = qy, pos[3 * (size_t)v + 2] = qz;
  nearest[v] = best;
}

static size_t node_of(const weld_grid *g, uint32_t x, uint32_t y, uint32_t z, uint32_t c) {
  return (x + (c & 1)) + (size_t)g->n[0] * ((y + ((c >> 1) & 1)) + (size_t)g->n[1] * (z + (c >> 2)));
}

static uint32_t edge_vertex(const weld_grid *g, const uint32_t *packed, const uint32_t *vbase, uint32_t x,
                            uint32_t y, uint32_t z, uint32_t ca, uint32_t cb) {
  uint32_t lo = (ca & cb) == ca ? ca : cb, type = ca ^ cb;
  size_t n = node_of(g, x, y, z, lo);
  return vbase[n] + (uint32_t)__builtin_popcount(packed[n] & ((1u << (type - 1)) - 1));
}

void weld_cell_tris(const weld_grid *g, const uint32_t *packed, const uint32_t *vbase, size_t i, uint32_t t,
                    uint32_t *tri) {
  uint32_t nx = g->n[0], ny = g->n[1];
  uint32_t x = (uint32_t)(i % nx), y = (uint32_t)(i / nx % ny), z = (uint32_t)(i / nx / ny);
  uint32_t in8 = 0;
  for (uint32_t c = 0; c < 8; c++)
    if (packed[node_of(g, x, y, z, c)] & WP_INSIDE) in8 |= 1u << c;
  for (uint32_t k = 0; k < 6; k++) {
    const uint32_t *q = KUHN + 4 * k;
    uint32_t m = 0, n = 0;
    for (uint32_t j = 0; j < 4; j++)
      if ((in8 >> q[j]) & 1) m |= 1u << j, n++;
    if (n == 0 || n == 4) continue;
    uint32_t *o3 = tri + 3 * (size_t)t;
    if (n == 2) {
      const uint32_t *o = EVEN_PAIR + 4 * m;
      uint32_t ik = edge_vertex(g, packed, vbase, x, y, z, q[o[0]], q[o[2]]);
      uint32_t il = edge_vertex(g, packed, vbase, x, y, z, q[o[0]], q[o[3]]);
      uint32_t jl = edge_vertex(g, packed, vbase, x, y, z, q[o[1]], q[o[3]]);
      uint32_t jk = edge_vertex(g, packed, vbase, x, y, z, q[o[1]], q[o[2]]);
      o3[0] = ik, o3[1] = il, o3[2] = jl;
      o3[3] = ik, o3[4] = jl, o3[5] = jk;
      t += 2;
    } else {
      uint32_t lone = n == 1 ? m : (~m & 15u);
      const uint32_t *o = EVEN_LONE + 4 * (uint32_t)__builtin_ctz(lone);
      uint32_t a = edge_vertex(g, packed, vbase, x, y, z, q[o[0]], q[o[1]]);
      uint32_t b = edge_vertex(g, packed, vbase, x, y, z, q[o[0]], q[o[2]]);
      uint32_t c = edge_vertex(g, packed, vbase, x, y, z, q[o[0]], q[o[3]]);
      o3[0] = a, o3[1] = n == 1 ? b : c, o3[2] = n == 1 ? c : b;
      t += 1;
    }
  }
}

sessile_status weld_scan_rows(uint32_t *rows, uint32_t nrows, uint32_t tot[3]) {
  uint64_t sum[3] = {0, 0, 0};
  for (uint32_t r = 0; r < nrows; r++)
    for (int k = 0; k < 3; k++) {
      uint32_t c = rows[3 * r + k];
      rows[3 * r + k] = (uint32_t)sum[k];
      sum[k] += c;
    }
  SESSILE_CHECK(sum[0] < UINT32_MAX && 3 * sum[1] < UINT32_MAX, SESSILE_ERR_NO_MEMORY,
                "welded surface: %llu vertices and %llu triangles exceed 32-bit indices; use a larger cell",
                (unsigned long long)sum[0], (unsigned long long)sum[1]);
  for (int k = 0; k < 3; k++) tot[k] = (uint32_t)sum[k];
  return SESSILE_OK;
}
