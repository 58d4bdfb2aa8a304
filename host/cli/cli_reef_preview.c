/* The reef's preview scene (docs/reef.md, "Output"): reef/meshes.ply holds
 * the distinct meshes (the seabed's first) one after the other, and
 * reef/scene.json a render scene (sessile/render/render_scene.h) with one
 * instance per glTF node: its mesh, its material's colour and its matrix
 * (cm).  preview.png and `sessile render reef/scene.json` draw it
 * instanced, so each organism has its pool entry's colour. */
#include <stdlib.h>
#include <string.h>
#include "cli_reef.h"
#include "sessile/render/render_scene.h"

/* The distinct meshes one after the other, and their ranges. */
static sessile_status parts_of(const sessile_reef_gltf *g, sessile_surface *all, sessile_render_part *parts) {
  uint64_t nv = 0, nf = 0;
  for (uint32_t m = 0; m < g->scene.nmeshes; m++) nv += g->surfaces[m].nv, nf += g->surfaces[m].nf;
  SESSILE_CHECK(nv < UINT32_MAX / 4 && nf < UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "the reef is too large to preview");
  SESSILE_CALL(sessile_surface_reserve(all, (uint32_t)nv, (uint32_t)nf));
  for (uint32_t m = 0; m < g->scene.nmeshes; m++) {
    const sessile_surface *s = &g->surfaces[m];
    parts[m] = (sessile_render_part){all->nv, s->nv, all->nf, s->nf};
    memcpy(all->pos + 3 * (size_t)all->nv, s->pos, 3 * (size_t)s->nv * sizeof *s->pos);
    for (size_t f = 0; f < 3 * (size_t)s->nf; f++) all->tri[3 * (size_t)all->nf + f] = s->tri[f] + all->nv;
    all->nv += s->nv, all->nf += s->nf;
  }
  return SESSILE_OK;
}

sessile_status cli_reef_preview_scene(sessile_run *run, const sessile_reef_gltf *g) {
  sessile_surface all = {0};
  sessile_render_part *parts = calloc(g->scene.nmeshes, sizeof *parts);
  sessile_render_instance *inst = calloc(g->scene.nnodes, sizeof *inst);
  sessile_status st = parts && inst ? parts_of(g, &all, parts)
                                    : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t k = 0; st == SESSILE_OK && k < g->scene.nnodes; k++) {
    const sessile_gltf_node *n = &g->nodes[k];
    const float *rgba = g->materials[g->meshes[n->mesh].material].rgba; /* linear, as glTF's */
    inst[k].part = n->mesh;
    for (int c = 0; c < 3; c++) inst[k].rgba[c] = sessile_render_srgb_byte(rgba[c]);
    inst[k].rgba[3] = 255;
    memcpy(inst[k].matrix, n->matrix, sizeof inst[k].matrix);
  }
  if (st == SESSILE_OK) st = sessile_run_write_surface(run, "reef/meshes.ply", &all, 0, NULL, NULL);
  if (st == SESSILE_OK)
    st = cli_reef_write_json(run, "reef/scene.json",
                             sessile_render_scene_json("meshes.ply", parts, g->scene.nmeshes, inst, g->scene.nnodes));
  sessile_surface_free(&all);
  free(parts);
  free(inst);
  return st;
}
