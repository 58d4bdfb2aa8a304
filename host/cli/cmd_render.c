/* `sessile render`: pictures of sessile's outputs (docs/render.md).
 * Meshes (.ply, .obj) and scenes (.json) are drawn through Vulkan and annotated with Cairo
 * (sessile/render/render_run.h); EXR slices by the 2-D renderer (sessile/render/render2d.h);
 * run directories by both (host/render/run_*.c). */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "cli.h"
#include "cli_progress.h"
#include "sessile/io/png.h"
#include "sessile/render/render2d.h"
#include "sessile/render/render_mesh.h"
#include "sessile/render/render_run.h"
#include "sessile/render/render_scene.h"

#define CMD "render"
/* A name in a message: at most 60 characters and "...", the reason after it whole. */
#define SHORT(name) cli_short((name), (char[CLI_SHORT_BUF]){0})

static const char *help =
    "usage: sessile render FILE.ply|FILE.obj|SCENE.json -o OUT.png [options]\n"
    "       sessile render FILE.exr -o OUT.png [--channel C] [--outline FILE.ply]\n"
    "                      [--colormap NAME] [--range LO HI] [--size WxH]\n"
    "       sessile render RUN_DIR [-o DIR] [--size WxH] [--progress MODE]\n"
    "       sessile render --sheet COLS -o OUT.png A.png [--caption TEXT] B.png ...\n"
    "\n"
    "Meshes are drawn offscreen through Vulkan (any device; lavapipe on a CPU):\n"
    "smooth shading from per-vertex normals (computed, area-weighted, when the\n"
    "file has none) under a key and a fill light, a ground grid in cm below the\n"
    "mesh with its spacing written in the lower left corner, a camera fitted to\n"
    "the bounds.  A scene file (SCENE.json: a reef's reef/scene.json) draws the\n"
    "parts of one PLY many times, each instance with its transform and colour.\n"
    "EXR slices (sessile grow's slices/*.exr) become a colour-mapped\n"
    "picture with a colour bar, axes in cm and the sponge's outline.  A run\n"
    "directory gets renders/: the final mesh from the four views, a contact sheet\n"
    "of the snapshots, the slices, plots of records.jsonl (and of an SDS run's\n"
    "sds/steps.csv: ms per step and cells against time).  Same input, same\n"
    "device: the same PNG bytes.  docs/render.md explains it all.\n"
    "\n"
    "Meshes:\n"
    "  -o, --out PATH        the PNG to write (required); with --turntable N the\n"
    "                        frames are PATH without .png + _000.png, _001.png ...\n"
    "  --view V              oblique (default), side, top, front\n"
    "  --turntable N         N frames turning about the vertical axis (1..3600)\n"
    "  --size WxH            pixels (default 1280x960; 1..16384 each)\n"
    "  --samples N           multisampling: 1, 4 (default) or 8, as the device allows\n"
    "  --background C        white (default), black, none (transparent), #rrggbb or #rrggbbaa\n"
    "  --color-by PROP       colour by a per-vertex PLY property through a colour map\n"
    "                        (a colour bar with the range is drawn on the right)\n"
    "  --colormap NAME       viridis (default), magma, coolwarm (default for ranges across 0)\n"
    "  --units U             cm per mesh unit (default 1: sessile writes cm)\n"
    "  --ortho               orthographic camera (default perspective)\n"
    "  --no-grid             no ground grid\n"
    "  --no-annotate         no text over the picture (grid label, colour bar)\n"
    "EXR slices:\n"
    "  -o, --out PATH        the PNG to write (required)\n"
    "  --channel C           the channel (default: the file's first, in name order: c\n"
    "                        for sessile grow's slices)\n"
    "  --outline FILE.ply    the surface whose cut by the slice's plane is drawn\n"
    "                        (default: a solid/mask/phi/sdf channel when the file has one)\n"
    "  --colormap NAME       viridis, magma, coolwarm (default: by the data's sign)\n"
    "  --range LO HI         the mapped range (default: the data's)\n"
    "  --size WxH            pixels (default 800x600; 64..16384 each)\n"
    "Run directories:\n"
    "  -o, --out DIR         the folder (default RUN_DIR/renders, listed in the run's\n"
    "                        manifest; refused while a run is writing RUN_DIR)\n"
    "  --size WxH            the final mesh's views (default 1280x960)\n"
    "  --progress MODE       pictures done on stderr: auto (a status line on a terminal,\n"
    "                        else a line a tenth), tty, lines, json or none (default\n"
    "                        auto; none with --quiet; docs/run.md \"Progress\")\n"
    "Contact sheets (no device; the options below only):\n"
    "  --sheet COLS          tile the PNGs given, in order, in rows of COLS (1..1000);\n"
    "                        each cell is the largest picture's size plus a 22-pixel\n"
    "                        caption strip, 8 pixels apart; pictures are copied pixel\n"
    "                        for pixel, never scaled; at most 16384 pixels a side\n"
    "  -o, --out PATH        the PNG to write (required)\n"
    "  --caption TEXT        the caption under the picture named just before it\n"
    "All:\n"
    "  --quiet               print nothing on success\n"
    "  --device D, --validation   the Vulkan device, the validation layer\n";

static int parse_size(const char *v, uint32_t *w, uint32_t *h) {
  char *end = NULL;
  if (v[0] < '0' || v[0] > '9') return -1; /* decimal digits only: no sign, blank or hex */
  errno = 0;
  unsigned long a = strtoul(v, &end, 10);
  if ((*end != 'x' && *end != 'X') || errno) return -1;
  const char *b0 = end + 1;
  if (b0[0] < '0' || b0[0] > '9') return -1;
  unsigned long b = strtoul(b0, &end, 10);
  if (*end || errno) return -1;
  if (a < 1 || a > 16384 || b < 1 || b > 16384) return -1;
  *w = (uint32_t)a;
  *h = (uint32_t)b;
  return 0;
}

static int hexbyte(const char *s) {
  int v = 0;
  for (int i = 0; i < 2; i++) {
    char c = s[i];
    int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
            : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
    if (d < 0) return -1;
    v = v * 16 + d;
  }
  return v;
}

static int parse_color(const char *v, unsigned char rgba[4]) {
  if (!strcmp(v, "white")) { memset(rgba, 255, 4); return 0; }
  if (!strcmp(v, "black")) { rgba[0] = rgba[1] = rgba[2] = 0; rgba[3] = 255; return 0; }
  if (!strcmp(v, "none")) { memset(rgba, 0, 4); return 0; }
  size_t n = strlen(v);
  if (v[0] != '#' || (n != 7 && n != 9)) return -1;
  for (size_t i = 0; i < (n - 1) / 2; i++) {
    int b = hexbyte(v + 1 + 2 * i);
    if (b < 0) return -1;
    rgba[i] = (unsigned char)b;
  }
  if (n == 7) rgba[3] = 255;
  return 0;
}

static int ends_with(const char *s, const char *suf) {
  size_t a = strlen(s), b = strlen(suf);
  return a >= b && strcmp(s + a - b, suf) == 0;
}

/* PATH.png -> PATH_<k>.png, k zero-padded to `digits`. */
static char *frame_name(const char *out, unsigned k, int digits) {
  size_t n = strlen(out);
  size_t stem = ends_with(out, ".png") ? n - 4 : n;
  char *p = malloc(stem + 32);
  if (p) snprintf(p, stem + 32, "%.*s_%0*u.png", (int)stem, out, digits & 7, k); /* digits <= 4 */
  return p;
}

static int fail(sessile_status s) {
  char msg[1100];
  snprintf(msg, sizeof msg, "%s", sessile_error_message());
  fprintf(stderr, "sessile " CMD ": error: %s\n", msg);
  return s == SESSILE_ERR_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
}

typedef struct render_cli {
  const char *in, *out;
  unsigned turntable;
  int quiet, no_annotate, have_size;
  int progress; /* --progress (cli_progress.h): a run directory's pictures */
  sessile_render_options o;
  /* slices */
  const char *channel, *outline;
  int have_range;
  double lo, hi;
  /* an option of one kind of input only, to refuse it with another */
  const char *mesh_only, *slice_only;
} render_cli;

/* A mesh m, or a scene sc (m NULL), to the PNG(s). */
static int draw_all(sessile_gpu *g, const sessile_render_mesh *m, const sessile_render_scene *sc, const render_cli *c) {
  sessile_mesh_renderer *r = NULL;
  double t0 = sessile_wall_seconds();
  sessile_status s = m ? sessile_mesh_renderer_create(g, m, &c->o, &r, NULL)
                       : sessile_scene_renderer_create(g, sc, &c->o, &r, NULL);
  if (s != SESSILE_OK) return fail(s);
  size_t bytes = (size_t)c->o.width * c->o.height * 4u;
  unsigned char *px = malloc(bytes);
  if (!px) {
    sessile_mesh_renderer_destroy(r);
    fprintf(stderr, "sessile " CMD ": error: out of host memory for a %ux%u image\n", c->o.width,
            c->o.height);
    return EXIT_RUNTIME;
  }
  unsigned frames = c->turntable ? c->turntable : 1;
  int digits = 3;
  for (unsigned k = frames - 1; k >= 1000; k /= 10) digits++;
  int rc = EXIT_OK;
  for (unsigned k = 0; k < frames && rc == EXIT_OK; k++) {
    sessile_render_result res;
    double az = c->turntable ? 360.0 * k / frames : 0.0;
    s = sessile_mesh_renderer_draw(r, az, px, &res);
    if (s == SESSILE_OK && !c->no_annotate)
      s = sessile_render_annotate(px, (int)c->o.width, (int)c->o.height, &res, c->o.color_by);
    if (s != SESSILE_OK) {
      rc = fail(s);
      break;
    }
    char *name = c->turntable ? frame_name(c->out, k, digits) : NULL;
    const char *path = c->turntable ? name : c->out;
    if (!path || sessile_png_write_rgba8(path, (int)c->o.width, (int)c->o.height, px) != SESSILE_OK) {
      fprintf(stderr, "sessile " CMD ": error: %s\n", path ? sessile_error_message() : "out of host memory");
      rc = EXIT_RUNTIME;
    } else if (!c->quiet) {
      printf("wrote %s: %ux%u, %u samples, %s%s view", path, c->o.width, c->o.height, c->o.samples,
             c->o.ortho ? "orthographic " : "", c->o.view);
      if (c->turntable) printf(" turned %.1f deg", az);
      if (res.grid_spacing_cm > 0) printf(", grid %g cm", res.grid_spacing_cm);
      if (res.colormap[0])
        printf(", %s by %s over [%g, %g]", res.colormap, c->o.color_by, res.prop_min, res.prop_max);
      printf("\n");
    }
    free(name);
  }
  if (rc == EXIT_OK && !c->quiet && m)
    printf("%u vertices, %u triangles; %.2f s\n", m->nv, m->nf, sessile_wall_seconds() - t0);
  if (rc == EXIT_OK && !c->quiet && !m)
    printf("%u instances of %u parts (%u vertices, %u triangles); %.2f s\n", sc->ninst, sc->nparts, sc->mesh->nv,
           sc->mesh->nf, sessile_wall_seconds() - t0);
  free(px);
  sessile_mesh_renderer_destroy(r);
  return rc;
}

static int parse_args(int argc, char **argv, render_cli *c, cli_gpu_opts *go) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    const char *v = NULL;
    if (cli_stray_value(CMD, argv, i)) return EXIT_USAGE;
    /* every valued option but none repeats: the second is refused */
#define VALUE() do { if (!(v = cli_value(CMD, argc, argv, &i)) || cli_once(CMD, a[1] == 'o' ? "--out" : a, a)) \
                       return EXIT_USAGE; } while (0)
    if (!strcmp(a, "-o") || !strcmp(a, "--out")) { VALUE(); c->out = v; }
    else if (!strcmp(a, "--view")) { VALUE(); c->o.view = v; c->mesh_only = a; }
    else if (!strcmp(a, "--channel")) { VALUE(); c->channel = v; c->slice_only = a; }
    else if (!strcmp(a, "--outline")) { VALUE(); c->outline = v; c->slice_only = a; }
    else if (!strcmp(a, "--range")) {
      /* two values: a missing second one is --range's, not the first's */
      if (i + 2 >= argc || !strncmp(argv[i + 1], "--", 2) || !strncmp(argv[i + 2], "--", 2))
        return cli_usage_error(CMD, "--range needs two values: LO HI, decimal numbers with LO < HI");
      if (cli_once(CMD, a, a)) return EXIT_USAGE;
      const char *v1 = argv[++i], *v2 = argv[++i];
      if (!cli_is_decimal(v1) || !cli_is_decimal(v2) || !isfinite(c->lo = strtod(v1, NULL)) ||
          !isfinite(c->hi = strtod(v2, NULL)) || !(c->lo < c->hi))
        return cli_usage_error(CMD, "--range: '%.40s %.40s' is not two decimal numbers LO < HI", v1, v2);
      c->have_range = 1, c->slice_only = a;
    } else if (!strcmp(a, "--no-annotate")) { c->no_annotate = 1; c->mesh_only = a; }
    else if (!strcmp(a, "--turntable")) {
      c->mesh_only = a;
      VALUE();
      if (cli_parse_uint(CMD, a, v, 1, 3600, &c->turntable)) return EXIT_USAGE;
    } else if (!strcmp(a, "--size")) {
      VALUE();
      if (parse_size(v, &c->o.width, &c->o.height))
        return cli_usage_error(CMD, "--size: '%.40s' is not WxH with 1..16384 pixels each", v);
      c->have_size = 1;
    } else if (!strcmp(a, "--samples")) {
      c->mesh_only = a;
      VALUE();
      if (cli_parse_uint(CMD, a, v, 1, 8, &c->o.samples)) return EXIT_USAGE;
      if (c->o.samples != 1 && c->o.samples != 4 && c->o.samples != 8)
        return cli_usage_error(CMD, "--samples: use 1, 4 or 8");
    } else if (!strcmp(a, "--background")) {
      c->mesh_only = a;
      VALUE();
      if (parse_color(v, c->o.background))
        return cli_usage_error(CMD, "--background: '%.40s' is not white, black, none, #rrggbb or #rrggbbaa", v);
    } else if (!strcmp(a, "--color-by")) { VALUE(); c->o.color_by = v; c->mesh_only = a; }
    else if (!strcmp(a, "--colormap")) { VALUE(); c->o.colormap = v; }
    else if (!strcmp(a, "--units")) {
      c->mesh_only = a;
      VALUE();
      if (cli_parse_double(CMD, a, v, 0, 1e6, &c->o.units_cm)) return EXIT_USAGE;
      if (!(c->o.units_cm > 0)) return cli_usage_error(CMD, "--units: '%.40s' is not a number in (0, 1e6]", v);
    } else if (!strcmp(a, "--ortho")) c->o.ortho = 1, c->mesh_only = a;
    else if (!strcmp(a, "--no-grid")) c->o.grid = 0, c->mesh_only = a;
    else if (!strcmp(a, "--quiet")) c->quiet = 1;
    else {
      int r = cli_progress_option(CMD, argc, argv, &i, &c->progress);
      if (r == 0) r = cli_gpu_option(CMD, argc, argv, &i, go);
      if (r < 0) return EXIT_USAGE;
      if (r > 0) continue;
      if (a[0] == '-' && a[1]) return cli_usage_error(CMD, "unknown option '%.60s'", a);
      if (c->in) return cli_usage_error(CMD, "one input only ('%s' and '%s')", SHORT(c->in), SHORT(a));
      c->in = a;
    }
#undef VALUE
  }
  return EXIT_OK;
}

/* An input must be a regular file: opened without blocking (a FIFO has no
 * writer) and refused otherwise, before any work; its identity in *st. */
static int check_input(const char *what, const char *path, struct stat *st) {
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return cli_usage_error(CMD, "cannot read %s'%s': %s", what, SHORT(path), strerror(errno));
  int ok = fstat(fd, st) == 0 && S_ISREG(st->st_mode);
  close(fd);
  if (!ok) return cli_usage_error(CMD, "%s'%s' is not a regular file", what, SHORT(path));
  return EXIT_OK;
}

/* The output's folder must exist, its name must be usable, the output must
 * not be a folder nor one of the nin inputs (same device and inode, through
 * any link): checked before any work so that bad input writes nothing. */
static int check_out(const char *out, const char *const *ins, int nin) {
  struct stat st;
  errno = 0;
  if (stat(out, &st) != 0 && errno != ENOENT)
    return cli_usage_error(CMD, "cannot write -o '%s': %s", SHORT(out), strerror(errno));
  if (errno == 0) {
    if (S_ISDIR(st.st_mode)) return cli_usage_error(CMD, "-o '%s' is a folder: name the PNG file", SHORT(out));
    for (int k = 0; k < nin; k++) {
      struct stat si;
      if (ins[k] && stat(ins[k], &si) == 0 && si.st_dev == st.st_dev && si.st_ino == st.st_ino)
        return cli_usage_error(CMD, "-o '%s' is the input '%s': write the picture elsewhere", SHORT(out),
                               SHORT(ins[k]));
    }
  }
  const char *slash = strrchr(out, '/');
  if (slash && slash != out) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - out), out);
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
      return cli_usage_error(CMD, "the folder of -o '%s' does not exist", SHORT(out));
  }
  return EXIT_OK;
}

/* FILE.exr -> OUT.png (no device). */
static int render_slice(const render_cli *c) {
  if (c->mesh_only) return cli_usage_error(CMD, "%s is for meshes, not EXR slices", c->mesh_only);
  if (!c->out) return cli_usage_error(CMD, "name the PNG to write with -o OUT.png");
  if (!ends_with(c->out, ".png")) return cli_usage_error(CMD, "-o '%s': the output must end in .png", SHORT(c->out));
  struct stat st;
  int rc = check_input("", c->in, &st);
  if (rc == EXIT_OK && c->outline) rc = check_input("--outline ", c->outline, &st);
  const char *ins[2] = {c->in, c->outline};
  if (rc == EXIT_OK) rc = check_out(c->out, ins, 2);
  if (rc != EXIT_OK) return rc;
  char names[1024];
  sessile_status s = sessile_render_slice_channels(c->in, names, sizeof names);
  if (s != SESSILE_OK) return fail(s);
  char first[256];
  snprintf(first, sizeof first, "%.*s", (int)strcspn(names, ","), names);
  const char *channel = c->channel ? c->channel : first;
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  if (c->have_size) o.width = (int)c->o.width, o.height = (int)c->o.height;
  o.colormap = c->o.colormap;
  o.fixed_range = c->have_range, o.vmin = c->lo, o.vmax = c->hi;
  o.outline_ply = c->outline;
  s = sessile_render_slice(c->in, channel, &o, c->out);
  if (s != SESSILE_OK) return fail(s);
  if (!c->quiet)
    printf("wrote %s: %dx%d, channel %s%s%s\n", c->out, o.width, o.height, channel,
           c->channel ? "" : " (the file's first)", c->outline ? ", outline from the mesh" : "");
  return cli_finish_stdout(EXIT_OK);
}

/* RUN_DIR -> RUN_DIR/renders or -o DIR. */
static int render_run(const render_cli *c, const cli_gpu_opts *go) {
  if (c->mesh_only || c->slice_only)
    return cli_usage_error(CMD, "%s is not an option for a run directory (-o DIR, --size, --quiet)",
                           c->mesh_only ? c->mesh_only : c->slice_only);
  if (c->out && ends_with(c->out, ".png"))
    return cli_usage_error(CMD, "-o '%s': a run directory's pictures go into a folder", SHORT(c->out));
  cli_progress pr;
  cli_progress_start(&pr, CMD, c->progress, c->quiet);
  sessile_render_run_opts o = {.out_dir = c->out, .quiet = c->quiet, .progress = cli_progress_report, .progress_user = &pr};
  if (c->have_size) o.width = c->o.width, o.height = c->o.height;
  sessile_render_plan *p = NULL;
  sessile_status s = sessile_render_plan_make(c->in, &o, &p);
  if (s != SESSILE_OK) return fail(s);
  sessile_gpu *g = NULL;
  s = cli_gpu_create(go, &g);
  double t0 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_render_plan_run(p, g, stdout);
  cli_progress_end(&pr);
  sessile_gpu_destroy(g);
  sessile_render_plan_destroy(p);
  if (s != SESSILE_OK) return fail(s);
  if (!c->quiet) printf("rendered %s in %.2f s\n", c->in, sessile_wall_seconds() - t0);
  return cli_finish_stdout(EXIT_OK);
}

/* --sheet COLS -o OUT.png A.png [--caption T] B.png ...: a contact sheet of
 * PNGs (sessile_render_contact_sheet; no device).  Its own parser, so that
 * no mesh, slice or device option is silently ignored here. */
static int render_sheet(int argc, char **argv) {
  const char *out = NULL;
  unsigned cols = 0;
  int quiet = 0, n = 0;
  const char **paths = calloc((size_t)argc, sizeof *paths);
  const char **caps = calloc((size_t)argc, sizeof *caps);
  int rc = EXIT_OK;
  if (!paths || !caps) {
    fprintf(stderr, "sessile " CMD ": error: out of host memory\n");
    rc = EXIT_RUNTIME;
  }
  for (int i = 1; i < argc && rc == EXIT_OK; i++) {
    const char *a = argv[i], *v = NULL;
    if (cli_stray_value(CMD, argv, i)) rc = EXIT_USAGE;
    else if (!strcmp(a, "--sheet")) {
      if (!(v = cli_value(CMD, argc, argv, &i)) || cli_once(CMD, a, a) || cli_parse_uint(CMD, a, v, 1, 1000, &cols))
        rc = EXIT_USAGE;
    } else if (!strcmp(a, "-o") || !strcmp(a, "--out")) {
      if (!(v = cli_value(CMD, argc, argv, &i)) || cli_once(CMD, "--out", a)) rc = EXIT_USAGE;
      else out = v;
    } else if (!strcmp(a, "--caption")) {
      if (!(v = cli_value(CMD, argc, argv, &i))) rc = EXIT_USAGE;
      else if (n == 0) rc = cli_usage_error(CMD, "--caption '%.60s' before any picture: it follows its picture", v);
      else if (caps[n - 1]) rc = cli_usage_error(CMD, "two captions for '%s'", SHORT(paths[n - 1]));
      else caps[n - 1] = v;
    } else if (!strcmp(a, "--quiet")) quiet = 1;
    else if (a[0] == '-' && a[1])
      rc = cli_usage_error(CMD, "'%.60s' is not an option of --sheet (-o, --caption, --quiet)", a);
    else paths[n++] = a;
  }
  if (rc == EXIT_OK && !out) rc = cli_usage_error(CMD, "name the sheet to write with -o OUT.png");
  if (rc == EXIT_OK && !ends_with(out, ".png"))
    rc = cli_usage_error(CMD, "-o '%s': the output must end in .png", SHORT(out));
  if (rc == EXIT_OK && n == 0) rc = cli_usage_error(CMD, "--sheet: name the PNGs to tile");
  for (int k = 0; k < n && rc == EXIT_OK; k++) {
    struct stat st;
    rc = check_input("", paths[k], &st);
  }
  if (rc == EXIT_OK) rc = check_out(out, paths, n);
  if (rc == EXIT_OK) {
    sessile_status s = sessile_render_contact_sheet(paths, caps, n, (int)cols, out);
    if (s != SESSILE_OK) rc = fail(s);
  }
  if (rc == EXIT_OK && !quiet) {
    unsigned c = cols < (unsigned)n ? cols : (unsigned)n, rows = ((unsigned)n + c - 1) / c;
    printf("wrote %s: %d picture%s in %u column%s, %u row%s\n", out, n, n == 1 ? "" : "s", c, c == 1 ? "" : "s",
           rows, rows == 1 ? "" : "s");
  }
  free(paths);
  free(caps);
  return cli_finish_stdout(rc);
}

int cmd_render(int argc, char **argv, const cli_gpu_opts *global) {
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return cli_finish_stdout(EXIT_OK);
    }
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "--sheet")) return render_sheet(argc, argv);
  render_cli c = {0};
  sessile_render_options_default(&c.o);
  cli_gpu_opts go = *global;
  int rc = parse_args(argc, argv, &c, &go);
  if (rc != EXIT_OK) return rc;
  if (!c.in) return cli_usage_error(CMD, "name a mesh (.ply, .obj), an EXR slice or a run directory");
  sessile_status s = cli_gpu_check(&go); /* an unknown --device: refused before anything is written */
  if (s != SESSILE_OK) return fail(s);
  struct stat st;
  if (stat(c.in, &st) != 0)
    return cli_usage_error(CMD, "cannot read '%s': %s", SHORT(c.in), strerror(errno));
  if (S_ISDIR(st.st_mode)) return render_run(&c, &go);
  if (ends_with(c.in, ".exr")) return render_slice(&c);
  if (c.slice_only) return cli_usage_error(CMD, "%s is for EXR slices, not meshes", c.slice_only);
  if (!c.out) return cli_usage_error(CMD, "name the PNG to write with -o OUT.png");
  if (!ends_with(c.out, ".png")) return cli_usage_error(CMD, "-o '%s': the output must end in .png", SHORT(c.out));
  if ((rc = check_input("", c.in, &st)) != EXIT_OK) return rc;
  const char *ins[1] = {c.in};
  if ((rc = check_out(c.out, ins, 1)) != EXIT_OK) return rc;
  s = sessile_render_options_check(&c.o, NULL);
  if (s != SESSILE_OK) return fail(s);
  sessile_render_mesh *m = NULL;
  sessile_render_scene *sc = NULL;
  int scene = sessile_render_is_scene(c.in);
  if (scene && c.o.color_by) return cli_usage_error(CMD, "--color-by is for meshes: a scene has its own colours");
  s = scene ? sessile_render_scene_read(c.in, &sc) : sessile_render_mesh_read(c.in, &m);
  if (s == SESSILE_OK && m) s = sessile_render_options_check(&c.o, m);
  sessile_gpu *g = NULL;
  if (s == SESSILE_OK) s = cli_gpu_create(&go, &g);
  if (s != SESSILE_OK) {
    sessile_render_mesh_destroy(m);
    sessile_render_scene_destroy(sc);
    return fail(s);
  }
  rc = draw_all(g, m, sc, &c);
  sessile_render_mesh_destroy(m);
  sessile_render_scene_destroy(sc);
  sessile_gpu_destroy(g);
  return cli_finish_stdout(rc);
}
