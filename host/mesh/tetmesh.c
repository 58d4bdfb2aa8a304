/* General tetrahedral meshes of the water: storage and the structured box
 * converted (sessile/mesh/tetmesh.h).  TetGen's conforming mesh lives in
 * tetgen_shim.cpp. */
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/tetmesh.h"

void sessile_tetmesh_free(sessile_tetmesh *m) {
  if (!m) return;
  free(m->xyz);
  free(m->tet);
  free(m->node_tags);
  free(m->bface);
  free(m->bface_tag);
  memset(m, 0, sizeof *m);
}

double sessile_tetmesh_tet_volume(const sessile_tetmesh *m, uint32_t t) {
  const double *a = m->xyz + 3 * m->tet[4 * t], *b = m->xyz + 3 * m->tet[4 * t + 1],
               *c = m->xyz + 3 * m->tet[4 * t + 2], *d = m->xyz + 3 * m->tet[4 * t + 3];
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

/* The side of the box all three nodes lie on (one tag bit), or 0. */
static uint32_t face_side(const sessile_box *b, const uint32_t n[3]) {
  uint32_t ijk[3][3];
  for (int q = 0; q < 3; q++) {
    ijk[q][0] = n[q] % b->n[0];
    ijk[q][1] = (n[q] / b->n[0]) % b->n[1];
    ijk[q][2] = n[q] / (b->n[0] * b->n[1]);
  }
  static const uint32_t lo_tag[3] = {SESSILE_TAG_INLET, SESSILE_TAG_SIDE, SESSILE_TAG_SUBSTRATUM};
  static const uint32_t hi_tag[3] = {SESSILE_TAG_OUTLET, SESSILE_TAG_SIDE, SESSILE_TAG_TOP};
  for (int a = 0; a < 3; a++) {
    if (ijk[0][a] == 0 && ijk[1][a] == 0 && ijk[2][a] == 0) return lo_tag[a];
    uint32_t m = b->n[a] - 1;
    if (ijk[0][a] == m && ijk[1][a] == m && ijk[2][a] == m) return hi_tag[a];
  }
  return 0;
}

sessile_status sessile_tetmesh_from_box(const sessile_box *box, sessile_tetmesh *out) {
  memset(out, 0, sizeof *out);
  uint32_t nn = sessile_box_nodes(box), nc = sessile_box_cells(box);
  uint64_t nt = 6ull * nc;
  SESSILE_CHECK(nt < UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "box of %u cells is too large for a tet mesh", nc);
  /* Boundary faces: 2 triangles per boundary square. */
  uint64_t nx = box->n[0] - 1, ny = box->n[1] - 1, nz = box->n[2] - 1;
  uint64_t nbf = 4 * (nx * ny + nx * nz + ny * nz);
  out->xyz = malloc((size_t)nn * 3 * sizeof *out->xyz);
  out->tet = malloc((size_t)nt * 4 * sizeof *out->tet);
  out->node_tags = calloc(nn, sizeof *out->node_tags);
  out->bface = malloc((size_t)nbf * 3 * sizeof *out->bface);
  out->bface_tag = malloc((size_t)nbf * sizeof *out->bface_tag);
  if (!out->xyz || !out->tet || !out->node_tags || !out->bface || !out->bface_tag) {
    sessile_tetmesh_free(out);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a %u-node tet mesh", nn);
  }
  out->nnodes = nn;
  for (uint32_t i = 0; i < nn; i++) sessile_box_node_pos(box, i, out->xyz + 3 * i);
  /* Outward faces of a positively oriented tet (v0..v3). */
  static const int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  uint32_t t = 0, f = 0;
  for (uint32_t k = 0; k + 1 < box->n[2]; k++)
    for (uint32_t j = 0; j + 1 < box->n[1]; j++)
      for (uint32_t i = 0; i + 1 < box->n[0]; i++)
        for (int q = 0; q < 6; q++, t++) {
          uint32_t *v = out->tet + 4 * (size_t)t;
          sessile_box_tet(box, i, j, k, q, v);
          for (int s = 0; s < 4; s++) {
            uint32_t n3[3] = {v[faces[s][0]], v[faces[s][1]], v[faces[s][2]]};
            uint32_t side = face_side(box, n3);
            if (!side) continue;
            if (f >= nbf) {
              sessile_tetmesh_free(out);
              return sessile_error_set(SESSILE_ERR_INTERNAL, "box boundary has more faces than expected");
            }
            memcpy(out->bface + 3 * (size_t)f, n3, sizeof n3);
            out->bface_tag[f++] = side;
            for (int c = 0; c < 3; c++) out->node_tags[n3[c]] |= side;
          }
        }
  out->ntets = t;
  out->nbfaces = f;
  SESSILE_CHECK(f == nbf, SESSILE_ERR_INTERNAL, "box boundary has %u faces, expected %llu", f,
                (unsigned long long)nbf);
  return SESSILE_OK;
}
