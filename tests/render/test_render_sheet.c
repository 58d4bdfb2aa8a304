/* sessile_render_contact_sheet: the sheet's size from the documented
 * geometry, every tile's pixels equal to its source, captions drawn only
 * where given, same bytes on rerun, bad input refused; and the PNG writer
 * (sessile_png_write_rgba8) read back by Cairo's reader. */
#include <math.h>
#include "render2d_testutil.h"
#include "sessile/io/png.h"
#include "sessile/render/render2d.h"
#include "testutil.h"


/* An opaque test pattern that differs per tile and per pixel. */
static unsigned char pattern(int tile, int x, int y, int c) {
  return (unsigned char)((x * (3 + c) + y * (5 + 2 * c) + 71 * tile) & 255);
}

static int make_tile(const char *path, int tile, int w, int h) {
  unsigned char *rgba = malloc((size_t)w * h * 4);
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      for (int c = 0; c < 3; c++) rgba[4 * ((size_t)y * w + x) + c] = pattern(tile, x, y, c);
      rgba[4 * ((size_t)y * w + x) + 3] = 255;
    }
  sessile_status s = sessile_png_write_rgba8(path, w, h, rgba);
  free(rgba);
  return s == SESSILE_OK ? 0 : -1;
}

static void bad(const char *what, sessile_status s, const char *out, const char *must_contain) {
  char msg[400];
  const char *m = sessile_error_message();
  snprintf(msg, sizeof msg, "%s: SESSILE_ERR_USAGE, one line naming '%s', nothing written [%s]", what, must_contain, m);
  t_true(msg, s == SESSILE_ERR_USAGE && !strchr(m, '\n') && strstr(m, must_contain) && !t_exists(out));
}

int main(void) {
  dir = t_scratch("test_render_sheet");
  const int tw[3] = {100, 60, 100}, th[3] = {80, 90, 40};
  char *paths[3] = {strdup(P("a.png")), strdup(P("b.png")), strdup(P("c.png"))}; /* kept: P() rotates */
  for (int k = 0; k < 3; k++) t_true("write a tile PNG", make_tile(paths[k], k, tw[k], th[k]) == 0);
  /* the PNG writer: the pattern reads back exactly */
  t_png a = t_png_read(paths[0]);
  int exact = a.px && a.w == 100 && a.h == 80;
  for (int y = 0; exact && y < 80; y++)
    for (int x = 0; x < 100; x++)
      for (int c = 0; c < 3; c++) exact &= ((t_px(&a, x, y) >> (16 - 8 * c)) & 255) == pattern(0, x, y, c);
  t_true("sessile_png_write_rgba8: 100 x 80 pattern reads back exactly (Cairo's PNG reader)", exact);
  free(a.px);
  unsigned char px[4] = {1, 2, 3, 255};
  t_true("PNG writer: 0 x 1 pixels refused, message, nothing written",
         sessile_png_write_rgba8(P("zero.png"), 0, 1, px) == SESSILE_ERR_USAGE && sessile_error_message()[0] &&
             !t_exists(P("zero.png")));

  const char *caps[3] = {"iteration 10, t = 1.5", NULL, "iteration 30"};
  t_ok("contact sheet of 3 tiles in 2 columns", sessile_render_contact_sheet((const char *const *)paths, caps, 3, 2, P("sheet.png")));
  int cw = 100, ch = 90 + SESSILE_SHEET_CAPTION_H, pad = SESSILE_SHEET_PAD;
  int W = pad + 2 * (cw + pad), H = pad + 2 * (ch + pad);
  t_png s = t_png_read(P("sheet.png"));
  char msg[200];
  snprintf(msg, sizeof msg, "sheet is %d x %d (2 columns, 2 rows of %d x %d cells)", W, H, cw, ch);
  t_true(msg, s.px && s.w == W && s.h == H);
  if (s.px && s.w == W && s.h == H) {
    for (int k = 0; k < 3; k++) {
      int col = k % 2, row = k / 2;
      int x0 = pad + col * (cw + pad) + (cw - tw[k]) / 2, y0 = pad + row * (ch + pad);
      int worst = 0;
      for (int y = 0; y < th[k]; y++)
        for (int x = 0; x < tw[k]; x++) {
          unsigned char rgb[3] = {pattern(k, x, y, 0), pattern(k, x, y, 1), pattern(k, x, y, 2)};
          worst = (int)fmax(worst, t_rgb_diff(t_px(&s, x0 + x, y0 + y), rgb));
        }
      snprintf(msg, sizeof msg, "tile %d (%d x %d at %d, %d) equals its source pixel for pixel (max level diff)", k,
               tw[k], th[k], x0, y0);
      t_check(msg, worst, 0);
      /* the caption strip: dark text pixels only where a caption was given */
      int dark = 0;
      for (int y = y0 + 90; y < y0 + ch; y++)
        for (int x = pad + col * (cw + pad); x < pad + col * (cw + pad) + cw; x++) {
          uint32_t q = t_px(&s, x, y);
          dark += ((q >> 16) & 255) < 128 && ((q >> 8) & 255) < 128 && (q & 255) < 128;
        }
      snprintf(msg, sizeof msg, "tile %d: caption strip has %d dark pixels (%s)", k, dark,
               caps[k] ? "a caption: > 20" : "no caption: 0");
      t_true(msg, caps[k] ? dark > 20 : dark == 0);
    }
  }
  free(s.px);
  t_ok("contact sheet again", sessile_render_contact_sheet((const char *const *)paths, caps, 3, 2, P("sheet2.png")));
  t_true("same input, identical PNG bytes", t_same_bytes(P("sheet.png"), P("sheet2.png")));

  const char *missing[2] = {paths[0], P("missing.png")};
  bad("a missing tile", sessile_render_contact_sheet(missing, NULL, 2, 2, P("b1.png")), P("b1.png"), "missing.png");
  FILE *f = fopen(P("text.png"), "w");
  if (f) fputs("not a png\n", f), fclose(f);
  const char *text[1] = {P("text.png")};
  bad("a tile that is not a PNG", sessile_render_contact_sheet(text, NULL, 1, 1, P("b2.png")), P("b2.png"), "text.png");
  bad("no tiles", sessile_render_contact_sheet((const char *const *)paths, NULL, 0, 1, P("b3.png")), P("b3.png"), "1..10000");
  bad("0 columns", sessile_render_contact_sheet((const char *const *)paths, NULL, 3, 0, P("b4.png")), P("b4.png"), "columns");
  const char *many[200];
  for (int k = 0; k < 200; k++) many[k] = paths[0];
  bad("a sheet wider than 16384 pixels", sessile_render_contact_sheet(many, NULL, 200, 200, P("b5.png")), P("b5.png"),
      "at most 16384");
  for (int k = 0; k < 3; k++) free(paths[k]);
  return t_finish(NULL);
}
