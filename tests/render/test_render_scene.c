/* Instanced scenes (render_scene.h; docs/render.md, "Scenes"):
 * - a scene of a "seabed" quad (green), two spheres (pure red: two
 *   instances of one part) and a cube (pure blue, non-uniformly scaled and
 *   sheared) seen from the top: the pixel under each organism's centre has its hue,
 *   a seabed pixel has the seabed's, and the red area is the two discs'
 *   pi (R1^2 + R2^2) px_per_cm^2 within 5 %;
 * - the same scene with every instance in the base colour, oblique with
 *   perspective, grid and 4 samples, against the merged mesh (the instances'
 *   vertices transformed on the host) drawn by the mesh renderer: the same
 *   framing (px_per_cm, grid) and at most 0.05 % of pixels more than 4
 *   levels apart, mean difference under 0.02 levels (float rounding may
 *   move a few edge pixels; lavapipe gives 0; the sheared box's normals
 *   through mat3(model) instead of the inverse transpose give 0.43 % and
 *   0.14);
 * - the scene written as PLY + JSON and read back: the same parts,
 *   instances and pixels;
 * - bad scenes refused (a part outside the mesh, a face of another part's
 *   vertices, an instance of a missing part, a singular or non-affine or
 *   non-finite matrix, a file of another format, a bad colour, colouring by
 *   a property). */
#define _DEFAULT_SOURCE /* M_PI, mkdtemp */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "render_shapes.h"
#include "sessile/io/io.h"
#include "sessile/render/render_scene.h"
#include "testutil.h"

enum { P_SEABED, P_SPHERE, P_CUBE, NPARTS };
static const unsigned char RED[3] = {255, 0, 0}, BLUE[3] = {0, 0, 255}, GREEN[3] = {60, 160, 60};
static const double R1 = 2.0, R2 = 1.5; /* the spheres' radii (unit sphere scaled) */

/* The parts in one surface: a 20 x 20 cm quad at z = 0, a unit icosphere, a unit cube. */
static void parts_surface(sessile_surface *s, sessile_render_part parts[NPARTS]) {
  double *sp;
  uint32_t *st, snv;
  uint32_t snf = shape_icosphere(4, 1.0, &sp, &st, &snv);
  double cp[72];
  uint32_t ct[36];
  shape_cube(0.0, 1.0, cp, ct);
  const double qp[12] = {0, 0, 0, 20, 0, 0, 20, 20, 0, 0, 20, 0};
  const uint32_t qt[6] = {0, 1, 2, 0, 2, 3};
  const double *pos[NPARTS] = {qp, sp, cp};
  const uint32_t *tri[NPARTS] = {qt, st, ct}, nv[NPARTS] = {4, snv, 24}, nf[NPARTS] = {2, snf, 12};
  memset(s, 0, sizeof *s);
  t_must("reserve", sessile_surface_reserve(s, 4 + snv + 24, 2 + snf + 12));
  for (int p = 0; p < NPARTS; p++) {
    parts[p] = (sessile_render_part){s->nv, nv[p], s->nf, nf[p]};
    memcpy(s->pos + 3 * (size_t)s->nv, pos[p], 3 * (size_t)nv[p] * sizeof(double));
    for (uint32_t i = 0; i < 3 * nf[p]; i++) s->tri[3 * (size_t)s->nf + i] = tri[p][i] + s->nv;
    s->nv += nv[p], s->nf += nf[p];
  }
  free(sp);
  free(st);
}

/* translate(t) . Rz(deg) . scale(sx, sy, sz), column-major. */
static void trs(double m[16], double tx, double ty, double tz, double deg, double sx, double sy, double sz) {
  double c = cos(deg * M_PI / 180), s = sin(deg * M_PI / 180);
  const double v[16] = {c * sx, s * sx, 0, 0, -s * sy, c * sy, 0, 0, 0, 0, sz, 0, tx, ty, tz, 1};
  memcpy(m, v, sizeof v);
}

static void instance(sessile_render_instance *in, uint32_t part, const unsigned char rgb[3]) {
  in->part = part;
  memcpy(in->rgba, rgb, 3);
  in->rgba[3] = 255;
}

/* The seabed, red spheres at (5, 5) and (15, 6), a blue box at (10, 14). */
static sessile_render_scene *make_scene(sessile_surface *surf) {
  sessile_render_scene *s = t_xalloc(sizeof *s);
  memset(s, 0, sizeof *s);
  s->parts = t_xalloc(NPARTS * sizeof *s->parts);
  s->nparts = NPARTS;
  parts_surface(surf, s->parts);
  t_must("scene mesh", sessile_render_mesh_from_arrays(surf->pos, surf->nv, surf->tri, surf->nf, &s->mesh));
  s->ninst = 4;
  s->inst = t_xalloc(4 * sizeof *s->inst);
  memset(s->inst, 0, 4 * sizeof *s->inst);
  instance(&s->inst[0], P_SEABED, GREEN);
  trs(s->inst[0].matrix, 0, 0, 0, 0, 1, 1, 1);
  instance(&s->inst[1], P_SPHERE, RED);
  trs(s->inst[1].matrix, 5, 5, R1, 0, R1, R1, R1);
  instance(&s->inst[2], P_CUBE, BLUE);
  trs(s->inst[2].matrix, 10, 14, 0, 30, 3, 2, 1.5);
  s->inst[2].matrix[8] = 1.2; /* a shear (x += 1.2 z): normals need the inverse transpose */
  instance(&s->inst[3], P_SPHERE, RED);
  trs(s->inst[3].matrix, 15, 6, R2, 70, R2, R2, R2);
  return s;
}

static unsigned char *draw(sessile_gpu *g, const sessile_render_scene *sc, const sessile_render_mesh *m,
                           const sessile_render_options *o, sessile_render_result *res) {
  sessile_mesh_renderer *r = NULL;
  unsigned char *px = t_xalloc((size_t)o->width * o->height * 4);
  t_must("renderer", m ? sessile_mesh_renderer_create(g, m, o, &r, NULL) : sessile_scene_renderer_create(g, sc, o, &r, NULL));
  t_must("draw", sessile_mesh_renderer_draw(r, 0, px, res));
  sessile_mesh_renderer_destroy(r);
  return px;
}

static void top_options(sessile_render_options *o) {
  sessile_render_options_default(o);
  o->width = o->height = 320;
  o->samples = 1;
  o->view = "top";
  o->ortho = 1;
  o->grid = 0;
  o->background[0] = o->background[1] = o->background[2] = 0;
}

static const unsigned char *pixel_at(const unsigned char *px, const sessile_render_result *res, uint32_t w,
                                     uint32_t h, double x, double y, double z) {
  double p[3] = {x, y, z}, u, v;
  project(res->clip_from_world, p, w, h, &u, &v);
  return px + 4 * ((size_t)(int)v * w + (size_t)(int)u);
}

static int is_red(const unsigned char *c) { return c[0] > 100 && c[1] < 20 && c[2] < 20; }
/* Red at any shade (ambient alone gives 0.15 x 255 = 38), on green or black. */
static int red_ink(const unsigned char *c) { return c[0] >= 30 && c[1] < 20 && c[2] < 20; }
static int is_blue(const unsigned char *c) { return c[2] > 100 && c[0] < 20 && c[1] < 20; }
static int is_green(const unsigned char *c) { return c[1] > c[0] + 40 && c[1] > c[2] + 40; }

static void test_colours(sessile_gpu *g, const sessile_render_scene *sc) {
  sessile_render_options o;
  top_options(&o);
  sessile_render_result res;
  unsigned char *px = draw(g, sc, NULL, &o, &res);
  const unsigned char *a = pixel_at(px, &res, o.width, o.height, 5, 5, 2 * R1);
  const unsigned char *b = pixel_at(px, &res, o.width, o.height, 15, 6, 2 * R2);
  const double *bm = sc->inst[2].matrix; /* the box's top centre: local (0.5, 0.5, 1) */
  const unsigned char *c = pixel_at(px, &res, o.width, o.height, 0.5 * bm[0] + 0.5 * bm[4] + bm[8] + bm[12],
                                    0.5 * bm[1] + 0.5 * bm[5] + bm[9] + bm[13], bm[10] + bm[14]);
  const unsigned char *d = pixel_at(px, &res, o.width, o.height, 18, 18, 0);
  printf("top: sphere 1 (%u %u %u), sphere 2 (%u %u %u), box (%u %u %u), seabed (%u %u %u)\n", a[0], a[1], a[2],
         b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]);
  t_true("the first sphere's centre is red", is_red(a));
  t_true("the second instance of the sphere is red too", is_red(b));
  t_true("the box's centre is blue", is_blue(c));
  t_true("the seabed is green", is_green(d));
  long red = 0, blue = 0;
  for (size_t i = 0; i < (size_t)o.width * o.height; i++) red += red_ink(px + 4 * i), blue += is_blue(px + 4 * i);
  double expect = M_PI * (R1 * R1 + R2 * R2) * res.px_per_cm * res.px_per_cm;
  printf("red pixels %ld, two discs %.1f; blue pixels %ld\n", red, expect, blue);
  t_check("red area = the two spheres' discs within 5 %", fabs(red - expect) / expect, 0.05);
  t_true("the box is drawn blue", blue > 100);
  const unsigned char black[3] = {0, 0, 0};
  t_true("the seabed fills most of the top view", count_not_bg(px, o.width, o.height, black) > (long)o.width * o.height / 2);
  free(px);
}

/* The instances' vertices transformed on the host, in one mesh. */
static sessile_render_mesh *merged(const sessile_render_scene *sc) {
  uint32_t nv = 0, nf = 0;
  for (uint32_t i = 0; i < sc->ninst; i++) nv += sc->parts[sc->inst[i].part].nv, nf += sc->parts[sc->inst[i].part].nf;
  double *pos = t_dalloc(3 * (size_t)nv);
  uint32_t *tri = t_xalloc(3 * (size_t)nf * sizeof *tri), at = 0, ft = 0;
  for (uint32_t i = 0; i < sc->ninst; i++) {
    const sessile_render_part *p = &sc->parts[sc->inst[i].part];
    const double *m = sc->inst[i].matrix;
    for (uint32_t v = 0; v < p->nv; v++) {
      const float *q = sc->mesh->pos + 3 * (size_t)(p->first_vertex + v);
      for (int k = 0; k < 3; k++)
        pos[3 * (size_t)(at + v) + k] = m[k] * q[0] + m[4 + k] * q[1] + m[8 + k] * q[2] + m[12 + k];
    }
    for (uint32_t f = 0; f < 3 * p->nf; f++) tri[3 * (size_t)ft + f] = sc->mesh->tri[3 * (size_t)p->first_face + f] - p->first_vertex + at;
    at += p->nv, ft += p->nf;
  }
  sessile_render_mesh *m = NULL;
  t_must("merged mesh", sessile_render_mesh_from_arrays(pos, nv, tri, nf, &m));
  free(pos);
  free(tri);
  return m;
}

static void test_instanced_equals_merged(sessile_gpu *g, sessile_render_scene *sc) {
  const unsigned char base[3] = SESSILE_RENDER_BASE_COLOR;
  unsigned char keep[4][4];
  for (uint32_t i = 0; i < sc->ninst; i++) memcpy(keep[i], sc->inst[i].rgba, 4), memcpy(sc->inst[i].rgba, base, 3);
  sessile_render_mesh *m = merged(sc);
  sessile_render_options o;
  sessile_render_options_default(&o);
  o.width = 400, o.height = 300;
  sessile_render_result ra, rb;
  unsigned char *a = draw(g, sc, NULL, &o, &ra), *b = draw(g, NULL, m, &o, &rb);
  long far = 0;
  double sum = 0;
  for (size_t i = 0; i < (size_t)o.width * o.height; i++) {
    int worst = 0;
    for (int k = 0; k < 3; k++) {
      int d = abs(a[4 * i + k] - b[4 * i + k]);
      worst = d > worst ? d : worst;
      sum += d;
    }
    far += worst > 4;
  }
  double n = (double)o.width * o.height, mean = sum / (3 * n);
  printf("instanced vs merged: %ld pixels more than 4 levels apart (%.3f %%), mean difference %.4f levels\n", far,
         100 * far / n, mean);
  t_check("the same framing (px per cm)", fabs(ra.px_per_cm - rb.px_per_cm) / rb.px_per_cm, 1e-5);
  t_check("the same grid spacing", fabs(ra.grid_spacing_cm - rb.grid_spacing_cm), 0);
  t_check("instanced = merged: pixels more than 4 levels apart (fraction)", far / n, 0.0005);
  t_check("instanced = merged: mean difference (levels)", mean, 0.02);
  free(a);
  free(b);
  sessile_render_mesh_destroy(m);
  for (uint32_t i = 0; i < sc->ninst; i++) memcpy(sc->inst[i].rgba, keep[i], 4);
}

static char T[512];
static const char *P(const char *name) {
  static char buf[4][600];
  static int k;
  k = (k + 1) & 3;
  snprintf(buf[k], sizeof buf[k], "%s/%s", T, name);
  return buf[k];
}

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  t_true("write a test file", f && fputs(text, f) >= 0);
  if (f) fclose(f);
}

static void test_file(sessile_gpu *g, const sessile_render_scene *sc, const sessile_surface *surf) {
  t_must("parts PLY", sessile_write_ply(P("parts.ply"), surf, NULL, 0, NULL, NULL));
  cJSON *j = sessile_render_scene_json("parts.ply", sc->parts, sc->nparts, sc->inst, sc->ninst);
  char *text = j ? cJSON_Print(j) : NULL;
  t_true("scene JSON", text != NULL);
  write_text(P("scene.json"), text ? text : "");
  free(text);
  cJSON_Delete(j);
  sessile_render_scene *back = NULL;
  t_must("read the scene file", sessile_render_scene_read(P("scene.json"), &back));
  int same = back && back->nparts == sc->nparts && back->ninst == sc->ninst &&
             !memcmp(back->parts, sc->parts, sc->nparts * sizeof *sc->parts) && back->mesh->nv == sc->mesh->nv;
  for (uint32_t i = 0; same && i < sc->ninst; i++)
    same = back->inst[i].part == sc->inst[i].part && !memcmp(back->inst[i].rgba, sc->inst[i].rgba, 4) &&
           !memcmp(back->inst[i].matrix, sc->inst[i].matrix, sizeof sc->inst[i].matrix);
  t_true("the file holds the same parts, instances, colours and matrices (exactly)", same);
  sessile_render_options o;
  top_options(&o);
  unsigned char *a = draw(g, sc, NULL, &o, NULL), *b = back ? draw(g, back, NULL, &o, NULL) : NULL;
  t_true("... and draws the same pixels", b && !memcmp(a, b, (size_t)o.width * o.height * 4));
  free(a);
  free(b);
  sessile_render_scene_destroy(back);
  /* bad files: each refused as usage with a line naming the file */
  static const struct { const char *name, *text, *needle; } bad[] = {
      {"fmt.json", "{\"format\": \"other\", \"version\": 1}", "not a scene file"},
      {"nomesh.json", "{\"format\": \"sessile render scene\", \"version\": 1, \"mesh\": \"missing.ply\","
                      " \"parts\": [[0, 4, 0, 2]], \"instances\": [{\"part\": 0, \"rgb\": [1, 2, 3],"
                      " \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]}", "missing.ply"},
      {"rgb.json", "{\"format\": \"sessile render scene\", \"version\": 1, \"mesh\": \"parts.ply\","
                   " \"parts\": [[0, 4, 0, 2]], \"instances\": [{\"part\": 0, \"rgb\": [1, 256, 3],"
                   " \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]}", "instances[0]"},
      {"part.json", "{\"format\": \"sessile render scene\", \"version\": 1, \"mesh\": \"parts.ply\","
                    " \"parts\": [[0, 4, 0, 2]], \"instances\": [{\"part\": 1, \"rgb\": [1, 2, 3],"
                    " \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]}", "names part 1"},
      {"text.json", "not json", "not JSON"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
    write_text(P(bad[k].name), bad[k].text);
    sessile_render_scene *s = NULL;
    sessile_status st = sessile_render_scene_read(P(bad[k].name), &s);
    char what[128];
    snprintf(what, sizeof what, "%s refused: '%s'", bad[k].name, bad[k].needle);
    /* the missing mesh's message names the mesh, the others the scene file */
    t_true(what, st == SESSILE_ERR_USAGE && !s && strstr(sessile_error_message(), bad[k].needle) &&
                     (k == 1 || strstr(sessile_error_message(), bad[k].name)));
    unlink(P(bad[k].name));
  }
  unlink(P("scene.json"));
  unlink(P("parts.ply"));
}

static void refused(const char *what, const sessile_render_scene *s, const char *needle) {
  sessile_status st = sessile_render_scene_check("scene", s);
  char line[160];
  snprintf(line, sizeof line, "refused: %s", what);
  t_true(line, st == SESSILE_ERR_USAGE && strstr(sessile_error_message(), needle));
}

static void test_refusals(sessile_gpu *g, sessile_render_scene *sc) {
  t_ok("the test scene passes the check", sessile_render_scene_check("scene", sc));
  sessile_render_part keep = sc->parts[P_CUBE];
  sc->parts[P_CUBE].nv += 1;
  refused("a part past the mesh's vertices", sc, "outside the mesh");
  sc->parts[P_CUBE] = keep;
  sc->parts[P_CUBE].first_vertex -= 1; /* the sphere's last vertex: the cube's faces are outside */
  sc->parts[P_CUBE].nv = 1;
  refused("a face using another part's vertices", sc, "not one of the part's");
  sc->parts[P_CUBE] = keep;
  sc->inst[2].part = NPARTS;
  refused("an instance of a missing part", sc, "names part 3");
  sc->inst[2].part = P_CUBE;
  double m[16];
  memcpy(m, sc->inst[2].matrix, sizeof m);
  sc->inst[2].matrix[10] = 0;
  refused("a singular matrix", sc, "instance 2's matrix");
  memcpy(sc->inst[2].matrix, m, sizeof m);
  sc->inst[2].matrix[3] = 0.5;
  refused("a projective matrix", sc, "instance 2's matrix");
  memcpy(sc->inst[2].matrix, m, sizeof m);
  sc->inst[2].matrix[13] = NAN;
  refused("a non-finite matrix", sc, "instance 2's matrix");
  memcpy(sc->inst[2].matrix, m, sizeof m);
  t_ok("restored", sessile_render_scene_check("scene", sc));
  sessile_render_options o;
  top_options(&o);
  o.color_by = "x";
  sessile_mesh_renderer *r = NULL;
  t_true("colouring a scene by a property is refused",
         sessile_scene_renderer_create(g, sc, &o, &r, NULL) == SESSILE_ERR_USAGE && !r);
}

static void test_srgb(void) {
  t_true("sRGB bytes: 0 -> 0, 1 -> 255, 0.5 -> 188, 0.0031308 -> 10", sessile_render_srgb_byte(0) == 0 &&
         sessile_render_srgb_byte(1) == 255 && sessile_render_srgb_byte(0.5) == 188 &&
         sessile_render_srgb_byte(0.0031308) == 10 && sessile_render_srgb_byte(2) == 255);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  snprintf(T, sizeof T, "%s/sessile_test_scene.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(T)) {
    printf("FAIL cannot create a scratch folder: %s\n", strerror(errno));
    return 1;
  }
  sessile_surface surf;
  sessile_render_scene *sc = make_scene(&surf);
  test_srgb();
  test_colours(g, sc);
  test_instanced_equals_merged(g, sc);
  test_file(g, sc, &surf);
  test_refusals(g, sc);
  sessile_render_scene_destroy(sc);
  sessile_surface_free(&surf);
  rmdir(T);
  return t_finish(g);
}
