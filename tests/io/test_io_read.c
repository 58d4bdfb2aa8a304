/* The io readers (sessile/io/io_read.h): files written by the io writers read
 * back to the same content (PLY binary with normals and a property, the
 * same as ascii and big-endian, OBJ exactly, an EXR plane's channels and
 * attributes), and hostile files each refused with one message that names
 * the file and the fault: absurd or short counts, short and long records,
 * data after the last element, non-finite coordinates, indices out of
 * range or overflowing, a FIFO (refused without blocking: an alarm fails a
 * hang) and a 2 GiB sparse file of zeros (refused from its first bytes). */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "sessile/io/io.h"
#include "sessile/io/io_read.h"
#include "testutil.h"

static char T[256];

static char *P(const char *name) {
  static char buf[8][512];
  static int k;
  k = (k + 1) % 8;
  snprintf(buf[k], sizeof buf[k], "%s/%s", T, name);
  return buf[k];
}

static void write_bytes(const char *name, const void *data, size_t n) {
  FILE *f = fopen(P(name), "wb");
  if (f) fwrite(data, 1, n, f), fclose(f);
}
static void write_text(const char *name, const char *text) { write_bytes(name, text, strlen(text)); }

typedef sessile_status (*reader_fn)(const char *, const sessile_mesh_read_opts *, sessile_mesh_in *);

/* A refusal: SESSILE_ERR_USAGE, nothing kept, the message names the file
 * and holds `want` (and not `never`, when given). */
static void refused(const char *what, reader_fn rd, const char *name, const sessile_mesh_read_opts *o,
                    const char *want, const char *never) {
  sessile_mesh_in m;
  sessile_status s = rd(P(name), o, &m);
  const char *msg = sessile_error_message();
  char line[300];
  snprintf(line, sizeof line, "refused: %s (\"%s\")", what, want);
  t_true(line, s == SESSILE_ERR_USAGE && m.pos == NULL && m.tri == NULL && strstr(msg, name) &&
                   strstr(msg, want) && !(never && strstr(msg, never)));
  printf("  message: %s\n", msg);
}

/* --- round trips ---------------------------------------------------------------- */
static void test_ply_round_trip(const sessile_surface *s, const double *nrm) {
  double *q = malloc(s->nv * sizeof *q);
  for (uint32_t v = 0; v < s->nv; v++) q[v] = 0.5 * v - 3;
  const char *names[1] = {"q"};
  const double *extra[1] = {q};
  t_ok("write a PLY with normals and a property", sessile_write_ply(P("s.ply"), s, nrm, 1, names, extra));
  sessile_mesh_read_opts o = {.keep_props = 1};
  sessile_mesh_in m;
  t_ok("read it back", sessile_read_ply(P("s.ply"), &o, &m));
  int same = m.nv == s->nv && m.nf == s->nf && m.normal && m.nprops == 1 && !strcmp(m.prop_names[0], "q");
  for (size_t i = 0; same && i < 3 * (size_t)s->nv; i++)
    same = m.pos[i] == (double)(float)s->pos[i] && m.normal[i] == (float)nrm[i];
  for (size_t i = 0; same && i < 3 * (size_t)s->nf; i++) same = m.tri[i] == s->tri[i];
  for (uint32_t v = 0; same && v < s->nv; v++) same = m.props[0][v] == (float)q[v];
  t_true("binary PLY: the written vertices (as float), normals, property and triangles", same);

  /* the same mesh as ascii (one record a line, %.9g: float exact) and big-endian */
  size_t cap = 200 + 80 * (size_t)s->nv + 40 * (size_t)s->nf, n = 0;
  char *txt = malloc(cap);
  n += (size_t)snprintf(txt + n, cap - n,
                        "ply\r\nformat ascii 1.0\r\ncomment x\r\nelement vertex %u\r\nproperty float x\r\n"
                        "property float y\r\nproperty double z\r\nelement face %u\r\n"
                        "property list uchar int vertex_indices\r\nend_header\r\n",
                        s->nv, s->nf);
  for (uint32_t v = 0; v < s->nv; v++)
    n += (size_t)snprintf(txt + n, cap - n, "%.9g %.9g\t%.17g\n", (float)s->pos[3 * v], (float)s->pos[3 * v + 1],
                          s->pos[3 * v + 2]);
  for (uint32_t f = 0; f < s->nf; f++)
    n += (size_t)snprintf(txt + n, cap - n, "3 %u %u %u\n", s->tri[3 * f], s->tri[3 * f + 1], s->tri[3 * f + 2]);
  n += (size_t)snprintf(txt + n, cap - n, "\n\n");
  write_bytes("a.ply", txt, n);
  sessile_mesh_in a;
  t_ok("ascii PLY reads", sessile_read_ply(P("a.ply"), NULL, &a));
  same = a.nv == s->nv && a.nf == s->nf && !a.normal && a.nprops == 0;
  for (uint32_t v = 0; same && v < s->nv; v++)
    same = (float)a.pos[3 * v] == (float)s->pos[3 * v] && a.pos[3 * v + 2] == s->pos[3 * v + 2];
  for (size_t i = 0; same && i < 3 * (size_t)s->nf; i++) same = a.tri[i] == s->tri[i];
  t_true("ascii PLY: the same vertices (%.9g floats as floats, a %.17g double column exactly) and triangles", same);

  n = (size_t)snprintf(txt, cap,
                       "ply\nformat binary_big_endian 1.0\nelement vertex %u\nproperty float x\nproperty float y\n"
                       "property float z\nelement face %u\nproperty list uchar uint vertex_indices\nend_header\n",
                       s->nv, s->nf);
  for (size_t i = 0; i < 3 * (size_t)s->nv; i++) {
    float f = (float)s->pos[i];
    uint32_t u;
    memcpy(&u, &f, 4);
    for (int b = 3; b >= 0; b--) txt[n++] = (char)(u >> (8 * b));
  }
  for (size_t f = 0; f < s->nf; f++) {
    txt[n++] = 3;
    for (int k = 0; k < 3; k++)
      for (int b = 3; b >= 0; b--) txt[n++] = (char)(s->tri[3 * f + (size_t)k] >> (8 * b));
  }
  write_bytes("be.ply", txt, n);
  sessile_mesh_in b;
  t_ok("big-endian PLY reads", sessile_read_ply(P("be.ply"), NULL, &b));
  same = b.nv == s->nv && b.nf == s->nf;
  for (size_t i = 0; same && i < 3 * (size_t)s->nv; i++) same = b.pos[i] == m.pos[i];
  for (size_t i = 0; same && i < 3 * (size_t)s->nf; i++) same = b.tri[i] == s->tri[i];
  t_true("big-endian PLY: the same as the little-endian file", same);
  sessile_mesh_in_free(&m);
  sessile_mesh_in_free(&a);
  sessile_mesh_in_free(&b);
  free(txt);
  free(q);
}

static void test_obj_round_trip(const sessile_surface *s, const double *nrm) {
  t_ok("write an OBJ with normals", sessile_write_obj(P("s.obj"), s, nrm));
  sessile_mesh_in m;
  t_ok("read it back", sessile_read_obj(P("s.obj"), NULL, &m));
  int same = m.nv == s->nv && m.nf == s->nf && !m.normal;
  for (size_t i = 0; same && i < 3 * (size_t)s->nv; i++) same = m.pos[i] == s->pos[i];
  for (size_t i = 0; same && i < 3 * (size_t)s->nf; i++) same = m.tri[i] == s->tri[i];
  t_true("OBJ: the written vertices exactly (v//n corners) and triangles", same);
  sessile_mesh_in_free(&m);
  write_text("q.obj", "# a quad and a triangle, negative and v/t/n indices\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                      "v 0 1 0 1\nvt 0 0\nf 1/1 2/1 3/1 4/1\nf -4//1 -2//1 -1//1\n");
  t_ok("a quad and negative indices read", sessile_read_obj(P("q.obj"), NULL, &m));
  const uint32_t want[9] = {0, 1, 2, 0, 2, 3, 0, 2, 3};
  t_true("the quad split into a fan, the negative indices counted from the last vertex",
         m.nv == 4 && m.nf == 3 && !memcmp(m.tri, want, sizeof want));
  sessile_mesh_in_free(&m);
}

static double chan_value(int c, uint32_t i, uint32_t j) { return c == 0 ? 0.25 * i - j : sin(0.1 * i) * j; }

static void test_exr_round_trip(void) {
  sessile_plane pl = {.origin = {1, 2, 3}, .axis_u = {1, 0, 0}, .axis_v = {0, 0, 2}, .spacing = {0.5, 0.25},
                      .width = 13, .height = 7};
  double *v[2];
  for (int c = 0; c < 2; c++) {
    v[c] = malloc(13 * 7 * sizeof(double));
    for (uint32_t j = 0; j < 7; j++)
      for (uint32_t i = 0; i < 13; i++) v[c][i + 13 * j] = chan_value(c, i, j);
  }
  const char *names[2] = {"c", "w"};
  t_ok("write an EXR plane", sessile_write_plane_exr_values(P("p.exr"), &pl, "test plane", 2, names,
                                                            (const double *const *)v, 5));
  sessile_exr_in *x = NULL;
  t_ok("open it", sessile_exr_open(P("p.exr"), &x));
  if (x) {
    const sessile_slice_header *h = sessile_exr_header(x);
    t_true("the header: plane, origin, spacing, axes, iteration, size, channels",
           !strcmp(h->plane, "test plane") && h->has_origin && h->origin[1] == 2 && h->has_spacing &&
               h->spacing[1] == 0.25 && h->has_axes && h->axis_v[2] == 1 && h->iteration == 5 && h->width == 13 &&
               h->height == 7 && h->nchannels == 5 && h->scanline && h->top_down && h->has_view);
    char list[64];
    sessile_exr_channel_list(x, list, sizeof list);
    t_true("the channel list: the data's, not the view's R, G, B",
           !strcmp(list, "c, w") && sessile_exr_find_channel(x, "w") == 4 && sessile_exr_find_channel(x, "R") == 2 &&
               sessile_exr_find_channel(x, "q") == -1 && sessile_exr_channel_is_float(x, 3));
    float *got[2] = {malloc(13 * 7 * sizeof(float)), malloc(13 * 7 * sizeof(float))};
    const char *want[2] = {"w", "c"};
    float *const dst[2] = {got[1], got[0]};
    t_ok("read both channels", sessile_exr_read_channels(x, 2, want, dst));
    int same = 1;
    for (int c = 0; c < 2; c++)
      for (int i = 0; i < 13 * 7 && same; i++) same = got[c][i] == (float)v[c][i];
    t_true("every pixel of both channels as written (row 0 at the low end of v, the file top-down)", same);
    free(got[0]), free(got[1]);
    sessile_exr_close(x);
  }
  free(v[0]), free(v[1]);
  sessile_exr_in *y = NULL;
  write_text("t.exr", "not an image\n");
  t_true("a text file: not an EXR, named", sessile_exr_open(P("t.exr"), &y) == SESSILE_ERR_USAGE && !y &&
                                              strstr(sessile_error_message(), "t.exr") &&
                                              strstr(sessile_error_message(), "not an EXR"));
}

/* --- hostile files -------------------------------------------------------------- */
static const char *HDR = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

static void ply_body(const char *name, const char *body) {
  char buf[1024];
  snprintf(buf, sizeof buf, "%s%s", HDR, body);
  write_text(name, buf);
}

static void test_hostile_ply(void) {
  write_text("max.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n"
                        "property float x\nproperty float y\nproperty float z\nend_header\n");
  refused("2^64-1 vertices", sessile_read_ply, "max.ply", NULL,
          "line 3: declares 18446744073709551615 vertices (at most 4294967294)", NULL);
  write_text("over.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n");
  refused("a count past 2^64, quoted as written", sessile_read_ply, "over.ply", NULL,
          "declares 99999999999999999999999 vertices", NULL);
  sessile_mesh_read_opts small = {.max_vertices = 2, .max_faces = 4};
  ply_body("lim.ply", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  refused("a count over the caller's limit", sessile_read_ply, "lim.ply", &small, "declares 3 vertices (at most 2)",
          NULL);
  write_text("faces.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 4000000000\n"
                          "property list uchar int vertex_indices\nend_header\n");
  refused("too many faces", sessile_read_ply, "faces.ply", NULL, "declares 4000000000 faces (at most", NULL);
  write_text("room.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n0123456789");
  refused("a count larger than the file", sessile_read_ply, "room.ply", NULL,
          "element vertex declares 1000 records but only 10 bytes follow", NULL);
  ply_body("short.ply", "0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  refused("a short row", sessile_read_ply, "short.ply", NULL, "line 11 (vertex 1 of 3): a short record (no value for z)",
          NULL);
  ply_body("long.ply", "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n");
  refused("a row with an extra value", sessile_read_ply, "long.ply", NULL,
          "line 11 (vertex 1 of 3): more values than the header declares ('7'", NULL);
  ply_body("extra.ply", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n");
  refused("an extra row", sessile_read_ply, "extra.ply", NULL, "line 14: data after the last element", NULL);
  ply_body("few.ply", "0 0 0\n1 0 0\n");
  refused("missing rows", sessile_read_ply, "few.ply", NULL, "the file ends after 2 of the 3 vertex records", NULL);
  ply_body("word.ply", "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  refused("a word for a number", sessile_read_ply, "word.ply", NULL, "'zero' is not a number (y)", NULL);
  ply_body("nan.ply", "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  refused("a NaN coordinate", sessile_read_ply, "nan.ply", NULL, "line 11 (vertex 1 of 3): coordinate y is nan", NULL);
  ply_body("inf.ply", "0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n");
  refused("an infinite coordinate", sessile_read_ply, "inf.ply", NULL, "coordinate z is -inf (not finite)", NULL);
  ply_body("idx.ply", "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  refused("an index out of range", sessile_read_ply, "idx.ply", NULL, "line 13 (face 0 of 1): vertex index 3 names no vertex (3 vertices)",
          NULL);
  ply_body("neg.ply", "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  refused("a negative index", sessile_read_ply, "neg.ply", NULL, "vertex index -1 names no vertex", NULL);
  ply_body("quad.ply", "0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n");
  const sessile_mesh_read_opts tri = {.triangles_only = 1};
  refused("a quad where only triangles are read", sessile_read_ply, "quad.ply", &tri, "4 corners (only triangles", NULL);
  write_text("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n");
  refused("an unknown format", sessile_read_ply, "fmt.ply", NULL, "line 2: unknown PLY format", NULL);

  /* binary: a body that ends early, and bytes after the last element */
  char bin[512];
  int n = snprintf(bin, sizeof bin, "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                                    "property float y\nproperty float z\nend_header\n");
  memset(bin + n, 0, 16);
  write_bytes("trail.ply", bin, (size_t)n + 16);
  refused("binary: bytes after the last element", sessile_read_ply, "trail.ply", NULL, "4 bytes after the last element",
          NULL);
  float nanf3[3] = {0, NAN, 0};
  memcpy(bin + n, nanf3, 12);
  write_bytes("bnan.ply", bin, (size_t)n + 12);
  refused("binary: a NaN coordinate", sessile_read_ply, "bnan.ply", NULL, "vertex 0 of 1: coordinate y is nan", NULL);
}

static void test_hostile_obj(void) {
  write_text("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n");
  refused("an index past 2^63, quoted as written", sessile_read_obj, "big.obj", NULL,
          "line 4: face index 99999999999999999999 refers to no vertex (3 so far)", "9223372036854775807");
  write_text("back.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9999999999999999999999/2\n");
  refused("a negative index past -2^63", sessile_read_obj, "back.obj", NULL,
          "face index -9999999999999999999999 refers to no vertex", "-9223372036854775808");
  write_text("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  refused("a NaN coordinate", sessile_read_obj, "nan.obj", NULL, "line 2: coordinate y is 'nan' (not finite)", NULL);
  write_text("two.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n");
  refused("a vertex of two numbers", sessile_read_obj, "two.obj", NULL, "line 2: a vertex needs x y z", NULL);
  write_text("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
  refused("index 0", sessile_read_obj, "zero.obj", NULL, "line 4: bad face index '0'", NULL);
  char *line = malloc(70000);
  memset(line, '1', 70000);
  memcpy(line, "f ", 2);
  line[69999] = 0;
  write_text("longf.obj", line);
  refused("an f line over 64 KiB", sessile_read_obj, "longf.obj", NULL, "line 1: a 'f' line of 65535 characters or more",
          NULL);
  /* a long comment is no fault */
  line[0] = '#';
  FILE *f = fopen(P("longc.obj"), "w");
  if (f) fprintf(f, "%s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", line), fclose(f);
  sessile_mesh_in m;
  t_ok("a comment over 64 KiB is skipped", sessile_read_obj(P("longc.obj"), NULL, &m));
  t_true("... and the mesh after it read (line numbers kept)", m.nv == 3 && m.nf == 1);
  sessile_mesh_in_free(&m);
  free(line);
  write_bytes("nul.obj", "v 0 0 0\nv 1\0 0 0\n", 17);
  refused("a NUL byte", sessile_read_obj, "nul.obj", NULL, "line 2 holds a NUL byte", NULL);
}

static void on_alarm(int sig) {
  (void)sig;
  static const char msg[] = "FAIL a reader blocked on a FIFO (alarm)\n";
  ssize_t k = write(1, msg, sizeof msg - 1);
  (void)k;
  _exit(1);
}

static void test_fifo_and_zeros(void) {
  signal(SIGALRM, on_alarm);
  alarm(20); /* a reader that blocks on the FIFO fails the test here */
  const char *fifos[3] = {"f.ply", "f.obj", "f.exr"};
  for (int k = 0; k < 3; k++) t_true("mkfifo", mkfifo(P(fifos[k]), 0600) == 0);
  refused("a FIFO as PLY, without blocking", sessile_read_ply, "f.ply", NULL, "is not a regular file", NULL);
  refused("a FIFO as OBJ, without blocking", sessile_read_obj, "f.obj", NULL, "is not a regular file", NULL);
  sessile_exr_in *x = NULL;
  t_true("a FIFO as EXR, refused without blocking",
         sessile_exr_open(P("f.exr"), &x) == SESSILE_ERR_USAGE && !x &&
             strstr(sessile_error_message(), "is not a regular file") && strstr(sessile_error_message(), "f.exr"));

  /* 2 GiB of zeros (sparse: no disk used) under each extension */
  const char *zeros[3] = {"z.ply", "z.obj", "z.exr"};
  for (int k = 0; k < 3; k++) {
    int fd = open(P(zeros[k]), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    t_true("a sparse 2 GiB file", fd >= 0 && ftruncate(fd, (off_t)2 << 30) == 0);
    if (fd >= 0) close(fd);
  }
  refused("2 GiB of zeros as PLY", sessile_read_ply, "z.ply", NULL, "not a PLY file", NULL);
  refused("2 GiB of zeros as OBJ", sessile_read_obj, "z.obj", NULL, "line 1 holds a NUL byte", NULL);
  t_true("2 GiB of zeros as EXR: not an EXR",
         sessile_exr_open(P("z.exr"), &x) == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "not an EXR"));
  for (int k = 0; k < 3; k++) unlink(P(zeros[k])), unlink(P(fifos[k]));
  alarm(0);
}

int main(void) {
  snprintf(T, sizeof T, "%s/sessile_test_io_read.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(T)) {
    printf("FAIL cannot create a scratch folder: %s\n", strerror(errno));
    return 1;
  }
  sessile_surface s = {0};
  const double c[3] = {0.5, -0.25, 1.0};
  t_must("icosphere", sessile_surface_icosphere(3, 0.75, c, &s));
  double *nrm = malloc(3 * (size_t)s.nv * sizeof *nrm);
  sessile_surface_normals(&s, nrm);
  test_ply_round_trip(&s, nrm);
  test_obj_round_trip(&s, nrm);
  test_exr_round_trip();
  test_hostile_ply();
  test_hostile_obj();
  test_fifo_and_zeros();
  free(nrm);
  sessile_surface_free(&s);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", T);
  if (system(cmd) != 0) printf("  (could not remove %s)\n", T);
  return t_finish(NULL);
}
