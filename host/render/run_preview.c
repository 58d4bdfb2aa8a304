/* sessile render — one mesh (or scene) file to one annotated PNG, and a
 * run's preview.png (render_run.h). */
#include <stdlib.h>
#include <string.h>
#include "sessile/io/png.h"
#include "sessile/render/render_run.h"
#include "sessile/render/render_scene.h"

sessile_status sessile_render_mesh_png(sessile_gpu *g, const char *mesh_path, const sessile_render_options *o,
                                       const char *png_out, sessile_render_result *res) {
  sessile_render_mesh *m = NULL;
  sessile_render_scene *sc = NULL;
  sessile_mesh_renderer *r = NULL;
  SESSILE_CALL(sessile_render_options_check(o, NULL));
  sessile_status s;
  if (sessile_render_is_scene(mesh_path)) { /* a scene file (render_scene.h): the reef's preview */
    s = sessile_render_scene_read(mesh_path, &sc);
    if (s == SESSILE_OK) s = sessile_scene_renderer_create(g, sc, o, &r, NULL);
  } else {
    SESSILE_CALL(sessile_render_mesh_read(mesh_path, &m));
    s = sessile_render_options_check(o, m);
    if (s == SESSILE_OK) s = sessile_mesh_renderer_create(g, m, o, &r, NULL);
  }
  unsigned char *px = NULL;
  sessile_render_result rr;
  memset(&rr, 0, sizeof rr);
  if (s == SESSILE_OK) {
    px = malloc((size_t)o->width * o->height * 4u);
    if (!px) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a %ux%u picture", o->width, o->height);
  }
  if (s == SESSILE_OK) s = sessile_mesh_renderer_draw(r, 0.0, px, &rr);
  if (s == SESSILE_OK) s = sessile_render_annotate(px, (int)o->width, (int)o->height, &rr, o->color_by);
  if (s == SESSILE_OK) s = sessile_png_write_rgba8(png_out, (int)o->width, (int)o->height, px);
  if (s == SESSILE_OK && res) *res = rr;
  free(px);
  sessile_mesh_renderer_destroy(r);
  sessile_render_mesh_destroy(m);
  sessile_render_scene_destroy(sc);
  return s;
}

sessile_status sessile_render_preview(sessile_gpu *g, const char *mesh_path, const char *png_out) {
  sessile_render_options o;
  sessile_render_options_default(&o);
  o.width = SESSILE_PREVIEW_W, o.height = SESSILE_PREVIEW_H;
  o.samples = 4;
  sessile_status s = sessile_render_mesh_png(g, mesh_path, &o, png_out, NULL);
  if (s == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "sample")) {
    o.samples = 1; /* a device without 4x multisampling */
    s = sessile_render_mesh_png(g, mesh_path, &o, png_out, NULL);
  }
  return s;
}
