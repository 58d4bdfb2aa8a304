/* sessile — 2-D pictures drawn with Cairo (host/render/): slices of EXR
 * files as colour-mapped images, plots of a run's records, contact sheets.
 * Every function writes one PNG atomically (sessile/io/png.h), writes nothing on
 * failure, and returns a sessile_status with a one-line message in
 * sessile_error_message() (bad input: SESSILE_ERR_USAGE, exit 2 in the CLI).
 * Same input, same Cairo version: the same PNG bytes.  docs/render.md. */
#ifndef SESSILE_RENDER2D_H
#define SESSILE_RENDER2D_H
#include <stddef.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Picture size limits (pixels per side). */
#define SESSILE_RENDER2D_MIN_SIZE 64
#define SESSILE_RENDER2D_MAX_SIZE 16384

typedef struct sessile_render2d_opts {
  int width, height;    /* picture size, 64..16384 each (default 800 x 600) */
  const char *colormap; /* slice: NULL or "auto" picks viridis or coolwarm by the data's sign */
  int fixed_range;      /* slice: 1 maps [vmin, vmax] (e.g. one range for a whole series) */
  double vmin, vmax;
  const char *title;    /* NULL: an automatic title (channel, plane, iteration) */
  /* The sponge's outline on a slice, from (first that applies):
   *  - outline_ply: a sessile PLY surface cut exactly by the slice's plane;
   *  - outline_channel: a channel of the EXR contoured at outline_level by
   *    marching squares (e.g. "solid" at 0.5);
   *  - a channel named "solid" or "mask" (level 0.5) or "phi" or "sdf"
   *    (level 0) when the EXR has one.  Else no outline. */
  const char *outline_ply;
  const char *outline_channel;
  double outline_level;
} sessile_render2d_opts;

/* Defaults: 800 x 600, automatic map and range, no title, automatic outline. */
void sessile_render2d_opts_default(sessile_render2d_opts *o);

/* One channel of an EXR slice written by sessile (sessile_write_slice_exr or
 * sessile_write_plane_exr: part "slice", float channels, the sessile:*
 * attributes) as a colour-mapped image with a colour bar, the physical axes
 * in cm, and the sponge's outline (see the options).  o may be NULL. */
sessile_status sessile_render_slice(const char *exr_path, const char *channel, const sessile_render2d_opts *o,
                                    const char *png_out);

/* The channels of a sessile EXR slice, as "a, b, c" in the file's order
 * (OpenEXR keeps them sorted by name), into names (n bytes); the first is
 * what `sessile render FILE.exr` draws by default.  The same checks as
 * sessile_render_slice (SESSILE_ERR_USAGE for anything but a sessile slice). */
sessile_status sessile_render_slice_channels(const char *exr_path, char *names, size_t n);

/* The plot area of a slice picture (pixels: left, top, width, height, with
 * the image's physical extent [u0, u1] x [v0, v1] mapped onto it, v up) —
 * what sessile_render_slice draws for this EXR and options.  For tests and
 * for callers that annotate. */
typedef struct sessile_slice_layout {
  int img_x, img_y, img_w, img_h; /* the image area */
  int bar_x, bar_y, bar_w, bar_h; /* the colour bar (bottom = vmin, top = vmax) */
  double u0, u1, v0, v1;          /* physical extent (cm) of the image area */
  double vmin, vmax;              /* the mapped range */
  char colormap[16];              /* the map used */
  int width, height;
} sessile_slice_layout;

sessile_status sessile_render_slice_layout(const char *exr_path, const char *channel,
                                           const sessile_render2d_opts *o, sessile_slice_layout *lay);

/* --- plots ------------------------------------------------------------------ */
#define SESSILE_PLOT_MAX_SERIES 8

typedef struct sessile_plot_series {
  const char *label;
  const double *x, *y; /* n points; NaN points are skipped */
  size_t n;
  int axis2;           /* 0: y on the left axis; 1: on the right-hand axis (y2label) */
  /* NULL, or each point's interval [ylo[i], yhi[i]] drawn as a vertical bar
   * with caps (a confidence interval); the y range covers the bars.  A point
   * whose bounds are not both finite has no bar. */
  const double *ylo, *yhi;
} sessile_plot_series;

typedef struct sessile_plot {
  const char *title, *xlabel, *ylabel; /* labels carry the units, e.g. "time per step (ms)" */
  int nseries;                         /* 1..SESSILE_PLOT_MAX_SERIES */
  sessile_plot_series series[SESSILE_PLOT_MAX_SERIES];
  const char *y2label; /* the right-hand axis's label (drawn when a series has axis2) */
} sessile_plot;

/* The data-to-pixel transform of a plot: x -> px0 + (x - x0) / (x1 - x0) * (px1 - px0),
 * y likewise (py0 is the bottom of the plot area, py1 its top); x0..x1 and
 * y0..y1 are the axes' ranges, extended to whole ticks by the 1-2-5 rule.
 * With has_y2 (some series has axis2), those series map y through y20..y21
 * instead (the right-hand axis, its own ticks every y2step); an axis that
 * no series with a finite point uses is 0..1. */
typedef struct sessile_plot_layout {
  double x0, x1, y0, y1;
  double px0, px1, py0, py1;
  double xstep, ystep; /* tick spacing */
  int width, height;
  int has_y2;               /* 0: no right-hand axis (y20, y21, y2step 0) */
  double y20, y21, y2step;
} sessile_plot_layout;

/* Points with markers joined by lines, one colour per series, interval
 * bars where a series has them, axes with ticks and labels, a legend.  With a right-hand axis the right margin
 * widens for its tick labels and label, the grid stays the left axis's, and
 * each axis's label takes the colour of its first series.  o may be NULL
 * (the defaults). */
sessile_status sessile_render_plot(const sessile_plot *p, const sessile_render2d_opts *o, const char *png_out);
sessile_status sessile_render_plot_layout(const sessile_plot *p, const sessile_render2d_opts *o,
                                          sessile_plot_layout *lay);

/* A plot from a run's records.jsonl.  what: a preset
 *   "solver"  nutrient solver iterations per growth iteration (sessile grow)
 *   "time"    seconds per growth iteration, total and per stage (sessile grow)
 *   "steps"   ms per step against cells (sessile sds run; the SDS paper's Fig. 12)
 * or "XKEY:YKEY[,YKEY...]" with dotted keys into each record
 * ("iteration:nutrient_solve.iterations").  Records without the keys are
 * skipped; no record with them at all is an error. */
sessile_status sessile_render_plot_records(const char *records_jsonl, const char *what,
                                           const sessile_render2d_opts *o, const char *png_out);

/* Fig. 12 of Porter & McCormack's SDS paper from `sessile sds run`'s
 * sds/steps.csv: against the simulated time, ms per step (left axis; steps
 * with ms <= 0 are no point) and the number of cells (right axis).  The
 * CSV's header names its columns (time, ms and cells needed, in any order,
 * others ignored); one row of plain numbers per step; blank lines skipped.
 * A missing column, a malformed row (named by its line) or no row at all is
 * SESSILE_ERR_USAGE. */
sessile_status sessile_render_plot_sds_steps(const char *steps_csv, const sessile_render2d_opts *o,
                                             const char *png_out);

/* --- contact sheets ------------------------------------------------------------ */
/* n PNGs tiled in rows of `cols`, each in a cell of the largest tile's size
 * with its caption under it (captions may be NULL).  Tiles are copied pixel
 * for pixel (not scaled); the sheet may be at most SESSILE_RENDER2D_MAX_SIZE
 * per side. */
sessile_status sessile_render_contact_sheet(const char *const *png_paths, const char *const *captions, int n,
                                            int cols, const char *png_out);

/* The sheet's geometry: a cell is cell_w = the widest tile by cell_h = the
 * tallest tile + SESSILE_SHEET_CAPTION_H; tile k (column k % cols, row k / cols)
 * has its top-left corner at
 *   x = PAD + col (cell_w + PAD) + (cell_w - tile_w) / 2,  y = PAD + row (cell_h + PAD)
 * (integer division), its caption centred in the strip under it; the sheet is
 * PAD + cols (cell_w + PAD) by PAD + rows (cell_h + PAD), rows = ceil(n / cols),
 * with cols reduced to n when n is smaller. */
#define SESSILE_SHEET_PAD 8
#define SESSILE_SHEET_CAPTION_H 22

#ifdef __cplusplus
}
#endif
#endif
