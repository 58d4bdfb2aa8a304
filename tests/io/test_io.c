/* The run directory's writers: atomic semantics (failures leave nothing,
 * abort leaves nothing, commit replaces), PLY/OBJ read back by small parsers
 * here, EXR slices read back with OpenEXR's C API and compared with the P1
 * interpolant of the box field on the plane, and determinism (two writes give
 * identical bytes).  The writers for any generator: multi-part PLY/OBJ
 * (parsed back here, indices offset per part), EXR on any plane (read back
 * with OpenEXR, against the sampled formula), VTU of any tet mesh (the box
 * through it gives the box writer's bytes), and their input checks.  The
 * .vtu/.pvd and the independent readers are checked by test_readers.sh. */
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
#include "sessile/io/io.h"
#include "sessile/mesh/tetmesh.h"
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
  /* sorted by name: the view's B, G, R (half), then c and ux (float) */
  int types_ok = cl && cl->num_channels == 5;
  for (int c = 0; types_ok && c < cl->num_channels; c++)
    types_ok &= cl->entries[c].pixel_type == (c < 3 ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT) &&
                !strcmp(cl->entries[c].name.str, (const char *[]){"B", "G", "R", "c", "ux"}[c]);
  t_true("EXR has HALF channels B, G, R and FLOAT channels c, ux", types_ok);
  const char *order = NULL, *vch = NULL;
  int32_t olen = 0, vlen = 0;
  t_true("EXR: sessile:row_order top-down, sessile:view_channel ux (the first given)",
         exr_attr_get_string(ctx, 0, "sessile:row_order", &olen, &order) == EXR_ERR_SUCCESS && olen == 8 &&
             !strncmp(order, "top-down", 8) &&
             exr_attr_get_string(ctx, 0, "sessile:view_channel", &vlen, &vch) == EXR_ERR_SUCCESS && vlen == 2 &&
             !strncmp(vch, "ux", 2));

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
      int which = !strcmp(ch->channel_name, "c") ? 0 : !strcmp(ch->channel_name, "ux") ? 1 : -1;
      ch->decode_to_ptr = which < 0 ? NULL : (uint8_t *)(img[which] + (size_t)y * w);
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
  /* reference: the P1 interpolant at each pixel's world position; EXR row
   * y is the plane's row h - 1 - y (the top row holds the highest v) */
  double err = 0, scale = 0;
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      double p[3];
      p[axis] = value;
      p[u] = box->origin[u] + box->h * x;
      p[v] = box->origin[v] + box->h * (h - 1 - y);
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
  /* simulated times: exact (the double reads back), integers as %d prints them */
  double tt[2] = {0, 0.1 + 0.2}, nan_t[2] = {0, NAN};
  t_ok("write a PVD of times", sessile_write_pvd_times(P("fields/times.pvd"), 2, tt, files));
  b = (char *)slurp(P("fields/times.pvd"), &n);
  const char *at = b ? strstr(b, "file=\"b.vtu\"") : NULL;
  const char *ts1 = b ? strstr(b, "timestep=\"0.30000000000000004\"") : NULL;
  t_true("PVD of times: 0 as \"0\", 0.1 + 0.2 exactly, with its file",
         b && strstr(b, "timestep=\"0\" group=\"\" part=\"0\" file=\"a.vtu\"") && ts1 && at && ts1 < at &&
             strtod(ts1 + 10, NULL) == tt[1]);
  free(b);
  t_true("PVD with a non-finite time is refused",
         sessile_write_pvd_times(P("fields/nan.pvd"), 2, nan_t, files) == SESSILE_ERR_USAGE &&
             !exists(P("fields/nan.pvd")));
  sessile_point_data bad = {"v", fc, NULL, 2};
  t_true("VTU with 2 components is refused", sessile_write_vtu(P("fields/c.vtu"), box, 1, &bad) == SESSILE_ERR_USAGE &&
                                                 !exists(P("fields/c.vtu")));
  free(vec);
  free(mask);
}

/* --- multi-part PLY / OBJ -------------------------------------------------- */
static int nothing_at(const char *p) { return !exists(p); }

/* Two spheres and an empty part between them; fields c (a formula of the
 * position) and part (the part's index). */
static void test_parts(void) {
  sessile_surface a = {0}, b = {0};
  double ca[3] = {0, 0, 0}, cb[3] = {2.5, -1, 0.5};
  t_ok("icosphere level 1", sessile_surface_icosphere(1, 0.5, ca, &a));
  t_ok("icosphere level 2", sessile_surface_icosphere(2, 1.0, cb, &b));
  double *na = malloc(3 * (size_t)a.nv * sizeof *na), *nb = malloc(3 * (size_t)b.nv * sizeof *nb);
  sessile_surface_normals(&a, na);
  sessile_surface_normals(&b, nb);
  double *fa[2] = {malloc(a.nv * sizeof(double)), malloc(a.nv * sizeof(double))};
  double *fb[2] = {malloc(b.nv * sizeof(double)), malloc(b.nv * sizeof(double))};
  for (uint32_t v = 0; v < a.nv; v++) fa[0][v] = 1 + 2 * a.pos[3 * v] - a.pos[3 * v + 2], fa[1][v] = 0;
  for (uint32_t v = 0; v < b.nv; v++) fb[0][v] = 1 + 2 * b.pos[3 * v] - b.pos[3 * v + 2], fb[1][v] = 2;
  const double *const fpa[2] = {fa[0], fa[1]}, *const fpb[2] = {fb[0], fb[1]};
  sessile_mesh_part parts[3] = {
      {"small", a.pos, a.nv, a.tri, a.nf, na, fpa},
      {"empty", NULL, 0, NULL, 0, NULL, NULL},
      {NULL, b.pos, b.nv, b.tri, b.nf, nb, fpb},
  };
  const char *names[2] = {"c", "part"};
  uint32_t tv = a.nv + b.nv, tf = a.nf + b.nf;
  t_ok("write PLY of 3 parts (one empty)", sessile_write_ply_parts(P("parts/u.ply"), 3, parts, 2, names));
  t_ok("write it again", sessile_write_ply_parts(P("parts/u2.ply"), 3, parts, 2, names));
  t_true("PLY parts: two writes give identical bytes", same_bytes(P("parts/u.ply"), P("parts/u2.ply")));
  size_t n = 0;
  uint8_t *buf = slurp(P("parts/u.ply"), &n);
  char *end = buf ? strstr((char *)buf, "end_header\n") : NULL;
  t_true("PLY parts has a header", end != NULL);
  if (end) {
    *end = 0;
    const uint8_t *d = (const uint8_t *)end + strlen("end_header\n");
    char expect[1024];
    snprintf(expect, sizeof expect,
             "ply\nformat binary_little_endian 1.0\ncomment sessile surface: 3 parts\n"
             "comment part small vertices 0 %u faces 0 %u\ncomment part empty vertices %u 0 faces %u 0\n"
             "comment part part2 vertices %u %u faces %u %u\nelement vertex %u\n"
             "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
             "property float nz\nproperty float c\nproperty float part\nelement face %u\n"
             "property list uchar uint vertex_indices\n",
             a.nv, a.nf, a.nv, a.nf, a.nv, b.nv, a.nf, b.nf, tv, tf);
    t_true("PLY parts header: part comments, union counts, x..nz c part", strcmp((char *)buf, expect) == 0);
    size_t need = (size_t)tv * 32 + (size_t)tf * 13;
    t_true("PLY parts body has the expected size", (size_t)(n - (size_t)(d - buf)) == need);
    if ((size_t)(n - (size_t)(d - buf)) == need) {
      double err = 0;
      for (uint32_t v = 0; v < tv; v++) {
        int second = v >= a.nv;
        uint32_t l = second ? v - a.nv : v;
        const double *pos = second ? b.pos : a.pos, *nrm = second ? nb : na;
        double want[8] = {pos[3 * l], pos[3 * l + 1], pos[3 * l + 2], nrm[3 * l], nrm[3 * l + 1],
                          nrm[3 * l + 2], second ? fb[0][l] : fa[0][l], second ? 2 : 0};
        for (int q = 0; q < 8; q++) err = fmax(err, fabs(rd_f32(d + 32 * (size_t)v + 4 * q) - (float)want[q]));
      }
      t_check("PLY parts vertex values == float32 of each part's input", err, 0);
      int faces_ok = 1;
      const uint8_t *fp = d + 32 * (size_t)tv;
      for (uint32_t f = 0; f < tf; f++, fp += 13) {
        int second = f >= a.nf;
        const uint32_t *t = second ? b.tri + 3 * (f - a.nf) : a.tri + 3 * f;
        uint32_t off = second ? a.nv : 0;
        faces_ok &= fp[0] == 3 && rd_u32(fp + 1) == t[0] + off && rd_u32(fp + 5) == t[1] + off &&
                    rd_u32(fp + 9) == t[2] + off;
      }
      t_true("PLY parts faces: the second sphere's indices are offset by the first's vertices", faces_ok);
    }
  }
  free(buf);

  /* one part through the union writer == the sponge writer, except the comments */
  sessile_mesh_part one = {"surface", a.pos, a.nv, a.tri, a.nf, na, fpa};
  t_ok("write a one-part union", sessile_write_ply_parts(P("parts/one.ply"), 1, &one, 2, names));
  t_ok("write the same surface with sessile_write_ply", sessile_write_ply(P("parts/s.ply"), &a, na, 2, names, fpa));
  size_t n1 = 0, n2 = 0;
  uint8_t *b1 = slurp(P("parts/one.ply"), &n1), *b2 = slurp(P("parts/s.ply"), &n2);
  char *e1 = b1 ? strstr((char *)b1, "element vertex") : NULL, *e2 = b2 ? strstr((char *)b2, "element vertex") : NULL;
  t_true("... the same bytes from 'element vertex' on",
         e1 && e2 && n1 - (size_t)(e1 - (char *)b1) == n2 - (size_t)(e2 - (char *)b2) &&
             !memcmp(e1, e2, n2 - (size_t)(e2 - (char *)b2)));
  free(b1);
  free(b2);

  /* OBJ */
  t_ok("write OBJ of 3 parts", sessile_write_obj_parts(P("parts/u.obj"), 3, parts));
  t_ok("write it again", sessile_write_obj_parts(P("parts/u2.obj"), 3, parts));
  t_true("OBJ parts: two writes give identical bytes", same_bytes(P("parts/u.obj"), P("parts/u2.obj")));
  FILE *f = fopen(P("parts/u.obj"), "r");
  char line[512], group[3][64] = {"", "", ""};
  uint32_t nv = 0, nn = 0, nf = 0;
  int ngroups = 0, faces_ok = 1, other = 0, og_ok = 1;
  double err = 0;
  while (f && fgets(line, sizeof line, f)) {
    double x, y, z;
    unsigned q[6];
    char name[64];
    if (line[0] == '#') continue;
    if (sscanf(line, "o %63s", name) == 1) {
      if (ngroups < 3) snprintf(group[ngroups], sizeof group[0], "%s", name);
      ngroups++;
    } else if (sscanf(line, "g %63s", name) == 1) {
      og_ok &= ngroups > 0 && ngroups <= 3 && !strcmp(name, group[ngroups - 1]);
    } else if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3 && nv < tv) {
      const double *p = nv < a.nv ? a.pos + 3 * nv : b.pos + 3 * (nv - a.nv);
      og_ok &= ngroups == (nv < a.nv ? 1 : 3);
      nv++;
      err = fmax(err, fmax(fabs(x - p[0]), fmax(fabs(y - p[1]), fabs(z - p[2]))));
    } else if (sscanf(line, "vn %lf %lf %lf", &x, &y, &z) == 3 && nn < tv) {
      const double *p = nn < a.nv ? na + 3 * nn : nb + 3 * (nn - a.nv);
      nn++;
      err = fmax(err, fmax(fabs(x - p[0]), fmax(fabs(y - p[1]), fabs(z - p[2]))));
    } else if (sscanf(line, "f %u//%u %u//%u %u//%u", &q[0], &q[1], &q[2], &q[3], &q[4], &q[5]) == 6 && nf < tf) {
      int second = nf >= a.nf;
      const uint32_t *t = second ? b.tri + 3 * (nf - a.nf) : a.tri + 3 * nf;
      uint32_t off = (second ? a.nv : 0) + 1;
      nf++;
      faces_ok &= q[0] == t[0] + off && q[1] == q[0] && q[2] == t[1] + off && q[3] == q[2] &&
                  q[4] == t[2] + off && q[5] == q[4];
    } else other++;
  }
  if (f) fclose(f);
  t_true("OBJ parts: o/g small, empty, part2 in order, each part's v lines under its own o",
         ngroups == 3 && og_ok && !strcmp(group[0], "small") && !strcmp(group[1], "empty") &&
             !strcmp(group[2], "part2"));
  t_true("OBJ parts: one v and vn per union vertex, one f per triangle, nothing else",
         nv == tv && nn == tv && nf == tf && other == 0);
  t_check("OBJ parts: coordinates and normals read back exactly", err, 0);
  t_true("OBJ parts: faces 1-based into the whole file (second sphere offset)", faces_ok);

  /* input checks: SESSILE_ERR_USAGE, a one-line message, nothing written */
  struct {
    const char *what, *msg;
    int k;
  } bad[] = {{"a NaN vertex coordinate", "non-finite", 0},
             {"an index past its part's vertices", "refers to vertex", 1},
             {"normals on one part only", "normals", 2},
             {"a part name with a space", "name without spaces", 3},
             {"no parts", "surface parts", 4},
             {"a repeated field name", "appears twice", 5},
             {"a part without field values", "no values", 6}};
  for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
    sessile_mesh_part bp[2] = {parts[0], parts[2]};
    double *pos = malloc(3 * (size_t)b.nv * sizeof *pos);
    uint32_t *tri = malloc(3 * (size_t)b.nf * sizeof *tri);
    memcpy(pos, b.pos, 3 * (size_t)b.nv * sizeof *pos);
    memcpy(tri, b.tri, 3 * (size_t)b.nf * sizeof *tri);
    bp[1].pos = pos, bp[1].tri = tri;
    int np = 2;
    const char *nm[2] = {"c", "part"};
    if (bad[q].k == 0) pos[7] = NAN;
    if (bad[q].k == 1) tri[5] = b.nv; /* < the union's count, past the part's */
    if (bad[q].k == 2) bp[1].normals = NULL;
    if (bad[q].k == 3) bp[0].name = "small part";
    if (bad[q].k == 4) np = 0;
    if (bad[q].k == 5) nm[1] = "c";
    if (bad[q].k == 6) bp[1].fields = NULL;
    char what[160];
    sessile_status s1 = sessile_write_ply_parts(P("parts/bad.ply"), np, bp, 2, nm);
    int msg1 = msg_has(bad[q].msg) && !strchr(sessile_error_message(), '\n');
    printf("     message: %s\n", sessile_error_message());
    snprintf(what, sizeof what, "PLY parts with %s: SESSILE_ERR_USAGE naming it, nothing written", bad[q].what);
    t_true(what, s1 == SESSILE_ERR_USAGE && msg1 && nothing_at(P("parts/bad.ply")));
    if (bad[q].k <= 4) {
      sessile_status s2 = sessile_write_obj_parts(P("parts/bad.obj"), np, bp);
      snprintf(what, sizeof what, "OBJ parts with %s: SESSILE_ERR_USAGE, nothing written", bad[q].what);
      t_true(what, s2 == SESSILE_ERR_USAGE && msg_has(bad[q].msg) && nothing_at(P("parts/bad.obj")));
    }
    free(pos);
    free(tri);
  }
  double nan_pos[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
  uint32_t one_tri[3] = {0, 1, 2};
  sessile_surface nan_s = {3, 1, 3, 1, nan_pos, one_tri};
  t_true("sessile_write_ply refuses a NaN vertex too (SESSILE_ERR_USAGE, nothing written)",
         sessile_write_ply(P("parts/nan.ply"), &nan_s, NULL, 0, NULL, NULL) == SESSILE_ERR_USAGE &&
             msg_has("non-finite") && nothing_at(P("parts/nan.ply")));
  t_true("parts folder holds only the good files", count_entries(P("parts")) == 6);
  for (int q = 0; q < 2; q++) free(fa[q]), free(fb[q]);
  free(na);
  free(nb);
  sessile_surface_free(&a);
  sessile_surface_free(&b);
}

/* --- EXR on any plane -------------------------------------------------------- */
/* Reads float channels names[0..nchan) of a one-part EXR into img (w x h),
 * other channels skipped; the file's rows are top-down, img's the plane's
 * (row 0 at the low end of v). */
static int read_exr(const char *path, int nchan, const char *const *names, float **img, int w, int h) {
  exr_context_t ctx = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) return 0;
  exr_attr_box2i_t dw;
  int ok = exr_get_data_window(ctx, 0, &dw) == EXR_ERR_SUCCESS && dw.min.x == 0 && dw.min.y == 0 &&
           dw.max.x == w - 1 && dw.max.y == h - 1;
  int32_t lines = 1;
  exr_get_scanlines_per_chunk(ctx, 0, &lines);
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int live = 0;
  for (int y = 0; ok && y < h; y += lines) {
    exr_chunk_info_t ci;
    ok = exr_read_scanline_chunk_info(ctx, 0, y, &ci) == EXR_ERR_SUCCESS;
    if (ok && !live) ok = exr_decoding_initialize(ctx, 0, &ci, &dec) == EXR_ERR_SUCCESS, live = ok;
    else if (ok) ok = exr_decoding_update(ctx, 0, &ci, &dec) == EXR_ERR_SUCCESS;
    for (int k = 0; ok && k < dec.channel_count; k++) {
      exr_coding_channel_info_t *ch = &dec.channels[k];
      int c = 0;
      while (c < nchan && strcmp(names[c], ch->channel_name)) c++;
      ch->decode_to_ptr = c < nchan ? (uint8_t *)(img[c] + (size_t)y * w) : NULL;
      ok = c == nchan || ch->data_type == EXR_PIXEL_FLOAT;
      if (!ok) break;
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
  for (int c = 0; ok && c < nchan; c++)
    for (int j = 0; j < h / 2; j++)
      for (int i = 0; i < w; i++) {
        float t = img[c][(size_t)j * w + i];
        img[c][(size_t)j * w + i] = img[c][(size_t)(h - 1 - j) * w + i];
        img[c][(size_t)(h - 1 - j) * w + i] = t;
      }
  return ok;
}

typedef struct plane_user {
  int calls;
  const sessile_box *box; /* for the P1 sampler */
  const double *fc, *fu;
} plane_user;

static double sample_formula(void *user, int channel, const double p[3]) {
  ((plane_user *)user)->calls++;
  if (channel == 0) return sin(p[0]) + 2 * p[1] * p[2];
  return p[0] < 0.2 ? NAN : p[0] - p[1];
}

static double sample_box(void *user, int channel, const double p[3]) {
  plane_user *u = user;
  return sessile_box_interpolate(u->box, channel == 0 ? u->fc : u->fu, p);
}

static void test_plane_exr(const sessile_box *box, const double *fc, const double *fu) {
  /* an oblique plane: u along (1, 1, 0), v along z */
  sessile_plane pl = {{-0.5, 0.25, 1.0}, {2, 2, 0}, {0, 0, 3}, {0.1, 0.2}, 7, 5};
  const char *names[2] = {"s", "d"};
  plane_user pu = {0};
  t_ok("write EXR on an oblique plane (sampler)",
       sessile_write_plane_exr(P("planes/ob.exr"), &pl, "oblique test plane", 2, names, sample_formula, &pu, 3));
  t_true("the sampler was called once per pixel and channel", pu.calls == 2 * 7 * 5);
  float *img[2] = {calloc(35, 4), calloc(35, 4)};
  double err = 0;
  int nan_ok = 1, ok = read_exr(P("planes/ob.exr"), 2, names, img, 7, 5);
  t_true("EXR plane reads back: 7 x 5 float channels s, d", ok);
  const double r2 = sqrt(0.5);
  for (int j = 0; ok && j < 5; j++)
    for (int i = 0; i < 7; i++) {
      double p[3] = {-0.5 + 0.1 * i * r2, 0.25 + 0.1 * i * r2, 1.0 + 0.2 * j};
      float s = img[0][j * 7 + i], d = img[1][j * 7 + i];
      err = fmax(err, fabs(s - (sin(p[0]) + 2 * p[1] * p[2])) / 4);
      if (p[0] < 0.2 - 1e-9) nan_ok &= isnan(d);
      else if (p[0] > 0.2 + 1e-9) err = fmax(err, fabs(d - (p[0] - p[1])));
    }
  t_check("EXR plane pixels == the formula at origin + i du + j dv (relative)", err, 1.2e-7);
  t_true("EXR plane: NaN samples are stored as NaN", nan_ok);
  exr_context_t ctx = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  const char *label = NULL;
  int32_t len = 0, it = -1;
  exr_attr_v3f_t o = {{{0}}}, au = {{{0}}}, av = {{{0}}};
  exr_attr_v2f_t sp = {{{0}}};
  int attrs = exr_start_read(&ctx, P("planes/ob.exr"), &init) == EXR_ERR_SUCCESS &&
              exr_attr_get_string(ctx, 0, "sessile:plane", &len, &label) == EXR_ERR_SUCCESS &&
              exr_attr_get_v3f(ctx, 0, "sessile:origin", &o) == EXR_ERR_SUCCESS &&
              exr_attr_get_v2f(ctx, 0, "sessile:spacing", &sp) == EXR_ERR_SUCCESS &&
              exr_attr_get_int(ctx, 0, "sessile:iteration", &it) == EXR_ERR_SUCCESS &&
              exr_attr_get_v3f(ctx, 0, "sessile:axis_u", &au) == EXR_ERR_SUCCESS &&
              exr_attr_get_v3f(ctx, 0, "sessile:axis_v", &av) == EXR_ERR_SUCCESS;
  attrs = attrs && len == (int32_t)strlen("oblique test plane") && !strncmp(label, "oblique test plane", (size_t)len) &&
          o.x == -0.5f && o.y == 0.25f && o.z == 1.0f && sp.x == 0.1f && sp.y == 0.2f && it == 3 &&
          au.x == (float)r2 && au.y == (float)r2 && au.z == 0 && av.x == 0 && av.y == 0 && av.z == 1;
  if (ctx) exr_finish(&ctx);
  t_true("EXR plane attributes: label, origin, spacing, iteration, unit axes", attrs);

  /* precomputed pixels: the same bytes as the sampler */
  double *vals[2] = {malloc(35 * sizeof(double)), malloc(35 * sizeof(double))};
  for (int j = 0; j < 5; j++)
    for (int i = 0; i < 7; i++) {
      double p[3];
      for (int a = 0; a < 3; a++) {
        double un = a < 2 ? r2 : 0, vn = a == 2 ? 1 : 0;
        p[a] = pl.origin[a] + i * 0.1 * un + j * 0.2 * vn;
      }
      for (int c = 0; c < 2; c++) vals[c][j * 7 + i] = sample_formula(&pu, c, p);
    }
  const double *const cv[2] = {vals[0], vals[1]};
  t_ok("write the same plane from precomputed values",
       sessile_write_plane_exr_values(P("planes/ob_values.exr"), &pl, "oblique test plane", 2, names, cv, 3));
  t_true("... gives the sampler's bytes", same_bytes(P("planes/ob.exr"), P("planes/ob_values.exr")));
  t_ok("write it again", sessile_write_plane_exr(P("planes/ob2.exr"), &pl, "oblique test plane", 2, names, sample_formula, &pu, 3));
  t_true("EXR plane: two writes give identical bytes", same_bytes(P("planes/ob.exr"), P("planes/ob2.exr")));

  /* the box's z = 0.61 plane through the P1 sampler == the box slice's pixels */
  sessile_plane zp = {{box->origin[0], box->origin[1], 0.61}, {1, 0, 0}, {0, 1, 0}, {box->h, box->h}, box->n[0], box->n[1]};
  plane_user bu = {0, box, fc, fu};
  const char *bn[2] = {"c", "ux"};
  sessile_slice_channel ch[2] = {{"ux", fu}, {"c", fc}};
  t_ok("write the box's z=0.61 plane through a P1 sampler",
       sessile_write_plane_exr(P("planes/z.exr"), &zp, NULL, 2, bn, sample_box, &bu, 0));
  t_ok("write the box slice z=0.61", sessile_write_slice_exr(P("planes/zs.exr"), box, SESSILE_AXIS_Z, 0.61, 2, ch, 0));
  int w = (int)box->n[0], h = (int)box->n[1];
  float *g[2] = {calloc((size_t)w * h, 4), calloc((size_t)w * h, 4)}, *s[2] = {calloc((size_t)w * h, 4), calloc((size_t)w * h, 4)};
  ok = read_exr(P("planes/z.exr"), 2, bn, g, w, h) && read_exr(P("planes/zs.exr"), 2, bn, s, w, h);
  err = 0;
  for (int q = 0; ok && q < w * h; q++) err = fmax(err, fmax(fabs(g[0][q] - s[0][q]), fabs(g[1][q] - s[1][q])));
  t_true("both read back", ok);
  t_check("plane writer with a P1 sampler == box slice writer (max abs diff)", err, 1e-6);

  /* input checks */
  struct {
    const char *what, *msg;
    int k;
  } bad[] = {{"width 0", "pixels", 0},         {"a NaN origin", "not finite", 1},
             {"parallel axes", "perpendicular", 2}, {"a zero axis", "non-zero", 3},
             {"spacing 0", "spacing", 4},      {"a repeated channel name", "appears twice", 5},
             {"no sampler", "no sampler", 6},   {"no channels", "channels", 7},
             {"a channel named R (the colour view's)", "colour view", 8}};
  for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
    sessile_plane b = pl;
    const char *nm[2] = {"s", "d"};
    int nc = 2;
    sessile_plane_sampler fn = sample_formula;
    if (bad[q].k == 0) b.width = 0;
    if (bad[q].k == 1) b.origin[1] = NAN;
    if (bad[q].k == 2) b.axis_v[0] = 1, b.axis_v[1] = 1, b.axis_v[2] = 0;
    if (bad[q].k == 3) memset(b.axis_u, 0, sizeof b.axis_u);
    if (bad[q].k == 4) b.spacing[1] = 0;
    if (bad[q].k == 5) nm[1] = "s";
    if (bad[q].k == 6) fn = NULL;
    if (bad[q].k == 7) nc = 0;
    if (bad[q].k == 8) nm[1] = "R";
    sessile_status st = sessile_write_plane_exr(P("planes/bad.exr"), &b, NULL, nc, nm, fn, &pu, 0);
    printf("     message: %s\n", sessile_error_message());
    char what[160];
    snprintf(what, sizeof what, "EXR plane with %s: SESSILE_ERR_USAGE naming it, nothing written", bad[q].what);
    t_true(what, st == SESSILE_ERR_USAGE && msg_has(bad[q].msg) && !strchr(sessile_error_message(), '\n') &&
                     nothing_at(P("planes/bad.exr")));
  }
  t_true("planes folder holds only the good files", count_entries(P("planes")) == 5);
  for (int c = 0; c < 2; c++) free(img[c]), free(vals[c]), free(g[c]), free(s[c]);
}

/* --- VTU of any tet mesh ------------------------------------------------------ */
static void test_vtu_tets(const sessile_box *box, const double *fc, const double *fu) {
  sessile_tetmesh m = {0};
  t_ok("tetmesh from the box", sessile_tetmesh_from_box(box, &m));
  size_t nn = m.nnodes;
  uint8_t *mask = malloc(nn);
  for (size_t i = 0; i < nn; i++) mask[i] = i % 3 == 0;
  sessile_point_data d[2] = {{"c", fc, NULL, 1}, {"solid", NULL, mask, 1}};
  sessile_vtu_field f[2] = {{.name = "c", .f64 = fc, .components = 1}, {.name = "solid", .u8 = mask, .components = 1}};
  t_ok("write the box with sessile_write_vtu", sessile_write_vtu(P("tets/box.vtu"), box, 2, d));
  t_ok("write its tetmesh with sessile_write_vtu_tets",
       sessile_write_vtu_tets(P("tets/mesh.vtu"), m.xyz, m.nnodes, m.tet, m.ntets, 2, f, 0, NULL));
  t_true("the box writer and the tet writer give identical bytes for the same mesh",
         same_bytes(P("tets/box.vtu"), P("tets/mesh.vtu")));

  /* cell data: Float64 volume, Float64 x3 centroid, Int32 id, UInt8 id % 6 */
  double *vol = malloc(m.ntets * sizeof *vol), *cen = malloc(3 * (size_t)m.ntets * sizeof *cen);
  int32_t *id = malloc(m.ntets * sizeof *id);
  uint8_t *kind = malloc(m.ntets);
  for (uint32_t t = 0; t < m.ntets; t++) {
    vol[t] = sessile_tetmesh_tet_volume(&m, t);
    for (int a = 0; a < 3; a++) {
      cen[3 * t + a] = 0;
      for (int q = 0; q < 4; q++) cen[3 * t + a] += 0.25 * m.xyz[3 * m.tet[4 * t + q] + a];
    }
    id[t] = (int32_t)t - 5;
    kind[t] = (uint8_t)(t % 6);
  }
  sessile_vtu_field cf[4] = {{.name = "volume", .f64 = vol, .components = 1},
                             {.name = "centroid", .f64 = cen, .components = 3},
                             {.name = "id", .i32 = id, .components = 1},
                             {.name = "kind", .u8 = kind, .components = 1}};
  t_ok("write a tet VTU with 2 point and 4 cell arrays",
       sessile_write_vtu_tets(P("tets/cells.vtu"), m.xyz, m.nnodes, m.tet, m.ntets, 2, f, 4, cf));
  t_ok("write it again", sessile_write_vtu_tets(P("tets/cells2.vtu"), m.xyz, m.nnodes, m.tet, m.ntets, 2, f, 4, cf));
  t_true("tet VTU: two writes give identical bytes", same_bytes(P("tets/cells.vtu"), P("tets/cells2.vtu")));
  size_t n = 0;
  char *b = (char *)slurp(P("tets/cells.vtu"), &n);
  char *cd = b ? strstr(b, "<CellData>") : NULL, *pd = b ? strstr(b, "</PointData>") : NULL,
       *pts = b ? strstr(b, "<Points>") : NULL;
  t_true("tet VTU: <CellData> between </PointData> and <Points>", cd && pd && pts && pd < cd && cd < pts);
  t_true("tet VTU: cell arrays volume Float64, centroid Float64 x3, id Int32, kind UInt8",
         cd && strstr(cd, "<DataArray type=\"Float64\" Name=\"volume\" NumberOfComponents=\"1\"") &&
             strstr(cd, "<DataArray type=\"Float64\" Name=\"centroid\" NumberOfComponents=\"3\"") &&
             strstr(cd, "<DataArray type=\"Int32\" Name=\"id\" NumberOfComponents=\"1\"") &&
             strstr(cd, "<DataArray type=\"UInt8\" Name=\"kind\" NumberOfComponents=\"1\""));
  free(b);

  /* input checks */
  struct {
    const char *what, *msg;
    int k;
  } bad[] = {{"a NaN coordinate", "non-finite", 0},          {"a tet index out of range", "refers to point", 1},
             {"zero tets", "at least 1", 2},                 {"zero points", "at least 1", 3},
             {"a field with two arrays", "exactly one", 4},  {"2 components", "components", 5},
             {"a repeated cell data name", "appears twice", 6}, {"an unnamed field", "needs a name", 7}};
  double *xyz = malloc(3 * nn * sizeof *xyz);
  uint32_t *tet = malloc(4 * (size_t)m.ntets * sizeof *tet);
  for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
    memcpy(xyz, m.xyz, 3 * nn * sizeof *xyz);
    memcpy(tet, m.tet, 4 * (size_t)m.ntets * sizeof *tet);
    sessile_vtu_field bcf[4] = {cf[0], cf[1], cf[2], cf[3]};
    uint32_t nv = m.nnodes, nt = m.ntets;
    if (bad[q].k == 0) xyz[3 * 17 + 1] = NAN;
    if (bad[q].k == 1) tet[4 * 9 + 2] = nv;
    if (bad[q].k == 2) nt = 0;
    if (bad[q].k == 3) nv = 0;
    if (bad[q].k == 4) bcf[2].u8 = kind;
    if (bad[q].k == 5) bcf[0].components = 2;
    if (bad[q].k == 6) bcf[3].name = "id";
    if (bad[q].k == 7) bcf[1].name = "";
    sessile_status st = sessile_write_vtu_tets(P("tets/bad.vtu"), xyz, nv, tet, nt, 2, f, 4, bcf);
    printf("     message: %s\n", sessile_error_message());
    char what[160];
    snprintf(what, sizeof what, "tet VTU with %s: SESSILE_ERR_USAGE naming it, nothing written", bad[q].what);
    t_true(what, st == SESSILE_ERR_USAGE && msg_has(bad[q].msg) && !strchr(sessile_error_message(), '\n') &&
                     nothing_at(P("tets/bad.vtu")));
  }
  t_true("tets folder holds only the good files", count_entries(P("tets")) == 4);
  free(xyz);
  free(tet);
  free(vol);
  free(cen);
  free(id);
  free(kind);
  free(mask);
  sessile_tetmesh_free(&m);
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
  t_ok("mkdirs parts", sessile_mkdirs(P("parts")));
  test_parts();
  t_ok("mkdirs planes", sessile_mkdirs(P("planes")));
  test_plane_exr(&box, fc, fu);
  t_ok("mkdirs tets", sessile_mkdirs(P("tets")));
  test_vtu_tets(&box, fc, fu);
  t_ok("mkdirs lim", sessile_mkdirs(P("lim")));
  test_failed_write_keeps_old();

  free(fc);
  free(fu);
  free(nrm);
  sessile_surface_free(&s);
  rm_rf(T);
  return t_finish(NULL);
}
