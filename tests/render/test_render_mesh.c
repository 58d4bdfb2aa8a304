/* The mesh renderer against analytic pictures (docs/render.md, "Tests"):
 * - a unit cube seen orthographically from the top covers edge^2 px_per_cm^2
 *   pixels (1 sample: no partial coverage) within 1 %;
 * - an icosphere's silhouette is a disc: radius from the area within 1 % of
 *   R px_per_cm, centroid at the image centre within 0.5 px, no pixel beyond
 *   R px_per_cm + 1;
 * - the three visible faces of a cube in the oblique view have the shade of
 *   the documented formula (lights of render_mesh.h, camera basis from the
 *   documented view angles) within 2 levels;
 * - a constant property colours through viridis(0.5); a range across 0
 *   picks coolwarm, symmetric;
 * - the same input twice gives identical pixels; the grid spacing is 1-2-5;
 * - unsupported sample counts and bad options are refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/gpu/graphics.h"
#include "render_shapes.h"
#include "sessile/io/colormap.h"
#include "sessile/render/render_mesh.h"
#include "testutil.h"

static unsigned char *render(sessile_gpu *g, const sessile_render_mesh *m, const sessile_render_options *o,
                             sessile_render_result *res) {
  sessile_mesh_renderer *r = NULL;
  unsigned char *px = t_xalloc((size_t)o->width * o->height * 4);
  t_must("renderer create", sessile_mesh_renderer_create(g, m, o, &r, NULL));
  t_must("draw", sessile_mesh_renderer_draw(r, 0, px, res));
  sessile_mesh_renderer_destroy(r);
  return px;
}

static void options(sessile_render_options *o, const char *view, uint32_t samples) {
  sessile_render_options_default(o);
  o->width = o->height = 256;
  o->samples = samples;
  o->view = view;
  o->ortho = 1;
  o->grid = 0;
  o->background[0] = o->background[1] = o->background[2] = 0;
}

static void test_cube_top(sessile_gpu *g) {
  double pos[72];
  uint32_t tri[36];
  shape_cube(0.0, 1.0, pos, tri);
  sessile_render_mesh *m = NULL;
  t_must("cube mesh", sessile_render_mesh_from_arrays(pos, 24, tri, 12, &m));
  sessile_render_options o;
  options(&o, "top", 1);
  o.width = o.height = 512; /* edges cost at most a pixel row per side: < 0.5 % here */
  sessile_render_result res;
  unsigned char *px = render(g, m, &o, &res);
  const unsigned char bg[3] = {0, 0, 0};
  double expect = res.px_per_cm * res.px_per_cm; /* 1 cm x 1 cm */
  long got = count_not_bg(px, o.width, o.height, bg);
  printf("cube from the top: %ld pixels, expected %.1f (%.3f px/cm)\n", got, expect, res.px_per_cm);
  t_check("unit cube, top, orthographic: covered area within 1 %", fabs(got - expect) / expect, 0.01);
  free(px);
  /* units: the same cube in mm (edge 10 units of 0.1 cm) covers the same pixels */
  for (int i = 0; i < 72; i++) pos[i] *= 10;
  sessile_render_mesh *mm = NULL;
  t_must("cube in mm", sessile_render_mesh_from_arrays(pos, 24, tri, 12, &mm));
  o.units_cm = 0.1;
  sessile_render_result r2;
  px = render(g, mm, &o, &r2);
  long got2 = count_not_bg(px, o.width, o.height, bg);
  t_check("the cube in mm with units 0.1: same px per cm", fabs(r2.px_per_cm - res.px_per_cm) / res.px_per_cm, 1e-9);
  t_check("... and the same area (pixels)", fabs((double)(got2 - got)), 0);
  free(px);
  sessile_render_mesh_destroy(mm);
  sessile_render_mesh_destroy(m);
}

static void test_sphere_disc(sessile_gpu *g) {
  double *pos;
  uint32_t *tri, nv;
  uint32_t nf = shape_icosphere(5, 2.0, &pos, &tri, &nv);
  sessile_render_mesh *m = NULL;
  t_must("icosphere", sessile_render_mesh_from_arrays(pos, nv, tri, nf, &m));
  free(pos);
  free(tri);
  const char *views[2] = {"front", "oblique"};
  for (int v = 0; v < 2; v++) {
    sessile_render_options o;
    options(&o, views[v], 1);
    sessile_render_result res;
    unsigned char *px = render(g, m, &o, &res);
    double R = 2.0 * res.px_per_cm, sx = 0, sy = 0, far = 0;
    long n = 0;
    double c[3] = {0, 0, 0}, cx, cy;
    project(res.clip_from_world, c, o.width, o.height, &cx, &cy);
    for (uint32_t y = 0; y < o.height; y++)
      for (uint32_t x = 0; x < o.width; x++) {
        const unsigned char *p = px + 4 * ((size_t)y * o.width + x);
        if (!p[0] && !p[1] && !p[2]) continue;
        n++;
        sx += x + 0.5;
        sy += y + 0.5;
        far = fmax(far, hypot(x + 0.5 - cx, y + 0.5 - cy));
      }
    double rfit = sqrt(n / 3.14159265358979);
    printf("sphere (%s): %ld pixels, radius from area %.2f px, expected %.2f; centroid (%.2f, %.2f), "
           "centre (%.2f, %.2f); farthest pixel %.2f\n",
           views[v], n, rfit, R, sx / n, sy / n, cx, cy, far);
    char what[160];
    snprintf(what, sizeof what, "sphere silhouette (%s): radius from area within 1 %%", views[v]);
    t_check(what, fabs(rfit - R) / R, 0.01);
    snprintf(what, sizeof what, "... (%s): centroid at the projected centre within 0.5 px", views[v]);
    t_check(what, hypot(sx / n - cx, sy / n - cy), 0.5);
    snprintf(what, sizeof what, "... (%s): no pixel beyond R + 1 px (a disc)", views[v]);
    t_check(what, fmax(0, far - (R + 1)), 0);
    free(px);
  }
  sessile_render_mesh_destroy(m);
}

/* The documented shade of camera-space normal n (render_mesh.h). */
static double shade_of(const double n[3]) {
  const double key[3] = SESSILE_RENDER_KEY_DIR, fill[3] = SESSILE_RENDER_FILL_DIR;
  double lk = sqrt(key[0] * key[0] + key[1] * key[1] + key[2] * key[2]);
  double lf = sqrt(fill[0] * fill[0] + fill[1] * fill[1] + fill[2] * fill[2]);
  double dk = (n[0] * key[0] + n[1] * key[1] + n[2] * key[2]) / lk;
  double df = (n[0] * fill[0] + n[1] * fill[1] + n[2] * fill[2]) / lf;
  return SESSILE_RENDER_AMBIENT + SESSILE_RENDER_KEY_W * fmax(dk, 0) + SESSILE_RENDER_FILL_W * fmax(df, 0);
}

static void test_shade(sessile_gpu *g) {
  double pos[72];
  uint32_t tri[36];
  shape_cube(0.0, 1.0, pos, tri);
  sessile_render_mesh *m = NULL;
  t_must("cube mesh", sessile_render_mesh_from_arrays(pos, 24, tri, 12, &m));
  sessile_render_options o;
  options(&o, "oblique", 4);
  sessile_render_result res;
  unsigned char *px = render(g, m, &o, &res);
  /* the documented oblique view: azimuth -60, elevation 30 (docs/render.md) */
  double az = -60 * 3.14159265358979 / 180, el = 30 * 3.14159265358979 / 180;
  double t[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)};
  double r[3] = {-sin(az), cos(az), 0};
  double u[3] = {t[1] * r[2] - t[2] * r[1], t[2] * r[0] - t[0] * r[2], t[0] * r[1] - t[1] * r[0]};
  const double face_n[3][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
  const double face_c[3][3] = {{1, 0.5, 0.5}, {0.5, 0, 0.5}, {0.5, 0.5, 1}};
  const char *names[3] = {"+x", "-y", "+z"};
  const unsigned char base[3] = SESSILE_RENDER_BASE_COLOR;
  for (int f = 0; f < 3; f++) {
    const double *n = face_n[f];
    double nc[3] = {n[0] * r[0] + n[1] * r[1] + n[2] * r[2], n[0] * u[0] + n[1] * u[1] + n[2] * u[2],
                    n[0] * t[0] + n[1] * t[1] + n[2] * t[2]};
    double s = shade_of(nc), x, y;
    project(res.clip_from_world, face_c[f], o.width, o.height, &x, &y);
    const unsigned char *p = px + 4 * ((size_t)floor(y) * o.width + (size_t)floor(x));
    double err = 0;
    for (int k = 0; k < 3; k++) {
      double e = fmin(255.0, base[k] * s);
      err = fmax(err, fabs(p[k] - e));
      if (k == 0)
        printf("face %s: camera normal (%.3f, %.3f, %.3f), shade %.4f, pixel (%.0f, %.0f) = (%d, %d, %d), "
               "expected (%.1f, %.1f, %.1f)\n", names[f], nc[0], nc[1], nc[2], s, x, y, p[0], p[1], p[2],
               fmin(255, base[0] * s), fmin(255, base[1] * s), fmin(255, base[2] * s));
    }
    char what[120];
    snprintf(what, sizeof what, "face %s shade within 2 levels of the formula", names[f]);
    t_check(what, err, 2.0);
  }
  t_check("without the grid the result's spacing is 0", res.grid_spacing_cm, 0);
  free(px);
  sessile_render_mesh_destroy(m);
}

static void test_color_and_determinism(sessile_gpu *g) {
  /* a flat square of 4 vertices with a property, seen from the top */
  const double pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
  sessile_render_mesh *m = NULL;
  t_must("square", sessile_render_mesh_from_arrays(pos, 4, tri, 2, &m));
  /* attach a property by hand (as the PLY reader would) */
  m->prop_names = calloc(1, sizeof(char *));
  m->props = calloc(1, sizeof(float *));
  m->prop_names[0] = strdup("c");
  m->props[0] = malloc(4 * sizeof(float));
  m->nprops = 1;
  for (int i = 0; i < 4; i++) m->props[0][i] = 3.0f;
  sessile_render_options o;
  options(&o, "top", 4);
  o.color_by = "c";
  sessile_render_result res;
  unsigned char *px = render(g, m, &o, &res);
  unsigned char want[3];
  sessile_colormap("viridis", 0.5, want);
  double nc[3] = {0, 0, 1}, s = shade_of(nc), err = 0;
  const unsigned char *p = px + 4 * ((size_t)128 * o.width + 128);
  for (int k = 0; k < 3; k++) err = fmax(err, fabs(p[k] - fmin(255, want[k] * s)));
  printf("constant property: pixel (%d, %d, %d), viridis(0.5) (%d, %d, %d) x shade %.4f\n", p[0], p[1], p[2],
         want[0], want[1], want[2], s);
  t_true("a constant property uses viridis", strcmp(res.colormap, "viridis") == 0);
  t_check("... and colours with viridis(0.5) x shade within 2 levels", err, 2.0);
  /* determinism: a second renderer, identical bytes */
  sessile_render_result res2;
  unsigned char *px2 = render(g, m, &o, &res2);
  t_true("same input, same device: identical pixels", memcmp(px, px2, (size_t)o.width * o.height * 4) == 0);
  free(px2);
  free(px);
  /* a range across 0: coolwarm, symmetric */
  const float v[4] = {-1, 0, 2, 0.5f};
  memcpy(m->props[0], v, sizeof v);
  px = render(g, m, &o, &res);
  t_true("a range across 0 picks coolwarm", strcmp(res.colormap, "coolwarm") == 0);
  t_check("... over [-2, 2]", fabs(res.prop_min + 2) + fabs(res.prop_max - 2), 0);
  free(px);
  o.colormap = "magma";
  px = render(g, m, &o, &res);
  t_true("--colormap magma is used as given", strcmp(res.colormap, "magma") == 0);
  t_check("... over the data's range [-1, 2] (not a diverging map)", fabs(res.prop_min + 1) + fabs(res.prop_max - 2), 0);
  free(px);
  /* the default: a grid, oblique, perspective: the grid spacing reaches the caller */
  sessile_render_options_default(&o);
  o.width = 160;
  o.height = 120;
  px = render(g, m, &o, &res);
  t_check("a default render: grid 0.1 cm for a 1 cm square", fabs(res.grid_spacing_cm - 0.1), 1e-12);
  const unsigned char white[3] = {255, 255, 255};
  t_true("... draws something on the white background", count_not_bg(px, o.width, o.height, white) > 100);
  free(px);
  /* bad options */
  sessile_render_options_default(&o);
  o.view = "below";
  t_true("unknown view refused (USAGE)", sessile_render_options_check(&o, m) == SESSILE_ERR_USAGE);
  printf("  message: %s\n", sessile_error_message());
  sessile_render_options_default(&o);
  o.color_by = "nope";
  t_true("unknown property refused (USAGE)", sessile_render_options_check(&o, m) == SESSILE_ERR_USAGE);
  printf("  message: %s\n", sessile_error_message());
  sessile_render_options_default(&o);
  o.width = 0;
  t_true("size 0 refused (USAGE)", sessile_render_options_check(&o, m) == SESSILE_ERR_USAGE);
  o.width = 100000;
  t_true("size 100000 refused (USAGE)", sessile_render_options_check(&o, m) == SESSILE_ERR_USAGE);
  sessile_render_options_default(&o);
  o.colormap = "jet";
  t_true("unknown colour map refused (USAGE)", sessile_render_options_check(&o, m) == SESSILE_ERR_USAGE);
  /* 8 samples: drawn where the device has them, refused as USAGE where not */
  sessile_render_options_default(&o);
  o.width = 64;
  o.height = 48;
  o.samples = 8;
  sessile_mesh_renderer *r = NULL;
  sessile_status st = sessile_mesh_renderer_create(g, m, &o, &r, NULL);
  int has8 = (sessile_gfx_sample_counts(g) & 8) != 0;
  printf("8 samples: device mask 0x%x, create -> %s\n", sessile_gfx_sample_counts(g), sessile_status_name(st));
  t_true("8 samples: made when supported, refused (USAGE) when not",
         has8 ? st == SESSILE_OK : st == SESSILE_ERR_USAGE);
  sessile_mesh_renderer_destroy(r);
  sessile_render_mesh_destroy(m);
}

static void test_colormaps(void) {
  unsigned char c[3];
  /* matplotlib's published endpoints: viridis #440154 .. #fde725, magma
   * #000004 .. #fcfdbf, coolwarm (59,76,192) .. (180,4,38) */
  sessile_colormap("viridis", 0, c);
  t_true("viridis(0) = #440154", c[0] == 0x44 && c[1] == 0x01 && c[2] == 0x54);
  sessile_colormap("viridis", 1, c);
  t_true("viridis(1) = #fde725", c[0] == 0xfd && c[1] == 0xe7 && c[2] == 0x25);
  sessile_colormap("magma", 0, c);
  t_true("magma(0) = #000004", c[0] == 0 && c[1] == 0 && c[2] == 4);
  sessile_colormap("magma", 1, c);
  t_true("magma(1) = #fcfdbf", c[0] == 0xfc && c[1] == 0xfd && c[2] == 0xbf);
  sessile_colormap("coolwarm", 0, c);
  t_true("coolwarm(0) = (59, 76, 192)", c[0] == 59 && c[1] == 76 && c[2] == 192);
  sessile_colormap("coolwarm", 1, c);
  t_true("coolwarm(1) = (180, 4, 38)", c[0] == 180 && c[1] == 4 && c[2] == 38);
  t_true("unknown map: -1", sessile_colormap("jet", 0.5, c) == -1);
  /* monotone lightness proxy: viridis's green channel rises over the map */
  int mono = 1;
  unsigned char prev[3];
  sessile_colormap("viridis", 0, prev);
  for (int i = 1; i < 256; i++) {
    sessile_colormap("viridis", i / 255.0, c);
    if (c[1] < prev[1]) mono = 0;
    memcpy(prev, c, 3);
  }
  t_true("viridis's green channel never falls (perceptually ordered)", mono);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  test_colormaps();
  test_cube_top(g);
  test_sphere_disc(g);
  test_shade(g);
  test_color_and_determinism(g);
  return t_finish(g);
}
