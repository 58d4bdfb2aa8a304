/* The mesh renderer: vertices (position in cm, normal, colour) and 32-bit
 * indices uploaded once; a target and two pipelines (lit triangles, unlit
 * grid lines) made once; each frame fits the camera and draws. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/gpu/graphics.h"
#include "mesh_internal.h"
#include "sessile/io/colormap.h"

/* One vertex as the pipelines read it (28 bytes). */
typedef struct vtx {
  float p[3], n[3];
  unsigned char c[4];
} vtx;
_Static_assert(sizeof(vtx) == 28, "vertex layout");

/* shaders/render/mesh_push.glsl */
typedef struct mesh_push {
  float mvp[16];
  float key[4], fill[4], eye[4], params[4];
} mesh_push;
_Static_assert(sizeof(mesh_push) == 128, "push layout");

struct sessile_mesh_renderer {
  sessile_gpu *gpu;
  sessile_gfx_target *target;
  sessile_gfx_pipeline *tris, *lines;
  sessile_gfx_buffer *vbuf, *ibuf, *gbuf;
  uint32_t nindex, ngrid;
  float *fit;    /* the vertices (cm) and then the grid's 4 corners: what the camera frames */
  size_t nfit;
  sessile_render_options o;
  char view[16];
  double lo[3], hi[3];     /* mesh bounds, cm */
  double glo[3], ghi[3];   /* grid box, cm */
  double spacing;
  double prop_min, prop_max;
  char colormap[16]; /* the map used, "" without colouring */
};

void sessile_render_options_default(sessile_render_options *o) {
  memset(o, 0, sizeof *o);
  o->width = 1280;
  o->height = 960;
  o->samples = 4;
  o->view = "oblique";
  o->background[0] = o->background[1] = o->background[2] = o->background[3] = 255;
  o->grid = 1;
  o->units_cm = 1.0;
}

sessile_status sessile_render_options_check(const sessile_render_options *o,
                                            const sessile_render_mesh *m) {
  SESSILE_CHECK(o->width >= 1 && o->width <= 16384 && o->height >= 1 && o->height <= 16384,
                SESSILE_ERR_USAGE, "size %ux%u is out of range (1..16384 pixels per side)", o->width,
                o->height);
  SESSILE_CHECK(o->samples == 1 || o->samples == 2 || o->samples == 4 || o->samples == 8,
                SESSILE_ERR_USAGE, "samples %u: use 1, 4 or 8", o->samples);
  double az, el;
  SESSILE_CHECK(render_view_angles_(o->view, &az, &el), SESSILE_ERR_USAGE,
                "unknown view '%s' (views: %s)", o->view ? o->view : "(null)",
                sessile_render_view_names());
  SESSILE_CHECK(isfinite(o->units_cm) && o->units_cm > 0 && o->units_cm <= 1e6, SESSILE_ERR_USAGE,
                "units %g: give the cm per mesh unit, in (0, 1e6]", o->units_cm);
  SESSILE_CHECK(!o->colormap || sessile_colormap_known(o->colormap), SESSILE_ERR_USAGE,
                "unknown colour map '%s' (maps: %s)", o->colormap, sessile_colormap_names());
  if (o->color_by && m && !sessile_render_mesh_property(m, o->color_by)) {
    char names[512] = "";
    size_t at = 0;
    for (int i = 0; i < m->nprops && at < sizeof names - 1; i++)
      at += (size_t)snprintf(names + at, sizeof names - at, "%s%s", i ? ", " : "", m->prop_names[i]);
    return sessile_error_set(SESSILE_ERR_USAGE, "the mesh has no per-vertex property '%s' (it has: %s)",
                             o->color_by, m->nprops ? names : "none");
  }
  return SESSILE_OK;
}

uint64_t sessile_render_bytes(const sessile_render_mesh *m, const sessile_render_options *o) {
  return (uint64_t)m->nv * sizeof(vtx) + (uint64_t)m->nf * 12u +
         sessile_gfx_target_bytes(o->width, o->height, o->samples);
}

/* Colours from the property through the map; the range is the finite
 * values' (symmetric about 0 for a diverging map on a range across 0). */
static void color_vertices(sessile_mesh_renderer *r, const sessile_render_mesh *m, vtx *v) {
  const unsigned char base[3] = SESSILE_RENDER_BASE_COLOR;
  const float *prop = r->o.color_by ? sessile_render_mesh_property(m, r->o.color_by) : NULL;
  if (!prop) {
    for (uint32_t i = 0; i < m->nv; i++) {
      memcpy(v[i].c, base, 3);
      v[i].c[3] = 255;
    }
    return;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (uint32_t i = 0; i < m->nv; i++)
    if (isfinite(prop[i])) {
      lo = fmin(lo, prop[i]);
      hi = fmax(hi, prop[i]);
    }
  if (!(lo <= hi)) lo = hi = 0;
  int across = lo < 0 && hi > 0;
  const char *map = r->o.colormap ? r->o.colormap : (across ? "coolwarm" : "viridis");
  if (sessile_colormap_diverging(map) && across) {
    double a = fmax(-lo, hi);
    lo = -a;
    hi = a;
  }
  r->prop_min = lo;
  r->prop_max = hi;
  snprintf(r->colormap, sizeof r->colormap, "%s", map);
  for (uint32_t i = 0; i < m->nv; i++) {
    if (!isfinite(prop[i])) {
      v[i].c[0] = v[i].c[1] = v[i].c[2] = 128;
    } else {
      double t = hi > lo ? (prop[i] - lo) / (hi - lo) : 0.5;
      sessile_colormap(map, t, v[i].c);
    }
    v[i].c[3] = 255;
  }
}

/* Grid lines on the plane just below the mesh: spacing 1-2-5 x 10^k cm for
 * about ten lines over the larger horizontal side, extended past the mesh
 * by 10 % of that side and snapped to whole spacings; the border darker. */
static sessile_status grid_build(sessile_mesh_renderer *r) {
  double span = fmax(r->hi[0] - r->lo[0], r->hi[1] - r->lo[1]);
  if (!(span > 0)) span = fmax(r->hi[2] - r->lo[2], 1e-6);
  double s = render_grid_spacing_(span);
  r->spacing = s;
  for (int k = 0; k < 2; k++) {
    r->glo[k] = floor((r->lo[k] - 0.10 * span) / s) * s;
    r->ghi[k] = ceil((r->hi[k] + 0.10 * span) / s) * s;
  }
  r->glo[2] = r->ghi[2] = r->lo[2] - 1e-4 * span;
  float *corner = r->fit + 3 * (r->nfit - 4);
  for (int i = 0; i < 4; i++) {
    corner[3 * i] = (float)(i & 1 ? r->ghi[0] : r->glo[0]);
    corner[3 * i + 1] = (float)(i & 2 ? r->ghi[1] : r->glo[1]);
    corner[3 * i + 2] = (float)r->glo[2];
  }
  if (!r->o.grid) return SESSILE_OK;
  uint32_t nx = (uint32_t)llround((r->ghi[0] - r->glo[0]) / s) + 1;
  uint32_t ny = (uint32_t)llround((r->ghi[1] - r->glo[1]) / s) + 1;
  r->ngrid = 2 * (nx + ny);
  vtx *g = calloc(r->ngrid, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint32_t at = 0;
  for (uint32_t i = 0; i < nx + ny; i++) {
    int along_y = i < nx; /* a line of constant x */
    uint32_t j = along_y ? i : i - nx;
    uint32_t last = along_y ? nx - 1 : ny - 1;
    double c = (along_y ? r->glo[0] : r->glo[1]) + j * s;
    unsigned char shade = (j == 0 || j == last) ? 110 : 175;
    for (int e = 0; e < 2; e++) {
      vtx *v = &g[at++];
      v->p[0] = (float)(along_y ? c : (e ? r->ghi[0] : r->glo[0]));
      v->p[1] = (float)(along_y ? (e ? r->ghi[1] : r->glo[1]) : c);
      v->p[2] = (float)r->glo[2];
      v->c[0] = v->c[1] = v->c[2] = shade;
      v->c[3] = 255;
    }
  }
  sessile_status st = sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_VERTEX, g, r->ngrid * sizeof *g,
                                                &r->gbuf);
  free(g);
  return st;
}

static sessile_status upload_mesh(sessile_mesh_renderer *r, const sessile_render_mesh *m) {
  vtx *v = malloc((size_t)m->nv * sizeof *v);
  SESSILE_CHECK(v, SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", m->nv);
  r->nfit = (size_t)m->nv + 4;
  r->fit = malloc(r->nfit * 3 * sizeof(float));
  if (!r->fit) {
    free(v);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", m->nv);
  }
  double u = r->o.units_cm;
  for (uint32_t i = 0; i < m->nv; i++)
    for (int k = 0; k < 3; k++) {
      v[i].p[k] = (float)(m->pos[3 * i + k] * u);
      v[i].n[k] = m->normal[3 * i + k];
      r->fit[3 * (size_t)i + k] = v[i].p[k];
    }
  color_vertices(r, m, v);
  sessile_status s = sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_VERTEX, v, (size_t)m->nv * sizeof *v,
                                               &r->vbuf);
  free(v);
  SESSILE_CALL(s);
  r->nindex = 3 * m->nf;
  return sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_INDEX, m->tri, (size_t)r->nindex * 4, &r->ibuf);
}

static sessile_status renderer_init(sessile_mesh_renderer *r, const sessile_render_mesh *m,
                                    double *t_upload) {
  const sessile_gpu_info *info = sessile_gpu_info_of(r->gpu);
  uint64_t need = sessile_render_bytes(m, &r->o);
  SESSILE_CHECK(info->device_local_bytes == 0 || need <= info->device_local_bytes, SESSILE_ERR_TOO_LARGE,
                "rendering %u vertices, %u triangles at %ux%u with %u samples needs about %.1f MiB "
                "of device memory, but '%s' has %.1f MiB: use a smaller size or fewer samples",
                m->nv, m->nf, r->o.width, r->o.height, r->o.samples, (double)need / 1048576.0,
                info->name, (double)info->device_local_bytes / 1048576.0);
  mesh_bounds_(m, r->lo, r->hi);
  for (int k = 0; k < 3; k++) {
    r->lo[k] *= r->o.units_cm;
    r->hi[k] *= r->o.units_cm;
  }
  SESSILE_CALL(sessile_gfx_target_create(r->gpu, r->o.width, r->o.height, r->o.samples, &r->target));
  sessile_gfx_pipeline_desc d = {.vert = "render/mesh.vert",
                                 .frag = "render/mesh.frag",
                                 .stride = sizeof(vtx),
                                 .nattr = 3,
                                 .attr = {{SESSILE_GFX_FLOAT3, 0}, {SESSILE_GFX_FLOAT3, 12},
                                          {SESSILE_GFX_UNORM8X4, 24}},
                                 .topology = SESSILE_GFX_TRIANGLES,
                                 .push_bytes = sizeof(mesh_push)};
  SESSILE_CALL(sessile_gfx_pipeline_create(r->target, &d, &r->tris));
  d.topology = SESSILE_GFX_LINES;
  SESSILE_CALL(sessile_gfx_pipeline_create(r->target, &d, &r->lines));
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(upload_mesh(r, m));
  SESSILE_CALL(grid_build(r));
  if (t_upload) *t_upload = sessile_wall_seconds() - t0;
  return SESSILE_OK;
}

sessile_status sessile_mesh_renderer_create(sessile_gpu *g, const sessile_render_mesh *m,
                                            const sessile_render_options *o,
                                            sessile_mesh_renderer **out, double *t_upload) {
  *out = NULL;
  SESSILE_CALL(sessile_render_options_check(o, m));
  sessile_mesh_renderer *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->gpu = g;
  r->o = *o;
  snprintf(r->view, sizeof r->view, "%s", o->view);
  r->o.view = r->view;
  sessile_status s = renderer_init(r, m, t_upload);
  r->o.color_by = NULL; /* the caller's strings: used while uploading, not kept */
  r->o.colormap = NULL;
  if (s != SESSILE_OK) {
    sessile_mesh_renderer_destroy(r);
    return s;
  }
  *out = r;
  return SESSILE_OK;
}

void sessile_mesh_renderer_destroy(sessile_mesh_renderer *r) {
  if (!r) return;
  sessile_gfx_buffer_destroy(r->gbuf);
  sessile_gfx_buffer_destroy(r->ibuf);
  sessile_gfx_buffer_destroy(r->vbuf);
  sessile_gfx_pipeline_destroy(r->lines);
  sessile_gfx_pipeline_destroy(r->tris);
  sessile_gfx_target_destroy(r->target);
  free(r->fit);
  free(r);
}

/* Camera-space direction (x right, y up, z toward the viewer) to world. */
static void to_world(const render_camera *c, const double cam[3], float out[4], double weight) {
  double w[3];
  double l = sqrt(cam[0] * cam[0] + cam[1] * cam[1] + cam[2] * cam[2]);
  for (int k = 0; k < 3; k++) w[k] = (cam[0] * c->right[k] + cam[1] * c->up[k] + cam[2] * c->toward[k]) / l;
  for (int k = 0; k < 3; k++) out[k] = (float)w[k];
  out[3] = (float)weight;
}

sessile_status sessile_mesh_renderer_draw(sessile_mesh_renderer *r, double azimuth_deg,
                                          unsigned char *rgba, sessile_render_result *res) {
  render_camera cam;
  /* With the grid, the camera frames the grid too (its corners are the
   * last 4 fit points): the mesh stands on a whole floor. */
  double flo[3], fhi[3];
  for (int k = 0; k < 3; k++) {
    flo[k] = fmin(r->lo[k], r->glo[k]);
    fhi[k] = fmax(r->hi[k], r->ghi[k]);
  }
  render_camera_fit_(r->view, azimuth_deg, r->o.ortho, r->o.width, r->o.height, r->fit,
                     r->nfit - (r->o.grid ? 0 : 4), flo, fhi, &cam);
  mesh_push p;
  memset(&p, 0, sizeof p);
  for (int i = 0; i < 16; i++) p.mvp[i] = (float)cam.clip_from_world[i];
  const double key[3] = SESSILE_RENDER_KEY_DIR, fill[3] = SESSILE_RENDER_FILL_DIR;
  to_world(&cam, key, p.key, SESSILE_RENDER_KEY_W);
  to_world(&cam, fill, p.fill, SESSILE_RENDER_FILL_W);
  for (int k = 0; k < 3; k++) p.eye[k] = (float)(cam.ortho ? cam.toward[k] : cam.eye[k]);
  p.eye[3] = cam.ortho ? 0.0f : 1.0f;
  p.params[0] = (float)SESSILE_RENDER_AMBIENT;
  p.params[1] = 1.0f;
  mesh_push pg = p;
  pg.params[1] = 0.0f;
  sessile_gfx_draw d[2] = {{r->tris, r->vbuf, r->ibuf, r->nindex, &p},
                           {r->lines, r->gbuf, NULL, r->ngrid, &pg}};
  float clear[4];
  for (int k = 0; k < 4; k++) clear[k] = (float)r->o.background[k] / 255.0f;
  double td = 0, tr = 0;
  SESSILE_CALL(sessile_gfx_render(r->target, clear, d, r->o.grid ? 2u : 1u, rgba, &td, &tr));
  if (res) {
    memset(res, 0, sizeof *res);
    res->grid_spacing_cm = r->o.grid ? r->spacing : 0;
    res->grid_min[0] = r->glo[0];
    res->grid_min[1] = r->glo[1];
    res->grid_max[0] = r->ghi[0];
    res->grid_max[1] = r->ghi[1];
    res->grid_z = r->glo[2];
    res->px_per_cm = cam.px_per_cm;
    memcpy(res->clip_from_world, cam.clip_from_world, sizeof res->clip_from_world);
    res->prop_min = r->prop_min;
    res->prop_max = r->prop_max;
    snprintf(res->colormap, sizeof res->colormap, "%s", r->colormap);
    res->t_draw = td;
    res->t_readback = tr;
  }
  return SESSILE_OK;
}
