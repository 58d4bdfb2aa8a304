/* Test meshes for the renderer's tests: a cube with one vertex per face
 * corner (so every face's computed normal is the face normal exactly), an
 * icosphere, and pixel helpers. */
#ifndef TEST_RENDER_SHAPES_H
#define TEST_RENDER_SHAPES_H
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The cube lo..lo+edge: 24 vertices, 12 triangles, counter-clockwise from outside. */
static void shape_cube(double lo, double edge, double pos[72], uint32_t tri[36]) {
  /* each face: normal axis, sign; corners in counter-clockwise order seen from outside */
  static const int quad[6][4][3] = {
      {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, /* +x */
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, /* -x */
      {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, /* +y */
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, /* -y */
      {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, /* +z */
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, /* -z */
  };
  for (int f = 0; f < 6; f++) {
    for (int c = 0; c < 4; c++)
      for (int k = 0; k < 3; k++) pos[3 * (4 * f + c) + k] = lo + edge * quad[f][c][k];
    uint32_t b = (uint32_t)(4 * f);
    uint32_t t[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
    memcpy(tri + 6 * f, t, sizeof t);
  }
}

/* An icosphere of radius r about the origin: level subdivisions of the
 * icosahedron, midpoints pushed to the sphere (vertices are duplicated on
 * shared edges: harmless for rendering, the normals are radial anyway).
 * Returns the triangle count; *pos and *tri are malloc'ed. */
static uint32_t shape_icosphere(int level, double r, double **pos_out, uint32_t **tri_out,
                                uint32_t *nv_out) {
  const double p = (1 + sqrt(5.0)) / 2;
  double v[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                     {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  static const int f0[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  uint32_t nf = 20;
  for (int l = 0; l < level; l++) nf *= 4;
  double *tris = malloc(sizeof(double) * 9 * nf); /* corner positions per triangle */
  for (int f = 0; f < 20; f++)
    for (int c = 0; c < 3; c++)
      for (int k = 0; k < 3; k++) tris[9 * f + 3 * c + k] = v[f0[f][c]][k];
  uint32_t cur = 20;
  for (int l = 0; l < level; l++) {
    for (int64_t f = (int64_t)cur - 1; f >= 0; f--) { /* in place, from the end */
      double a[3], b[3], c[3], ab[3], bc[3], ca[3];
      for (int k = 0; k < 3; k++) {
        a[k] = tris[9 * f + k];
        b[k] = tris[9 * f + 3 + k];
        c[k] = tris[9 * f + 6 + k];
        ab[k] = (a[k] + b[k]) / 2;
        bc[k] = (b[k] + c[k]) / 2;
        ca[k] = (c[k] + a[k]) / 2;
      }
      const double *q[4][3] = {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}};
      for (int s = 0; s < 4; s++)
        for (int cc = 0; cc < 3; cc++)
          for (int k = 0; k < 3; k++) tris[9 * (4 * f + s) + 3 * cc + k] = q[s][cc][k];
    }
    cur *= 4;
  }
  double *pos = malloc(sizeof(double) * 9 * nf);
  uint32_t *tri = malloc(sizeof(uint32_t) * 3 * nf);
  for (uint32_t i = 0; i < 3 * nf; i++) {
    double *x = tris + 3 * i;
    double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int k = 0; k < 3; k++) pos[3 * i + k] = r * x[k] / l;
    tri[i] = i;
  }
  free(tris);
  *pos_out = pos;
  *tri_out = tri;
  *nv_out = 3 * nf;
  return nf;
}

/* Pixels whose RGB differs from the background's. */
static long count_not_bg(const unsigned char *px, uint32_t w, uint32_t h, const unsigned char bg[3]) {
  long n = 0;
  for (size_t i = 0; i < (size_t)w * h; i++)
    if (px[4 * i] != bg[0] || px[4 * i + 1] != bg[1] || px[4 * i + 2] != bg[2]) n++;
  return n;
}

/* World point (cm) to pixel through a column-major clip_from_world. */
static void project(const double M[16], const double p[3], uint32_t w, uint32_t h, double *x, double *y) {
  double c[4];
  for (int i = 0; i < 4; i++) c[i] = M[i] * p[0] + M[4 + i] * p[1] + M[8 + i] * p[2] + M[12 + i];
  *x = (c[0] / c[3] + 1) * w / 2;
  *y = (c[1] / c[3] + 1) * h / 2;
}
#endif
