/* The run directory's writers: atomic semantics (failures leave nothing,
 * abort leaves nothing, commit replaces), PLY/OBJ read back by small parsers
 * here, EXR slices read back with OpenEXR's C API and compared with the P1
 * interpolant of the box field on the plane, and determinism (two writes give
 * identical bytes).  The .vtu/.pvd and the independent readers are checked by
 * test_readers.sh. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include "sessile/io.h"
#include "testutil.h"

static char T[256]; /* scratch folder */

static char *P(const char *name) { /* T/name, from a small ring of buffers */
  static char buf[8][512];
  static int k;
  k = (k + 1) % 8;
  snprintf(buf[k], sizeof buf[k], "%s/%s", T, name);
  return buf[k];
}

static int exists(const char *p) {
  struct stat st;
  return stat(p, &st) == 0;
}

/* Entries of folder d other than . and .. */
static int count_entries(const char *d) {
  DIR *dir = opendir(d);
  if (!dir) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(dir)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  closedir(dir);
  return n;
}

static uint8_t *slurp(const char *p, size_t *n) {
  FILE *f = fopen(p, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long sz = ftell(f);
  fseek(f, 0, SEEK_SET);
  uint8_t *b = malloc((size_t)sz + 1);
  *n = fread(b, 1, (size_t)sz, f);
  b[*n] = 0;
  fclose(f);
  return b;
}

static int same_bytes(const char *a, const char *b) {
  size_t na = 0, nb = 0;
  uint8_t *x = slurp(a, &na), *y = slurp(b, &nb);
  int same = x && y && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

static int msg_has(const char *s) { return strstr(sessile_error_message(), s) != NULL; }

static void rm_rf(const char *d) {
  DIR *dir = opendir(d);
  if (!dir) return;
  struct dirent *e;
  char p[1024];
  while ((e = readdir(dir))) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    snprintf(p, sizeof p, "%s/%s", d, e->d_name);
    struct stat st;
    if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode)) {
      chmod(p, 0755);
      rm_rf(p);
    } else unlink(p);
  }
  closedir(dir);
  rmdir(d);
}

/* --- atomic files ----------------------------------------------------------- */
static void test_atomic(void) {
  sessile_status s;
  /* mkdir -p, twice, and through a file */
  t_ok("mkdirs a/b/c", sessile_mkdirs(P("a/b/c/")));
  t_true("mkdirs created a/b/c", exists(P("a/b/c")));
  t_ok("mkdirs on an existing folder", sessile_mkdirs(P("a/b")));
  t_ok("write a/file", sessile_write_file_atomic(P("a/file"), "x", 1));
  s = sessile_mkdirs(P("a/file/sub"));
  printf("     message: %s\n", sessile_error_message());
  t_true("mkdirs through a file fails with SESSILE_ERR_IO naming the folder",
         s == SESSILE_ERR_IO && msg_has(P("a/file")) && msg_has(strerror(ENOTDIR)));

  /* a missing folder */
  s = sessile_write_file_atomic(P("missing/x.bin"), "abc", 3);
  printf("     message: %s\n", sessile_error_message());
  t_true("write into a missing folder fails with SESSILE_ERR_IO, path and errno text",
         s == SESSILE_ERR_IO && msg_has(P("missing/x.bin")) && msg_has(strerror(ENOENT)));
  t_true("... and creates nothing", !exists(P("missing")));

  /* a read-only folder (root ignores permissions: then the folder is a file) */
  t_ok("mkdirs ro", sessile_mkdirs(P("ro")));
  chmod(P("ro"), 0555);
  s = sessile_write_file_atomic(P("ro/x.bin"), "abc", 3);
  if (geteuid() == 0) {
    printf("     (running as root: permissions do not apply; using a path under a file)\n");
    unlink(P("ro/x.bin"));
    s = sessile_write_file_atomic(P("a/file/x.bin"), "abc", 3);
    printf("     message: %s\n", sessile_error_message());
    t_true("write under a file fails with SESSILE_ERR_IO and errno text",
           s == SESSILE_ERR_IO && msg_has(P("a/file/x.bin")) && msg_has(strerror(ENOTDIR)));
  } else {
    printf("     message: %s\n", sessile_error_message());
    t_true("write into a read-only folder fails with SESSILE_ERR_IO and errno text",
           s == SESSILE_ERR_IO && msg_has(P("ro/x.bin")) && msg_has(strerror(EACCES)));
  }
  t_true("... and leaves the read-only folder empty", count_entries(P("ro")) == 0);
  chmod(P("ro"), 0755);

  /* abort leaves nothing */
  t_ok("mkdirs ab", sessile_mkdirs(P("ab")));
  sessile_atomic_file af;
  t_ok("atomic open", sessile_atomic_open(P("ab/file.txt"), &af));
  t_true("the temporary is in the same folder, not the final name",
         count_entries(P("ab")) == 1 && !exists(P("ab/file.txt")));
  fputs("half a file", af.f);
  sessile_atomic_abort(&af);
  t_true("sessile_atomic_abort leaves nothing", count_entries(P("ab")) == 0);
  sessile_atomic_abort(NULL); /* NULL-safe */

  /* commit replaces an older file */
  t_ok("write old", sessile_write_file_atomic(P("ab/file.txt"), "old content\n", 12));
  t_ok("write new", sessile_write_file_atomic(P("ab/file.txt"), "new\n", 4));
  size_t n = 0;
  uint8_t *b = slurp(P("ab/file.txt"), &n);
  t_true("a committed file replaces the older one", b && n == 4 && !memcmp(b, "new\n", 4));
  free(b);
  t_true("... and no temporary remains", count_entries(P("ab")) == 1);
}

/* A write that fails half-way (file size limit -> EFBIG) leaves the old file. */
static void test_failed_write_keeps_old(void) {
  sessile_box box;
  double origin[3] = {0, 0, 0};
  uint32_t cells[3] = {24, 24, 24};
  t_ok("box 25^3", sessile_box_make(origin, 0.1, cells, 1, &box));
  size_t nn = sessile_box_nodes(&box);
  double *f = malloc(nn * sizeof *f);
  for (size_t i = 0; i < nn; i++) f[i] = sin(0.37 * (double)i);
  t_ok("write the old field file", sessile_write_file_atomic(P("lim/field.vtu"), "old\n", 4));
  struct rlimit old, lim;
  getrlimit(RLIMIT_FSIZE, &old);
  lim = old;
  lim.rlim_cur = 4096;
  signal(SIGXFSZ, SIG_IGN);
  setrlimit(RLIMIT_FSIZE, &lim);
  sessile_point_data d = {"f", f, NULL, 1};
  sessile_status s = sessile_write_vtu(P("lim/field.vtu"), &box, 1, &d);
  setrlimit(RLIMIT_FSIZE, &old);
  printf("     message: %s\n", sessile_error_message());
  t_true("a write cut off by the file size limit fails with SESSILE_ERR_IO naming the file",
         s == SESSILE_ERR_IO && msg_has(P("lim/field.vtu")) && msg_has(strerror(EFBIG)));
  size_t n = 0;
  uint8_t *b = slurp(P("lim/field.vtu"), &n);
  t_true("... keeps the older file whole and removes the temporary",
         b && n == 4 && !memcmp(b, "old\n", 4) && count_entries(P("lim")) == 1);
  free(b);
  free(f);
}

/* --- PLY / OBJ ------------------------------------------------------------ */
static uint32_t rd_u32(const uint8_t *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static float rd_f32(const uint8_t *p) {
  uint32_t u = rd_u32(p);
  float f;
  memcpy(&f, &u, 4);
  return f;
}

static void test_ply(const sessile_surface *s, const double *nrm) {
  double *c = malloc(s->nv * sizeof *c), *k = malloc(s->nv * sizeof *k);
  for (uint32_t v = 0; v < s->nv; v++) c[v] = s->pos[3 * v + 2] * 0.5 + 0.25, k[v] = v;
  const char *names[2] = {"c", "vertex_id"};
  const double *extra[2] = {c, k};
  t_ok("write PLY", sessile_write_ply(P("mesh/s.ply"), s, nrm, 2, names, extra));
  t_ok("write PLY again", sessile_write_ply(P("mesh/s2.ply"), s, nrm, 2, names, extra));
  t_true("PLY: two writes give identical bytes", same_bytes(P("mesh/s.ply"), P("mesh/s2.ply")));

  size_t n = 0;
  uint8_t *b = slurp(P("mesh/s.ply"), &n);
  char *end = b ? strstr((char *)b, "end_header\n") : NULL;
  t_true("PLY has a header ending in end_header", end != NULL);
  if (!end) return;
  *end = 0;
  const uint8_t *d = (const uint8_t *)end + strlen("end_header\n");
  char expect[1024];
  snprintf(expect, sizeof expect,
           "ply\nformat binary_little_endian 1.0\ncomment sessile sponge surface\nelement vertex %u\n"
           "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
           "property float nz\nproperty float c\nproperty float vertex_id\nelement face %u\n"
           "property list uchar uint vertex_indices\n",
           s->nv, s->nf);
  t_true("PLY header lists vertex (x y z nx ny nz c vertex_id) and face elements",
         strcmp((char *)b, expect) == 0);
  size_t need = (size_t)s->nv * 32 + (size_t)s->nf * 13;
  t_true("PLY body has the expected size", (size_t)(n - (size_t)(d - b)) == need);
  if ((size_t)(n - (size_t)(d - b)) == need) {
    double err = 0;
    int faces_ok = 1;
    for (uint32_t v = 0; v < s->nv; v++) {
      const uint8_t *r = d + 32 * (size_t)v;
      double want[8] = {s->pos[3 * v], s->pos[3 * v + 1], s->pos[3 * v + 2], nrm[3 * v], nrm[3 * v + 1],
                        nrm[3 * v + 2], c[v], k[v]};
      for (int q = 0; q < 8; q++) err = fmax(err, fabs(rd_f32(r + 4 * q) - (float)want[q]));
    }
    const uint8_t *fp = d + 32 * (size_t)s->nv;
    for (uint32_t f = 0; f < s->nf; f++, fp += 13)
      faces_ok &= fp[0] == 3 && rd_u32(fp + 1) == s->tri[3 * f] && rd_u32(fp + 5) == s->tri[3 * f + 1] &&
                  rd_u32(fp + 9) == s->tri[3 * f + 2];
    t_check("PLY vertex values == float32 of the input (max abs diff)", err, 0);
    t_true("PLY faces read back equal the triangles", faces_ok);
  }
  free(b);
  free(c);
  free(k);
}

static void test_obj(const sessile_surface *s, const double *nrm) {
  t_ok("write OBJ", sessile_write_obj(P("mesh/s.obj"), s, nrm));
  t_ok("write OBJ again", sessile_write_obj(P("mesh/s2.obj"), s, nrm));
  t_true("OBJ: two writes give identical bytes", same_bytes(P("mesh/s.obj"), P("mesh/s2.obj")));
  FILE *f = fopen(P("mesh/s.obj"), "r");
  char line[512];
  uint32_t nv = 0, nn = 0, nf = 0;
  double err = 0;
  int faces_ok = 1, other = 0;
  while (f && fgets(line, sizeof line, f)) {
    double x, y, z;
    unsigned a[6];
    if (line[0] == '#') continue;
    if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3 && nv < s->nv) {
      const double *p = s->pos + 3 * nv++;
      err = fmax(err, fmax(fabs(x - p[0]), fmax(fabs(y - p[1]), fabs(z - p[2]))));
    } else if (sscanf(line, "vn %lf %lf %lf", &x, &y, &z) == 3 && nn < s->nv) {
      const double *p = nrm + 3 * nn++;
      err = fmax(err, fmax(fabs(x - p[0]), fmax(fabs(y - p[1]), fabs(z - p[2]))));
    } else if (sscanf(line, "f %u//%u %u//%u %u//%u", &a[0], &a[1], &a[2], &a[3], &a[4], &a[5]) == 6 &&
               nf < s->nf) {
      const uint32_t *t = s->tri + 3 * nf++;
      faces_ok &= a[0] == t[0] + 1 && a[1] == t[0] + 1 && a[2] == t[1] + 1 && a[3] == t[1] + 1 &&
                  a[4] == t[2] + 1 && a[5] == t[2] + 1;
    } else other++;
  }
  if (f) fclose(f);
  t_true("OBJ has one v and vn per vertex, one f per triangle, nothing else",
         nv == s->nv && nn == s->nv && nf == s->nf && other == 0);
  t_check("OBJ coordinates and normals read back exactly (max abs diff)", err, 0);
  t_true("OBJ faces are 1-based a//a b//b c//c of the triangles", faces_ok);
}

/* --- EXR -------------------------------------------------------------------- */
static double field_c(const double p[3]) { return sin(1.3 * p[0]) + cos(2.0 * p[1]) + p[2] * p[2]; }
static double field_u(const double p[3]) { return p[0] * p[1] - 0.5 * p[2]; }

/* Reads every channel of the slice back and compares with the P1 interpolant. */
static void check_slice(const char *path, const sessile_box *box, sessile_axis axis, double value,
                        const double *fc, const double *fu, int iteration) {
  static const char an[3] = {'x', 'y', 'z'};
  char what[160];
  exr_context_t ctx = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
    t_true("EXR opens with exr_start_read", 0);
    return;
  }
  int u = axis == SESSILE_AXIS_X ? 1 : 0, v = axis == SESSILE_AXIS_Z ? 1 : 2;
  exr_attr_box2i_t dw;
  exr_get_data_window(ctx, 0, &dw);
  int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  snprintf(what, sizeof what, "EXR %c=%g: data window %d x %d == box nodes %u x %u", an[axis], value, w, h,
           box->n[u], box->n[v]);
  t_true(what, dw.min.x == 0 && dw.min.y == 0 && w == (int)box->n[u] && h == (int)box->n[v]);
  exr_compression_t comp;
  exr_get_compression(ctx, 0, &comp);
  t_true("EXR compression is ZIP", comp == EXR_COMPRESSION_ZIP);
  const exr_attr_chlist_t *cl = NULL;
  exr_get_channels(ctx, 0, &cl);
  int types_ok = cl && cl->num_channels == 2;
  for (int c = 0; types_ok && c < cl->num_channels; c++) types_ok &= cl->entries[c].pixel_type == EXR_PIXEL_FLOAT;
  t_true("EXR has 2 FLOAT channels", types_ok);

  const char *plane = NULL;
  int32_t len = 0, it = -1;
  exr_attr_v3f_t o = {{{0}}};
  exr_attr_v2f_t sp = {{{0}}};
  char want_plane[64];
  snprintf(want_plane, sizeof want_plane, "%c=%.9g", an[axis], value);
  int attrs = exr_attr_get_string(ctx, 0, "sessile:plane", &len, &plane) == EXR_ERR_SUCCESS &&
              exr_attr_get_v3f(ctx, 0, "sessile:origin", &o) == EXR_ERR_SUCCESS &&
              exr_attr_get_v2f(ctx, 0, "sessile:spacing", &sp) == EXR_ERR_SUCCESS &&
              exr_attr_get_int(ctx, 0, "sessile:iteration", &it) == EXR_ERR_SUCCESS;
  double want_o[3] = {box->origin[0], box->origin[1], box->origin[2]};
  want_o[axis] = value;
  t_true("EXR attributes sessile:plane/origin/spacing/iteration read back",
         attrs && len == (int32_t)strlen(want_plane) && !strncmp(plane, want_plane, (size_t)len) &&
             o.x == (float)want_o[0] && o.y == (float)want_o[1] && o.z == (float)want_o[2] &&
             sp.x == (float)box->h && sp.y == (float)box->h && it == iteration);

  float *img[2] = {calloc((size_t)w * h, 4), calloc((size_t)w * h, 4)};
  int32_t lines = 1;
  exr_get_scanlines_per_chunk(ctx, 0, &lines);
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int live = 0, ok = 1;
  for (int y = 0; ok && y < h; y += lines) {
    exr_chunk_info_t ci;
    ok = exr_read_scanline_chunk_info(ctx, 0, y, &ci) == EXR_ERR_SUCCESS;
    if (ok && !live) ok = exr_decoding_initialize(ctx, 0, &ci, &dec) == EXR_ERR_SUCCESS, live = ok;
    else if (ok) ok = exr_decoding_update(ctx, 0, &ci, &dec) == EXR_ERR_SUCCESS;
    for (int k = 0; ok && k < dec.channel_count; k++) {
      exr_coding_channel_info_t *ch = &dec.channels[k];
      int which = strcmp(ch->channel_name, "c") == 0 ? 0 : 1;
      ch->decode_to_ptr = (uint8_t *)(img[which] + (size_t)y * w);
      ch->user_pixel_stride = 4;
      ch->user_line_stride = 4 * w;
      ch->user_bytes_per_element = 4;
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (ok) ok = exr_decoding_choose_default_routines(ctx, 0, &dec) == EXR_ERR_SUCCESS;
    if (ok) ok = exr_decoding_run(ctx, 0, &dec) == EXR_ERR_SUCCESS;
  }
  if (live) exr_decoding_destroy(ctx, &dec);
  exr_finish(&ctx);
  t_true("EXR pixels decode", ok);
  /* reference: the P1 interpolant at each pixel's world position */
  double err = 0, scale = 0;
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      double p[3];
      p[axis] = value;
      p[u] = box->origin[u] + box->h * x;
      p[v] = box->origin[v] + box->h * y;
      double rc = sessile_box_interpolate(box, fc, p), ru = sessile_box_interpolate(box, fu, p);
      err = fmax(err, fmax(fabs(img[0][(size_t)y * w + x] - rc), fabs(img[1][(size_t)y * w + x] - ru)));
      scale = fmax(scale, fmax(fabs(rc), fabs(ru)));
    }
  snprintf(what, sizeof what, "EXR %c=%g pixels vs P1 interpolant (max abs diff / max |ref|)", an[axis], value);
  t_check(what, err / scale, 1.2e-7); /* float32 rounding: 2^-24 relative, plus blend */
  free(img[0]);
  free(img[1]);
}

static void test_exr(const sessile_box *box, const double *fc, const double *fu) {
  sessile_slice_channel ch[2] = {{"ux", fu}, {"c", fc}};
  struct {
    sessile_axis a;
    double v;
  } planes[4] = {{SESSILE_AXIS_Z, 0.61}, {SESSILE_AXIS_Y, box->origin[1] + 2 * box->h},
                 {SESSILE_AXIS_X, box->origin[0] + (box->n[0] - 1) * box->h}, {SESSILE_AXIS_X, 0.3}};
  for (int q = 0; q < 4; q++) {
    char name[64];
    snprintf(name, sizeof name, "slices/p%d.exr", q);
    t_ok("write EXR slice", sessile_write_slice_exr(P(name), box, planes[q].a, planes[q].v, 2, ch, 7 + q));
    check_slice(P(name), box, planes[q].a, planes[q].v, fc, fu, 7 + q);
  }
  t_ok("write EXR slice again", sessile_write_slice_exr(P("slices/again.exr"), box, SESSILE_AXIS_Z, 0.61, 2, ch, 7));
  t_true("EXR: two writes give identical bytes", same_bytes(P("slices/p0.exr"), P("slices/again.exr")));
  sessile_status s = sessile_write_slice_exr(P("slices/out.exr"), box, SESSILE_AXIS_Z, 99.0, 2, ch, 0);
  printf("     message: %s\n", sessile_error_message());
  t_true("EXR plane outside the box fails with SESSILE_ERR_USAGE and writes nothing",
         s == SESSILE_ERR_USAGE && msg_has("outside the box") && !exists(P("slices/out.exr")) &&
             count_entries(P("slices")) == 5);
}

static void test_vtu_pvd(const sessile_box *box, const double *fc, const double *fu) {
  size_t nn = sessile_box_nodes(box);
  double *vec = malloc(3 * nn * sizeof *vec);
  uint8_t *mask = malloc(nn);
  for (size_t i = 0; i < nn; i++) vec[3 * i] = fc[i], vec[3 * i + 1] = fu[i], vec[3 * i + 2] = -1, mask[i] = i % 3 == 0;
  sessile_point_data d[3] = {{"c", fc, NULL, 1}, {"u", vec, NULL, 3}, {"solid", NULL, mask, 1}};
  t_ok("write VTU", sessile_write_vtu(P("fields/a.vtu"), box, 3, d));
  t_ok("write VTU again", sessile_write_vtu(P("fields/b.vtu"), box, 3, d));
  t_true("VTU: two writes give identical bytes", same_bytes(P("fields/a.vtu"), P("fields/b.vtu")));
  int ts[2] = {0, 5};
  const char *files[2] = {"a.vtu", "b.vtu"};
  t_ok("write PVD", sessile_write_pvd(P("fields/series.pvd"), 2, ts, files));
  t_ok("write PVD again", sessile_write_pvd(P("fields/series2.pvd"), 2, ts, files));
  t_true("PVD: two writes give identical bytes", same_bytes(P("fields/series.pvd"), P("fields/series2.pvd")));
  size_t n = 0;
  char *b = (char *)slurp(P("fields/series.pvd"), &n);
  t_true("PVD lists both data sets with their time steps",
         b && strstr(b, "timestep=\"0\" group=\"\" part=\"0\" file=\"a.vtu\"") &&
             strstr(b, "timestep=\"5\" group=\"\" part=\"0\" file=\"b.vtu\""));
  free(b);
  sessile_point_data bad = {"v", fc, NULL, 2};
  t_true("VTU with 2 components is refused", sessile_write_vtu(P("fields/c.vtu"), box, 1, &bad) == SESSILE_ERR_USAGE &&
                                                 !exists(P("fields/c.vtu")));
  free(vec);
  free(mask);
}

int main(void) {
  snprintf(T, sizeof T, "%s/sessile_test_io.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(T)) {
    printf("FAIL cannot create a scratch folder: %s\n", strerror(errno));
    return 1;
  }
  test_atomic();

  sessile_surface s = {0};
  double center[3] = {0.5, -0.25, 1.0};
  t_ok("icosphere", sessile_surface_icosphere(3, 0.75, center, &s));
  double *nrm = malloc(3 * (size_t)s.nv * sizeof *nrm);
  sessile_surface_normals(&s, nrm);
  t_ok("mkdirs mesh", sessile_mkdirs(P("mesh")));
  test_ply(&s, nrm);
  test_obj(&s, nrm);

  sessile_box box;
  double origin[3] = {-1.0, 0.5, 0.0};
  uint32_t cells[3] = {8, 6, 4};
  t_ok("box", sessile_box_make(origin, 0.25, cells, 1, &box));
  size_t nn = sessile_box_nodes(&box);
  double *fc = malloc(nn * sizeof *fc), *fu = malloc(nn * sizeof *fu);
  for (uint32_t i = 0; i < nn; i++) {
    double p[3];
    sessile_box_node_pos(&box, i, p);
    fc[i] = field_c(p);
    fu[i] = field_u(p);
  }
  t_ok("mkdirs slices", sessile_mkdirs(P("slices")));
  test_exr(&box, fc, fu);
  t_ok("mkdirs fields", sessile_mkdirs(P("fields")));
  test_vtu_pvd(&box, fc, fu);
  t_ok("mkdirs lim", sessile_mkdirs(P("lim")));
  test_failed_write_keeps_old();

  free(fc);
  free(fu);
  free(nrm);
  sessile_surface_free(&s);
  rm_rf(T);
  return t_finish(NULL);
}
