/* Helpers of the 2-D picture tests (tests/render/test_render_{slice,plot,sheet}.c):
 * a PNG read back through Cairo's reader (independent of sessile's writer),
 * file bytes, and a scratch folder. */
#ifndef RENDER2D_TESTUTIL_H
#define RENDER2D_TESTUTIL_H
#include <cairo.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct t_png {
  int w, h;
  uint32_t *px; /* 0xAARRGGBB, w x h; NULL when the file could not be read */
} t_png;

static inline t_png t_png_read(const char *path) {
  t_png p = {0, 0, NULL};
  cairo_surface_t *s = cairo_image_surface_create_from_png(path);
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    p.w = cairo_image_surface_get_width(s), p.h = cairo_image_surface_get_height(s);
    int stride = cairo_image_surface_get_stride(s);
    p.px = malloc((size_t)p.w * p.h * 4);
    const unsigned char *d = cairo_image_surface_get_data(s);
    for (int y = 0; p.px && y < p.h; y++) memcpy(p.px + (size_t)y * p.w, d + (size_t)y * stride, (size_t)p.w * 4);
  }
  cairo_surface_destroy(s);
  return p;
}

static inline uint32_t t_px(const t_png *p, int x, int y) { return p->px[(size_t)y * p->w + x]; }

/* max over channels of |pixel - rgb| */
static inline int t_rgb_diff(uint32_t px, const unsigned char rgb[3]) {
  int d = 0;
  for (int k = 0; k < 3; k++) {
    int c = (int)(px >> (16 - 8 * k)) & 255, e = abs(c - rgb[k]);
    if (e > d) d = e;
  }
  return d;
}

static inline int t_exists(const char *path) { return access(path, F_OK) == 0; }

/* The whole file, or NULL (size in *n). */
static inline unsigned char *t_slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = malloc(len > 0 ? (size_t)len : 1);
  *n = b && fread(b, 1, (size_t)len, f) == (size_t)len ? (size_t)len : 0;
  fclose(f);
  return b;
}

static inline int t_same_bytes(const char *a, const char *b) {
  size_t na = 0, nb = 0;
  unsigned char *x = t_slurp(a, &na), *y = t_slurp(b, &nb);
  int same = x && y && na == nb && na > 0 && !memcmp(x, y, na);
  free(x);
  free(y);
  return same;
}

/* A fresh scratch folder under the test's working directory. */
static inline const char *t_scratch(const char *name) {
  static char dir[256];
  snprintf(dir, sizeof dir, "%s.out", name);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) return NULL;
  mkdir(dir, 0777);
  return dir;
}

/* The test's scratch folder (set from t_scratch) and a path in it: 16
 * rotating buffers, so several in one call are fine. */
static const char *dir;
static inline const char *P(const char *name) {
  static char buf[16][512];
  static int k;
  k = (k + 1) % 16;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}
#endif
