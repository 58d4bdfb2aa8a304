/* sessile_render_slice: a linear ramp written into an EXR maps, pixel by
 * pixel, to the colour map's values; a signed field takes the diverging map
 * with 0 at its centre; the colour bar ends are the map's ends; the outline
 * (a level-set channel, or a surface mesh cut by the plane) lies on the
 * circle it should; same bytes on rerun; bad input: an error and no file. */
#include <math.h>
#include <openexr.h>
#include "render2d_testutil.h"
#include "sessile/io/colormap.h"
#include "sessile/io/io.h"
#include "sessile/render/render2d.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"


/* The test plane: u along world x, v along world z, 21 x 11 nodes of
 * 0.5 x 0.25 cm, so u in [0, 10] and v in [0, 2.5] cm. */
static const sessile_plane plane = {{1, 2, -1}, {1, 0, 0}, {0, 0, 1}, {0.5, 0.25}, 21, 11};
static double ramp(double u) { return 3 + 0.7 * u; }                 /* 3 .. 10 */
static double signed_field(double u) { return 1.4 * u - 3; } /* -3 .. 11 */
static const double disc_u = 6, disc_v = 1.25, disc_r = 1;

/* Every pixel of the image area against the map of the analytic value at
 * its centre (the renderer's sampling); t within 1e-6 of a bin edge may take
 * either bin (float32 storage). */
static void check_image(const char *png, const sessile_slice_layout *L, double (*f)(double), const char *what) {
  t_png p = t_png_read(png);
  char msg[200];
  snprintf(msg, sizeof msg, "%s: PNG reads back as %d x %d", what, L->width, L->height);
  t_true(msg, p.px && p.w == L->width && p.h == L->height);
  if (!p.px) return;
  int worst = 0;
  for (int py = 0; py < L->img_h; py++)
    for (int px = 0; px < L->img_w; px++) {
      double u = L->u0 + (px + 0.5) / L->img_w * (L->u1 - L->u0);
      double t = (f(u) - L->vmin) / (L->vmax - L->vmin);
      int best = 255;
      for (int k = -1; k <= 1; k++) {
        unsigned char rgb[3];
        sessile_colormap(L->colormap, t + k * 1e-6, rgb);
        int d = t_rgb_diff(t_px(&p, L->img_x + px, L->img_y + py), rgb);
        if (d < best) best = d;
      }
      if (best > worst) worst = best;
    }
  snprintf(msg, sizeof msg, "%s: %d x %d image pixels vs %s(t of the value at the pixel centre), max level diff",
           what, L->img_w, L->img_h, L->colormap);
  t_check(msg, worst, 1);
  /* the colour bar: top row = map(1), bottom row = map(0), across its width */
  unsigned char top[3], bot[3];
  sessile_colormap(L->colormap, 1, top);
  sessile_colormap(L->colormap, 0, bot);
  int bd = 0;
  for (int x = 0; x < L->bar_w; x++) {
    bd = fmax(bd, t_rgb_diff(t_px(&p, L->bar_x + x, L->bar_y), top));
    bd = fmax(bd, t_rgb_diff(t_px(&p, L->bar_x + x, L->bar_y + L->bar_h - 1), bot));
  }
  snprintf(msg, sizeof msg, "%s: colour bar top row = %s(1), bottom row = %s(0), max level diff", what,
           L->colormap, L->colormap);
  t_check(msg, bd, 0);
  free(p.px);
}

/* The outline passes through the circle's four extreme points: a dark pixel
 * (the 1.5 px black line) within 1 pixel of each; the disc's centre is not dark. */
static void check_outline(const char *png, const sessile_slice_layout *L, const char *what) {
  t_png p = t_png_read(png);
  if (!p.px) {
    t_true(what, 0);
    return;
  }
  double kx = L->img_w / (L->u1 - L->u0), ky = L->img_h / (L->v1 - L->v0);
  const double du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
  int darkest_max = 0;
  for (int k = 0; k < 4; k++) {
    double x = L->img_x + (disc_u + disc_r * du[k] - L->u0) * kx;
    double y = L->img_y + (L->v1 - disc_v - disc_r * dv[k]) * ky;
    int darkest = 255;
    for (int j = -1; j <= 1; j++)
      for (int i = -1; i <= 1; i++) {
        uint32_t q = t_px(&p, (int)floor(x) + i, (int)floor(y) + j);
        int m = (int)fmax(fmax((q >> 16) & 255, (q >> 8) & 255), q & 255);
        if (m < darkest) darkest = m;
      }
    if (darkest > darkest_max) darkest_max = darkest;
  }
  char msg[200];
  snprintf(msg, sizeof msg, "%s: outline at the circle's 4 extreme points (brightest of the darkest 3x3 pixels, <= 60)", what);
  t_check(msg, darkest_max, 60);
  uint32_t c = t_px(&p, (int)(L->img_x + (disc_u - L->u0) * kx), (int)(L->img_y + (L->v1 - disc_v) * ky));
  int m = (int)fmax(fmax((c >> 16) & 255, (c >> 8) & 255), c & 255);
  snprintf(msg, sizeof msg, "%s: no outline at the disc's centre (brightest channel %d > 60)", what, m);
  t_true(msg, m > 60);
  free(p.px);
}

/* A valid EXR that sessile did not write: part "image", channel Y, no sessile:* attributes. */
static int write_foreign_exr(const char *path) {
  exr_context_t ctx;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) return 0;
  int part = 0, ok = 1;
  float px[16] = {0};
  ok &= exr_add_part(ctx, "image", EXR_STORAGE_SCANLINE, &part) == EXR_ERR_SUCCESS;
  ok &= exr_initialize_required_attr_simple(ctx, part, 4, 4, EXR_COMPRESSION_NONE) == EXR_ERR_SUCCESS;
  ok &= exr_add_channel(ctx, part, "Y", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1) == EXR_ERR_SUCCESS;
  ok &= exr_write_header(ctx) == EXR_ERR_SUCCESS;
  exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
  int live = 0;
  for (int y = 0; ok && y < 4; y++) {
    exr_chunk_info_t ci;
    ok &= exr_write_scanline_chunk_info(ctx, part, y, &ci) == EXR_ERR_SUCCESS;
    if (ok && !live) ok = exr_encoding_initialize(ctx, part, &ci, &enc) == EXR_ERR_SUCCESS, live = ok;
    else if (ok) ok = exr_encoding_update(ctx, part, &ci, &enc) == EXR_ERR_SUCCESS;
    if (!ok) break;
    enc.channels[0].user_pixel_stride = 4;
    enc.channels[0].user_line_stride = 16;
    enc.channels[0].user_bytes_per_element = 4;
    enc.channels[0].user_data_type = EXR_PIXEL_FLOAT;
    enc.channels[0].encode_from_ptr = (const uint8_t *)(px + 4 * y);
    if (y == 0) ok &= exr_encoding_choose_default_routines(ctx, part, &enc) == EXR_ERR_SUCCESS;
    ok &= exr_encoding_run(ctx, part, &enc) == EXR_ERR_SUCCESS;
  }
  if (live) exr_encoding_destroy(ctx, &enc);
  return exr_finish(&ctx) == EXR_ERR_SUCCESS && ok;
}

static void bad(const char *what, sessile_status s, const char *out, const char *must_contain) {
  char msg[400];
  const char *m = sessile_error_message();
  snprintf(msg, sizeof msg, "%s: SESSILE_ERR_USAGE, one line naming '%s', nothing written [%s]", what, must_contain, m);
  t_true(msg, s == SESSILE_ERR_USAGE && !strchr(m, '\n') && strstr(m, must_contain) && !t_exists(out));
}

int main(void) {
  dir = t_scratch("test_render_slice");
  size_t n = (size_t)plane.width * plane.height;
  double *fr = t_dalloc(n), *fs = t_dalloc(n), *fc = t_dalloc(n), *fphi = t_dalloc(n);
  for (uint32_t j = 0; j < plane.height; j++)
    for (uint32_t i = 0; i < plane.width; i++) {
      double u = i * plane.spacing[0], v = j * plane.spacing[1];
      size_t q = (size_t)j * plane.width + i;
      fr[q] = ramp(u);
      fs[q] = signed_field(u);
      fc[q] = i == 0 && j == 0 ? -1e-9 : ramp(u); /* float noise below 0 stays one-signed */
      fphi[q] = disc_r - hypot(u - disc_u, v - disc_v);
    }
  const char *names[3] = {"ramp", "s", "c"};
  const double *vals[3] = {fr, fs, fc};
  t_must("write the ramp EXR", sessile_write_plane_exr_values(P("ramp.exr"), &plane, "test plane", 3, names, vals, 4));
  const char *dnames[2] = {"c", "phi"};
  const double *dvals[2] = {fr, fphi};
  t_must("write the disc EXR", sessile_write_plane_exr_values(P("disc.exr"), &plane, "disc plane", 2, dnames, dvals, 0));

  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  sessile_slice_layout L;
  /* one-signed ramp: viridis over the data range */
  t_ok("render channel ramp", sessile_render_slice(P("ramp.exr"), "ramp", &o, P("ramp.png")));
  t_ok("layout of channel ramp", sessile_render_slice_layout(P("ramp.exr"), "ramp", &o, &L));
  t_true("ramp: viridis, range [3, 10], image aspect 10 : 2.5 within a pixel",
         !strcmp(L.colormap, "viridis") && fabs(L.vmin - 3) < 1e-6 && fabs(L.vmax - 10) < 1e-6 &&
             fabs(L.img_w - 4.0 * L.img_h) <= 4.0 && L.u0 == 0 && fabs(L.u1 - 10) < 1e-9);
  check_image(P("ramp.png"), &L, ramp, "ramp");
  /* signed: coolwarm, symmetric range, so 0 falls on the map's centre */
  t_ok("render channel s", sessile_render_slice(P("ramp.exr"), "s", &o, P("s.png")));
  t_ok("layout of channel s", sessile_render_slice_layout(P("ramp.exr"), "s", &o, &L));
  t_true("signed s (-3 .. 11): coolwarm over [-11, 11]",
         !strcmp(L.colormap, "coolwarm") && fabs(L.vmin + 11) < 1e-5 && fabs(L.vmax - 11) < 1e-5);
  check_image(P("s.png"), &L, signed_field, "signed s");
  {
    t_png p = t_png_read(P("s.png"));
    /* the pixel whose centre is nearest u = 3/1.4 (s = 0) has the map's centre colour */
    double uz = 3 / 1.4;
    int px = (int)floor((uz - L.u0) / (L.u1 - L.u0) * L.img_w);
    double u = L.u0 + (px + 0.5) / L.img_w * (L.u1 - L.u0), t = (signed_field(u) - L.vmin) / (L.vmax - L.vmin);
    unsigned char mid[3];
    sessile_colormap("coolwarm", 0.5, mid);
    char msg[160];
    snprintf(msg, sizeof msg, "signed s: the pixel at s = 0 (t = %.4f) has coolwarm(0.5), max level diff", t);
    t_check(msg, p.px ? t_rgb_diff(t_px(&p, L.img_x + px, L.img_y + L.img_h / 2), mid) : 999, 1);
    free(p.px);
  }
  /* one-signed with float noise: viridis */
  t_ok("layout of channel c (min -1e-9)", sessile_render_slice_layout(P("ramp.exr"), "c", &o, &L));
  t_true("c with a -1e-9 pixel stays one-signed (viridis)", !strcmp(L.colormap, "viridis"));
  /* a fixed range and a chosen map */
  o.fixed_range = 1, o.vmin = 0, o.vmax = 20, o.colormap = "magma";
  t_ok("render ramp with magma on [0, 20]", sessile_render_slice(P("ramp.exr"), "ramp", &o, P("magma.png")));
  t_ok("layout with magma on [0, 20]", sessile_render_slice_layout(P("ramp.exr"), "ramp", &o, &L));
  t_true("magma on [0, 20] is used", !strcmp(L.colormap, "magma") && L.vmin == 0 && L.vmax == 20);
  check_image(P("magma.png"), &L, ramp, "ramp, magma [0, 20]");
  sessile_render2d_opts_default(&o);

  /* the outline: the phi channel's 0 contour, and an icosphere cut by the plane */
  t_ok("render c with the phi outline", sessile_render_slice(P("disc.exr"), "c", &o, P("disc.png")));
  t_ok("layout of disc", sessile_render_slice_layout(P("disc.exr"), "c", &o, &L));
  check_outline(P("disc.png"), &L, "phi = 0 contour (marching squares)");
  sessile_surface sph = {0};
  double centre[3] = {plane.origin[0] + disc_u, plane.origin[1], plane.origin[2] + disc_v};
  t_must("icosphere", sessile_surface_icosphere(4, disc_r, centre, &sph));
  t_must("write the sphere PLY", sessile_write_ply(P("sphere.ply"), &sph, NULL, 0, NULL, NULL));
  sessile_surface_free(&sph);
  char ply[512];
  snprintf(ply, sizeof ply, "%s", P("sphere.ply"));
  o.outline_ply = ply;
  t_ok("render ramp with the sphere's cut", sessile_render_slice(P("ramp.exr"), "ramp", &o, P("cut.png")));
  t_ok("layout of cut", sessile_render_slice_layout(P("ramp.exr"), "ramp", &o, &L));
  check_outline(P("cut.png"), &L, "icosphere (level 4) cut by the plane");
  sessile_render2d_opts_default(&o);

  /* determinism */
  t_ok("render ramp again", sessile_render_slice(P("ramp.exr"), "ramp", &o, P("ramp2.png")));
  t_true("same input, identical PNG bytes", t_same_bytes(P("ramp.png"), P("ramp2.png")));

  /* bad input: SESSILE_ERR_USAGE, one line, nothing written */
  bad("missing file", sessile_render_slice(P("nope.exr"), "c", &o, P("bad1.png")), P("bad1.png"), "nope.exr");
  bad("unknown channel lists the channels", sessile_render_slice(P("ramp.exr"), "q", &o, P("bad2.png")),
      P("bad2.png"), "channels: c, ramp, s");
  o.width = 0;
  bad("size 0", sessile_render_slice(P("ramp.exr"), "c", &o, P("bad3.png")), P("bad3.png"), "0 x 600");
  o.width = 100000;
  bad("size 100000", sessile_render_slice(P("ramp.exr"), "c", &o, P("bad4.png")), P("bad4.png"), "100000");
  sessile_render2d_opts_default(&o);
  t_true("write a foreign EXR", write_foreign_exr(P("foreign.exr")));
  bad("an EXR sessile did not write", sessile_render_slice(P("foreign.exr"), "Y", &o, P("bad5.png")), P("bad5.png"),
      "not a sessile slice");
  FILE *f = fopen(P("text.exr"), "w");
  if (f) fputs("not an image\n", f), fclose(f);
  bad("a text file", sessile_render_slice(P("text.exr"), "c", &o, P("bad6.png")), P("bad6.png"), "not an EXR");
  o.colormap = "rainbow";
  bad("unknown colour map", sessile_render_slice(P("ramp.exr"), "c", &o, P("bad7.png")), P("bad7.png"), "rainbow");
  sessile_render2d_opts_default(&o);
  o.outline_ply = "missing.ply";
  bad("missing outline mesh", sessile_render_slice(P("ramp.exr"), "c", &o, P("bad8.png")), P("bad8.png"), "missing.ply");
  free(fr), free(fs), free(fc), free(fphi);
  return t_finish(NULL);
}
