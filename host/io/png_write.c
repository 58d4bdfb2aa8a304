/* sessile io — PNG through libpng (sessile/png.h).
 *
 * libpng writes into the atomic file's stream, so a reader of a run directory
 * sees the old picture or the new one.  Deterministic: libpng adds no tIME
 * chunk unless asked, and the compression level, strategy and row filters are
 * set explicitly (library defaults may change between versions). */
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include "sessile/io.h"
#include "sessile/png.h"

typedef struct png_failure {
  char msg[200];
} png_failure;

static void on_png_error(png_structp png, png_const_charp msg) {
  png_failure *f = png_get_error_ptr(png);
  snprintf(f->msg, sizeof f->msg, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg) {
  (void)png, (void)msg; /* warnings are not failures; nothing goes to stderr */
}

static int fail(sessile_status s, char *err, size_t errlen) {
  if (err && errlen) snprintf(err, errlen, "%s", sessile_error_message());
  return (int)s;
}

int sessile_png_write_rgba8(const char *path, int w, int h, const unsigned char *rgba, char *err,
                            size_t errlen) {
  if (!path || !path[0]) return fail(sessile_error_set(SESSILE_ERR_USAGE, "cannot write a PNG: no path given"), err, errlen);
  if (w < 1 || h < 1 || w > (1 << 20) || h > (1 << 20))
    return fail(sessile_error_set(SESSILE_ERR_USAGE, "cannot write '%s': %d x %d pixels (1..%d each)", path, w,
                                  h, 1 << 20),
                err, errlen);
  if (!rgba) return fail(sessile_error_set(SESSILE_ERR_USAGE, "cannot write '%s': no pixels given", path), err, errlen);

  sessile_atomic_file af;
  sessile_status s = sessile_atomic_open(path, &af);
  if (s != SESSILE_OK) return fail(s, err, errlen);
  png_failure failure = {{0}};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : NULL;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    sessile_atomic_abort(&af);
    return fail(sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path), err, errlen);
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    sessile_atomic_abort(&af);
    return fail(sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", path, failure.msg), err, errlen);
  }
  png_init_io(png, af.f);
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, 0); /* Z_DEFAULT_STRATEGY */
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  for (int y = 0; y < h; y++) png_write_row(png, rgba + (size_t)y * (size_t)w * 4);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  s = sessile_atomic_commit(&af);
  return s == SESSILE_OK ? 0 : fail(s, err, errlen);
}
