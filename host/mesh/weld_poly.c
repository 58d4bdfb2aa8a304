/* The host's polygonisation passes (marching tetrahedra on the Kuhn
 * decomposition), row by row as shaders/mesh/weld_count/vert/tri.comp, and
 * the scan of the per-row counts that both paths use (docs/weld.md). */
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

static int inside_at(const weld_grid *g, const double *field, uint32_t x, uint32_t y, uint32_t z) {
  return field[x + (size_t)g->n[0] * (y + (size_t)g->n[1] * z)] < 0.0;
}

void weld_count_row(const weld_grid *g, const double *field, uint32_t r, uint32_t *packed, uint32_t rows[2]) {
  uint32_t nx = g->n[0], ny = g->n[1], nz = g->n[2];
  uint32_t y = r % ny, z = r / ny, nv = 0, nt = 0;
  for (uint32_t x = 0; x < nx; x++) {
    int in0 = inside_at(g, field, x, y, z);
    uint32_t w = in0 ? WP_INSIDE : 0;
    for (uint32_t e = 1; e < 8; e++) {
      uint32_t x1 = x + (e & 1), y1 = y + ((e >> 1) & 1), z1 = z + (e >> 2);
      if (x1 < nx && y1 < ny && z1 < nz && inside_at(g, field, x1, y1, z1) != in0) w |= 1u << (e - 1);
    }
    if (x + 1 < nx && y + 1 < ny && z + 1 < nz) {
      uint32_t cube = 0;
      for (uint32_t c = 0; c < 8; c++)
        if (inside_at(g, field, x + (c & 1), y + ((c >> 1) & 1), z + (c >> 2))) cube |= 1u << c;
      uint32_t t = cube_triangles(cube);
      w |= t << WP_TRI_SHIFT;
      nt += t;
    }
    nv += (uint32_t)__builtin_popcount(w & 127u);
    packed[x + (size_t)nx * r] = w;
  }
  rows[0] = nv, rows[1] = nt;
}

void weld_vert_row(const weld_grid *g, const double *field, const uint32_t *packed, uint32_t r, uint32_t v,
                   uint32_t *vbase, double *pos, uint32_t *nearest) {
  uint32_t nx = g->n[0], ny = g->n[1];
  uint32_t y = r % ny, z = r / ny;
  double h = g->h;
  for (uint32_t x = 0; x < nx; x++) {
    size_t i = x + (size_t)nx * r;
    uint32_t w = packed[i];
    vbase[i] = v;
    if ((w & 127u) == 0) continue;
    double f0 = field[i];
    double px = g->lo[0] + h * (double)x, py = g->lo[1] + h * (double)y, pz = g->lo[2] + h * (double)z;
    uint32_t b = weld_brick_of(g, x, y, z);
    uint32_t e0 = g->boff[b], e1 = g->boff[b + 1];
    for (uint32_t e = 1; e < 8; e++) {
      if (!(w & (1u << (e - 1)))) continue;
      uint32_t dx = e & 1, dy = (e >> 1) & 1, dz = e >> 2;
      double f1 = field[i + dx + (size_t)nx * (dy + (size_t)ny * dz)];
      double t = f0 / (f0 - f1);
      t = weld_min(weld_max(t, WELD_TMIN), 1.0 - WELD_TMIN);
      double qx = px + t * (h * (double)dx), qy = py + t * (h * (double)dy), qz = pz + t * (h * (double)dz);
      uint32_t best = UINT32_MAX;
      double bd = 0;
      for (uint32_t k = e0; k < e1; k++) {
        uint32_t c = g->blist[k];
        double d = weld_capsule_sdf(g->cap + (size_t)c * WC_STRIDE, qx, qy, qz);
        if (best == UINT32_MAX || d < bd) best = c, bd = d;
      }
      pos[3 * (size_t)v] = qx, pos[3 * (size_t)v + 1] = qy, pos[3 * (size_t)v + 2] = qz;
      nearest[v] = best;
      v++;
    }
  }
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

void weld_tri_row(const weld_grid *g, const uint32_t *packed, const uint32_t *vbase, uint32_t r, uint32_t t,
                  uint32_t *tri) {
  uint32_t nx = g->n[0], ny = g->n[1], nz = g->n[2];
  uint32_t y = r % ny, z = r / ny;
  if (y + 1 >= ny || z + 1 >= nz) return;
  for (uint32_t x = 0; x + 1 < nx; x++) {
    if (((packed[x + (size_t)nx * r] >> WP_TRI_SHIFT) & 15u) == 0) continue;
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
}

sessile_status weld_scan_rows(uint32_t *rows, uint32_t nrows, uint32_t *nv, uint32_t *nt) {
  uint64_t sv = 0, st = 0;
  for (uint32_t r = 0; r < nrows; r++) {
    uint32_t cv = rows[2 * r], ct = rows[2 * r + 1];
    rows[2 * r] = (uint32_t)sv, rows[2 * r + 1] = (uint32_t)st;
    sv += cv, st += ct;
    SESSILE_CHECK(sv < UINT32_MAX && 3 * st < UINT32_MAX, SESSILE_ERR_NO_MEMORY,
                  "welded surface: more than 2^32 vertices or triangle indices; use a larger cell");
  }
  *nv = (uint32_t)sv, *nt = (uint32_t)st;
  return SESSILE_OK;
}
