/* The scene renderer (render_scene.h): the parts' vertices and 32-bit
 * indices uploaded once, the instances grouped by part in one instance
 * buffer, one instanced draw per part; the camera, the grid and the draw
 * are the mesh renderer's (mesh_render.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh_internal.h"
#include "sessile/render/render_scene.h"

/* Every instance's vertices in cm (what the camera frames, as the merged
 * mesh's vertices would be) and their bounds. */
static sessile_status fit_points(sessile_mesh_renderer *r, const sessile_render_scene *s) {
  uint64_t n = 0;
  for (uint32_t i = 0; i < s->ninst; i++) n += s->parts[s->inst[i].part].nv;
  SESSILE_CHECK(n < UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE,
                "the scene's %u instances have %llu vertices in all: too many to frame", s->ninst,
                (unsigned long long)n);
  r->nfit = (size_t)n + 4;
  r->fit = malloc(r->nfit * 3 * sizeof(float));
  SESSILE_CHECK(r->fit, SESSILE_ERR_NO_MEMORY, "out of host memory for %llu vertices", (unsigned long long)n);
  for (int k = 0; k < 3; k++) r->lo[k] = INFINITY, r->hi[k] = -INFINITY;
  float *q = r->fit;
  const double u = r->o.units_cm;
  for (uint32_t i = 0; i < s->ninst; i++) {
    const sessile_render_part *pt = &s->parts[s->inst[i].part];
    const double *m = s->inst[i].matrix;
    for (uint32_t v = pt->first_vertex; v < pt->first_vertex + pt->nv; v++, q += 3) {
      const float *p = s->mesh->pos + 3 * (size_t)v;
      for (int k = 0; k < 3; k++) {
        q[k] = (float)(u * (m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k]));
        r->lo[k] = fmin(r->lo[k], q[k]);
        r->hi[k] = fmax(r->hi[k], q[k]);
      }
    }
  }
  return SESSILE_OK;
}

/* The instances grouped by part (a counting sort: the file's order within
 * a part), each with its transform to cm; one group per part drawn. */
static sessile_status upload_instances(sessile_mesh_renderer *r, const sessile_render_scene *s) {
  uint32_t *start = calloc((size_t)s->nparts + 1, sizeof *start);
  render_inst *in = malloc((size_t)s->ninst * sizeof *in);
  r->groups = calloc(s->nparts, sizeof *r->groups);
  sessile_status st = SESSILE_OK;
  if (!start || !in || !r->groups) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t i = 0; st == SESSILE_OK && i < s->ninst; i++) start[s->inst[i].part + 1]++;
  for (uint32_t p = 0; st == SESSILE_OK && p < s->nparts; p++) {
    if (start[p + 1])
      r->groups[r->ngroups++] = (render_group){3 * s->parts[p].first_face, 3 * s->parts[p].nf, start[p], start[p + 1]};
    start[p + 1] += start[p];
  }
  for (uint32_t i = 0; st == SESSILE_OK && i < s->ninst; i++) {
    const sessile_render_instance *a = &s->inst[i];
    render_inst *b = &in[start[a->part]++];
    for (int c = 0; c < 16; c++) b->m[c] = (float)(a->matrix[c] * ((c & 3) < 3 ? r->o.units_cm : 1.0));
    memcpy(b->c, a->rgba, 3);
    b->c[3] = 255;
  }
  if (st == SESSILE_OK)
    st = sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_VERTEX, in, (size_t)s->ninst * sizeof *in, &r->instbuf);
  free(in);
  free(start);
  return st;
}

static sessile_status upload_parts(sessile_mesh_renderer *r, const sessile_render_mesh *m) {
  vtx *v = calloc(m->nv, sizeof *v);
  SESSILE_CHECK(v, SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", m->nv);
  for (uint32_t i = 0; i < m->nv; i++)
    for (int k = 0; k < 3; k++) v[i].p[k] = m->pos[3 * i + k], v[i].n[k] = m->normal[3 * i + k];
  sessile_status s = sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_VERTEX, v, (size_t)m->nv * sizeof *v, &r->vbuf);
  free(v);
  SESSILE_CALL(s);
  return sessile_gfx_buffer_create(r->gpu, SESSILE_GFX_INDEX, m->tri, (size_t)m->nf * 12u, &r->ibuf);
}

static sessile_status scene_init(sessile_mesh_renderer *r, const sessile_render_scene *s, double *t_upload) {
  SESSILE_CALL(fit_points(r, s));
  uint64_t need = sessile_render_bytes(s->mesh, &r->o) + (uint64_t)s->ninst * sizeof(render_inst);
  SESSILE_CALL(render_target_make_(r, need, s->mesh->nv, s->mesh->nf, 1));
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(upload_parts(r, s->mesh));
  SESSILE_CALL(upload_instances(r, s));
  SESSILE_CALL(render_grid_build_(r));
  if (t_upload) *t_upload = sessile_wall_seconds() - t0;
  return SESSILE_OK;
}

sessile_status sessile_scene_renderer_create(sessile_gpu *g, const sessile_render_scene *s,
                                             const sessile_render_options *o, sessile_mesh_renderer **out,
                                             double *t_upload) {
  *out = NULL;
  SESSILE_CALL(sessile_render_options_check(o, NULL));
  SESSILE_CHECK(!o->color_by, SESSILE_ERR_USAGE,
                "colouring by a property is for single meshes: a scene's colours are its instances'");
  SESSILE_CALL(sessile_render_scene_check("scene", s));
  sessile_mesh_renderer *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->gpu = g;
  r->o = *o;
  snprintf(r->view, sizeof r->view, "%s", o->view);
  r->o.view = r->view;
  r->o.colormap = NULL; /* the caller's string, not kept */
  sessile_status st = scene_init(r, s, t_upload);
  if (st != SESSILE_OK) {
    sessile_mesh_renderer_destroy(r);
    return st;
  }
  *out = r;
  return SESSILE_OK;
}

unsigned char sessile_render_srgb_byte(double linear) {
  double c = linear <= 0 || !(linear == linear) ? 0 : linear >= 1 ? 1 : linear;
  double e = c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
  return (unsigned char)lround(e * 255.0);
}
