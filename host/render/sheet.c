/* sessile render — contact sheets (render2d.h): PNGs tiled in a grid with a
 * caption under each.  Tiles are read by Cairo's PNG reader and painted at
 * integer offsets without scaling, so every tile pixel is its source's. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "draw2d.h"

sessile_status sessile_render_contact_sheet(const char *const *png_paths, const char *const *captions, int n,
                                            int cols, const char *png_out) {
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  SESSILE_CHECK(n >= 1 && n <= 10000 && png_paths, SESSILE_ERR_USAGE, "a contact sheet needs 1..10000 pictures (got %d)", n);
  SESSILE_CHECK(cols >= 1 && cols <= 1000, SESSILE_ERR_USAGE, "a contact sheet needs 1..1000 columns (got %d)", cols);
  if (cols > n) cols = n;
  cairo_surface_t **tile = calloc((size_t)n, sizeof *tile);
  SESSILE_CHECK(tile, SESSILE_ERR_NO_MEMORY, "out of memory for %d tiles", n);
  sessile_status st = SESSILE_OK;
  int cw = 0, th = 0;
  for (int k = 0; k < n && st == SESSILE_OK; k++) {
    const char *path = png_paths[k];
    if (!path || access(path, R_OK) != 0) {
      st = sessile_error_set(SESSILE_ERR_USAGE, "cannot read '%s': %s", path ? path : "(null)",
                             path ? strerror(errno) : "no path");
      break;
    }
    /* Cairo reports a file that is not a PNG as "out of memory": look first */
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[8] = {0};
    FILE *f = fopen(path, "rb");
    size_t got = f ? fread(head, 1, 8, f) : 0;
    if (f) fclose(f);
    if (got != 8 || memcmp(head, magic, 8)) {
      st = sessile_error_set(SESSILE_ERR_USAGE, "'%s' is not a PNG file", path);
      break;
    }
    tile[k] = cairo_image_surface_create_from_png(path);
    cairo_status_t cs = cairo_surface_status(tile[k]);
    if (cs != CAIRO_STATUS_SUCCESS) {
      st = sessile_error_set(SESSILE_ERR_USAGE, "cannot read '%s' as a PNG: %s", path, cairo_status_to_string(cs));
      break;
    }
    int w = cairo_image_surface_get_width(tile[k]), h = cairo_image_surface_get_height(tile[k]);
    if (w > cw) cw = w;
    if (h > th) th = h;
  }
  int rows = (n + cols - 1) / cols, ch = th + SESSILE_SHEET_CAPTION_H;
  long long W = SESSILE_SHEET_PAD + (long long)cols * (cw + SESSILE_SHEET_PAD);
  long long H = SESSILE_SHEET_PAD + (long long)rows * (ch + SESSILE_SHEET_PAD);
  if (st == SESSILE_OK && (W > SESSILE_RENDER2D_MAX_SIZE || H > SESSILE_RENDER2D_MAX_SIZE))
    st = sessile_error_set(SESSILE_ERR_USAGE,
                           "a contact sheet of %d pictures (%d x %d each) in %d columns would be %lld x %lld pixels "
                           "(at most %d a side): use more or fewer columns, or smaller pictures",
                           n, cw, th, cols, W, H, SESSILE_RENDER2D_MAX_SIZE);
  d2_canvas cv = {0};
  if (st == SESSILE_OK)
    st = d2_canvas_create(&cv, (int)(W < SESSILE_RENDER2D_MIN_SIZE ? SESSILE_RENDER2D_MIN_SIZE : W),
                          (int)(H < SESSILE_RENDER2D_MIN_SIZE ? SESSILE_RENDER2D_MIN_SIZE : H), png_out);
  if (st == SESSILE_OK) {
    cairo_t *cr = cv.cr;
    for (int k = 0; k < n; k++) {
      int col = k % cols, row = k / cols, w = cairo_image_surface_get_width(tile[k]);
      int cx = SESSILE_SHEET_PAD + col * (cw + SESSILE_SHEET_PAD), cy = SESSILE_SHEET_PAD + row * (ch + SESSILE_SHEET_PAD);
      cairo_set_source_surface(cr, tile[k], cx + (cw - w) / 2, cy);
      cairo_paint(cr);
      if (captions && captions[k] && captions[k][0]) {
        cairo_save(cr);
        cairo_rectangle(cr, cx, cy + th, cw, SESSILE_SHEET_CAPTION_H);
        cairo_clip(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        d2_text(cr, cx + 0.5 * cw, cy + th + 0.5 * SESSILE_SHEET_CAPTION_H, 13, 0.5, 0.5, 0, captions[k]);
        cairo_restore(cr);
      }
    }
    st = d2_canvas_write_png(&cv, png_out);
  }
  d2_canvas_destroy(&cv);
  for (int k = 0; k < n; k++)
    if (tile[k]) cairo_surface_destroy(tile[k]);
  free(tile);
  return st;
}
