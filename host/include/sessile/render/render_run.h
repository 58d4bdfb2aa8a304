/* sessile — pictures of whole runs (docs/render.md "Runs"): the text drawn
 * over a mesh picture (the grid's scale, a colour bar), one mesh file to one
 * PNG, a run's preview.png, and `sessile render RUN_DIR`'s renders/ folder
 * (the final mesh from the standard views, a contact sheet of the snapshots,
 * the slices, plots of the records).
 *
 * Every PNG is written atomically (sessile/io/png.h); same input, same device:
 * the same bytes.  Bad input is SESSILE_ERR_USAGE with a one-line message,
 * found before anything is written. */
#ifndef SESSILE_RENDER_RUN_H
#define SESSILE_RENDER_RUN_H
#include <stdio.h>
#include "sessile/progress.h"
#include "sessile/render/render_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Draws the annotation over w x h RGBA pixels (row 0 at the top, straight
 * alpha): "grid 2 cm" in the lower left corner when res has a grid, and,
 * when color_by names the property coloured (res->colormap set), a colour
 * bar on the right with the property's name and its range.  Pictures
 * smaller than 64 x 48 are left as drawn.  Pixels the text and bar do not
 * touch keep their bytes. */
sessile_status sessile_render_annotate(unsigned char *rgba, int w, int h, const sessile_render_result *res,
                                       const char *color_by);

/* A mesh file to one annotated PNG (read, check, draw one frame, annotate,
 * write); a scene file (FILE.json, render_scene.h) is drawn instanced.
 * res may be NULL. */
sessile_status sessile_render_mesh_png(sessile_gpu *g, const char *mesh_path, const sessile_render_options *o,
                                       const char *png_out, sessile_render_result *res);

/* A run's preview: the mesh from the oblique view, 640 x 480, 4 samples
 * (1 where the device has no 4), annotated. */
#define SESSILE_PREVIEW_W 640
#define SESSILE_PREVIEW_H 480
sessile_status sessile_render_preview(sessile_gpu *g, const char *mesh_path, const char *png_out);

/* --- run directories --------------------------------------------------------- */
typedef struct sessile_render_run_opts {
  const char *out_dir; /* NULL: RUN_DIR/renders (listed in the run's manifest) */
  uint32_t width, height; /* the final mesh's views (default 1280 x 960) */
  int quiet;
  sessile_progress_fn progress; /* pictures done of those planned (NULL: none) */
  void *progress_user;
} sessile_render_run_opts;

typedef struct sessile_render_plan sessile_render_plan;

/* Reads the run directory (manifest, generator, meshes, slices, records)
 * and decides what to draw, without a device and without writing anything.
 * SESSILE_ERR_USAGE: not a run directory (no manifest.json), a generator
 * without a known layout, nothing to draw, a planted symlink where a
 * folder or file of the run should be, or (writing into RUN_DIR/renders) a
 * run still holding the folder's lock.  When writing into RUN_DIR/renders
 * the plan holds the run folder's lock until it is destroyed, so no run
 * starts in the folder while its pictures are written. */
sessile_status sessile_render_plan_make(const char *run_dir, const sessile_render_run_opts *o,
                                        sessile_render_plan **out);
void sessile_render_plan_destroy(sessile_render_plan *p);
/* Draws everything planned; prints one line per picture to log (NULL: quiet). */
sessile_status sessile_render_plan_run(sessile_render_plan *p, sessile_gpu *g, FILE *log);

#ifdef __cplusplus
}
#endif
#endif
