/* The renderer's inputs and output, without a device:
 * - one mesh (a square pyramid: a quad base split into a fan, 4 triangles,
 *   a per-vertex property) written as ASCII PLY, binary little- and
 *   big-endian PLY (with an extra element and a list property to skip) and
 *   OBJ (v/t/n corners, negative indices) reads back to the same vertices,
 *   triangles and property;
 * - the computed normals are area-weighted (checked on a vertex whose two
 *   faces differ in area) and the file's normals are used when present;
 * - bad files are refused with SESSILE_ERR_USAGE: missing, unknown
 *   extension, NaN coordinate, no faces, no vertices, an index out of
 *   range, a count larger than the file, a truncated body, a bad header;
 * - the PNG writer's bytes decode with libpng to the same pixels, 8-bit
 *   RGBA, and encode identically twice; it writes nothing into a missing
 *   folder. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "sessile/io/png.h"
#include "sessile/render/render_mesh.h"
#include "testutil.h"

static char dir[256];

static const char *path_of(const char *name) {
  static char p[4][512];
  static int k = 0;
  k = (k + 1) % 4;
  snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
  return p[k];
}

static void write_text(const char *name, const char *text) {
  FILE *f = fopen(path_of(name), "wb");
  fputs(text, f);
  fclose(f);
}

/* pyramid: base (0,0,0) (2,0,0) (2,2,0) (0,2,0), apex (1,1,1); property q = 10 v */
static const float PV[5][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 1}};
static const char *ASCII_PLY =
    "ply\nformat ascii 1.0\ncomment a test pyramid\nelement vertex 5\nproperty float x\n"
    "property float y\nproperty float z\nproperty double q\nelement face 5\n"
    "property list uchar int vertex_indices\nelement extra 1\nproperty list uchar float junk\n"
    "end_header\n0 0 0 0\n2 0 0 10\n2 2 0 20\n0 2 0 30\n1 1 1 40\n4 3 2 1 0\n3 0 1 4\n3 1 2 4\n"
    "3 2 3 4\n3 3 0 4\n2 1.5 2.5\n";

static void put(FILE *f, const void *p, size_t n, int big) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++) fputc(b[big ? n - 1 - i : i], f);
}

static void write_binary(const char *name, int big) {
  FILE *f = fopen(path_of(name), "wb");
  fprintf(f, "ply\r\nformat binary_%s_endian 1.0\r\nelement vertex 5\r\nproperty float x\r\n"
             "property float y\r\nproperty float z\r\nproperty double q\r\nelement face 5\r\n"
             "property list uchar int vertex_indices\r\nproperty uchar flag\r\nend_header\r\n",
          big ? "big" : "little");
  for (int v = 0; v < 5; v++) {
    for (int k = 0; k < 3; k++) put(f, &PV[v][k], 4, big);
    double q = 10.0 * v;
    put(f, &q, 8, big);
  }
  const int faces[5][5] = {{4, 3, 2, 1, 0}, {3, 0, 1, 4}, {3, 1, 2, 4}, {3, 2, 3, 4}, {3, 3, 0, 4}};
  for (int fc = 0; fc < 5; fc++) {
    unsigned char n = (unsigned char)faces[fc][0];
    fputc(n, f);
    for (int k = 1; k <= n; k++) {
      int32_t x = faces[fc][k];
      put(f, &x, 4, big);
    }
    fputc(7, f); /* flag */
  }
  fclose(f);
}

static void check_pyramid(const char *what, const sessile_render_mesh *m, int with_prop) {
  char msg[200];
  int ok = m && m->nv == 5 && m->nf == 6;
  for (int v = 0; ok && v < 5; v++)
    for (int k = 0; k < 3; k++) ok = ok && m->pos[3 * v + k] == PV[v][k];
  /* the quad's fan (3 2 1)(3 1 0), then the four sides */
  const uint32_t tri[18] = {3, 2, 1, 3, 1, 0, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  ok = ok && memcmp(m->tri, tri, sizeof tri) == 0;
  snprintf(msg, sizeof msg, "%s: 5 vertices, the quad split into 2 triangles + 4 sides, same positions", what);
  t_true(msg, ok);
  if (with_prop) {
    const float *q = m ? sessile_render_mesh_property(m, "q") : NULL;
    int pk = q != NULL;
    for (int v = 0; pk && v < 5; v++) pk = q[v] == 10.0f * v;
    snprintf(msg, sizeof msg, "%s: property q read as 0, 10, 20, 30, 40", what);
    t_true(msg, pk);
  }
}

static void test_readers(void) {
  sessile_render_mesh *m = NULL;
  write_text("a.ply", ASCII_PLY);
  t_ok("ascii PLY reads", sessile_render_mesh_read(path_of("a.ply"), &m));
  check_pyramid("ascii PLY", m, 1);
  /* apex normal: area-weighted mean of the 4 side normals = +z by symmetry;
   * base vertex 0 touches the base triangle (3 1 0, area 2, normal -z) and
   * sides (0 1 4) and (3 0 4) (area sqrt(2) each, normals (0,-1,1)/sqrt2 and
   * (-1,0,1)/sqrt2): sum of area x normal = (-1, -1, -2 + 2) = (-1, -1, 0) */
  if (m) {
    const float *n4 = m->normal + 12, *n0 = m->normal;
    t_check("apex normal = +z", fabs(n4[0]) + fabs(n4[1]) + fabs(n4[2] - 1), 1e-6);
    double e = fabs(n0[0] + sqrt(0.5)) + fabs(n0[1] + sqrt(0.5)) + fabs(n0[2]);
    printf("vertex 0 normal (%.6f, %.6f, %.6f), area-weighted expectation (-0.707107, -0.707107, 0)\n",
           n0[0], n0[1], n0[2]);
    t_check("base corner normal is the area-weighted mean (-1,-1,0)/sqrt2", e, 1e-6);
  }
  sessile_render_mesh_destroy(m);
  write_binary("le.ply", 0);
  t_ok("binary little-endian PLY reads", sessile_render_mesh_read(path_of("le.ply"), &m));
  check_pyramid("binary LE PLY", m, 1);
  sessile_render_mesh_destroy(m);
  write_binary("be.ply", 1);
  t_ok("binary big-endian PLY reads", sessile_render_mesh_read(path_of("be.ply"), &m));
  check_pyramid("binary BE PLY", m, 1);
  sessile_render_mesh_destroy(m);
  write_text("p.obj", "# pyramid\nv 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 1 1 1\nvt 0 0\nvn 0 0 1\n"
                      "o p\ng p\nf 4/1/1 3/1/1 2/1/1 1/1/1\nf 1//1 2//1 5//1\nf -4 -3 -1\nf 3/1 4/1 5/1\nf 4 1 5\n");
  t_ok("OBJ reads", sessile_render_mesh_read(path_of("p.obj"), &m));
  check_pyramid("OBJ", m, 0);
  sessile_render_mesh_destroy(m);
  /* file normals are used (normalised) */
  write_text("n.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
                      "0 0 0 0 0 2\n1 0 0 0 3 0\n0 1 0 4 0 0\n3 0 1 2\n");
  t_ok("PLY with normals reads", sessile_render_mesh_read(path_of("n.ply"), &m));
  if (m) {
    t_true("the file's normals are kept, normalised",
           m->has_file_normals && m->normal[2] == 1.0f && m->normal[4] == 1.0f && m->normal[6] == 1.0f &&
               m->nprops == 0);
  }
  sessile_render_mesh_destroy(m);
}

static void expect_bad(const char *what, const char *name, const char *text) {
  if (text) write_text(name, text);
  sessile_render_mesh *m = NULL;
  sessile_status s = sessile_render_mesh_read(path_of(name), &m);
  char msg[200];
  snprintf(msg, sizeof msg, "refused as USAGE: %s", what);
  t_true(msg, s == SESSILE_ERR_USAGE && m == NULL);
  printf("  message: %s\n", sessile_error_message());
}

static void test_bad(void) {
  const char *hdr = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  char buf[1024];
  expect_bad("missing file", "none.ply", NULL);
  expect_bad("unknown extension", "m.stl", "solid x\n");
  snprintf(buf, sizeof buf, "%s0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", hdr);
  expect_bad("a NaN coordinate", "nan.ply", buf);
  snprintf(buf, sizeof buf, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", hdr);
  expect_bad("an index out of range", "idx.ply", buf);
  snprintf(buf, sizeof buf, "%s0 0 0\n1 0 0\n", hdr);
  expect_bad("a truncated body", "trunc.ply", buf);
  expect_bad("no faces", "nof.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  expect_bad("no vertices", "nov.ply",
             "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
             "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n");
  expect_bad("a count larger than the file (no allocation)", "huge.ply",
             "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
             "property float y\nproperty float z\nend_header\n");
  expect_bad("a bad header", "hdr.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty vec3 p\nend_header\n");
  expect_bad("not a PLY", "not.ply", "hello\n");
  expect_bad("OBJ face before its vertices", "bad.obj", "f 1 2 3\nv 0 0 0\n");
  expect_bad("OBJ without faces", "nof.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_bad("all vertices at one point", "pt.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
}

/* Decodes with libpng (the simplified API): w, h and 8-bit RGBA pixels. */
static unsigned char *png_decode(const char *path, int *w, int *h) {
  png_image im;
  memset(&im, 0, sizeof im);
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&im, path)) return NULL;
  im.format = PNG_FORMAT_RGBA;
  unsigned char *px = malloc(PNG_IMAGE_SIZE(im));
  if (!px || !png_image_finish_read(&im, NULL, px, 0, NULL)) {
    free(px);
    png_image_free(&im);
    return NULL;
  }
  *w = (int)im.width;
  *h = (int)im.height;
  return px;
}

static void test_png(void) {
  const int w = 37, h = 23;
  unsigned char *px = malloc((size_t)w * h * 4);
  for (int i = 0; i < w * h * 4; i++) px[i] = (unsigned char)((i * 7919u) >> 3);
  t_ok("PNG written", sessile_png_write_rgba8(path_of("x.png"), w, h, px));
  int rw = 0, rh = 0;
  unsigned char *back = png_decode(path_of("x.png"), &rw, &rh);
  t_true("libpng reads it back: same size, same RGBA bytes",
         back && rw == w && rh == h && memcmp(back, px, (size_t)w * h * 4) == 0);
  free(back);
  unsigned char *a = NULL, *b = NULL;
  size_t na = 0, nb = 0;
  t_ok("encode", sessile_png_encode_rgba8(w, h, px, &a, &na));
  t_ok("encode again", sessile_png_encode_rgba8(w, h, px, &b, &nb));
  t_true("two encodings are identical bytes (no time chunk)", a && b && na == nb && memcmp(a, b, na) == 0);
  free(a);
  free(b);
  t_true("a missing folder: refused (SESSILE_ERR_IO), the message names the file",
         sessile_png_write_rgba8(path_of("no/such/x.png"), w, h, px) == SESSILE_ERR_IO &&
             strstr(sessile_error_message(), "png: ") && strstr(sessile_error_message(), "x.png"));
  printf("  message: %s\n", sessile_error_message());
  t_true("a size of 0: refused as USAGE, the size in the message",
         sessile_png_write_rgba8(path_of("z.png"), 0, h, px) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "0 x 23"));
  t_true("... and nothing written", access(path_of("z.png"), F_OK) != 0);
  free(px);
}

int main(void) {
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/sessile-test-render-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) {
    printf("FAIL cannot make a temporary folder\n");
    return 1;
  }
  test_readers();
  test_bad();
  test_png();
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) printf("note: could not remove %s\n", dir);
  return t_finish(NULL);
}
