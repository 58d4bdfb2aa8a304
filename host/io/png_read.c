/* The 16-bit greyscale PNG reader (sessile/io/io_read.h; heightfields).
 * The file is opened by io (O_NONBLOCK, regular files only) and libpng
 * reads it through a callback on that descriptor; its header is checked
 * (kind, depth, size against the caller's limit) before the pixels are
 * allocated.  8-bit files are refused: 256 levels make terraces of a
 * seabed (docs/reef.md says why there is no warning instead). */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "io_internal.h"

typedef struct png_in {
  jmp_buf jb;
  char msg[200];
  int fd;
  unsigned char *rows; /* the 16-bit samples, big-endian as the file holds them */
  png_bytep *ptr;      /* each row's start */
} png_in;

static void on_error(png_structp p, png_const_charp msg) {
  png_in *r = png_get_error_ptr(p);
  snprintf(r->msg, sizeof r->msg, "%s", msg);
  longjmp(r->jb, 1);
}
static void on_warning(png_structp p, png_const_charp msg) { (void)p, (void)msg; }

static void read_fd(png_structp p, png_bytep dst, png_size_t n) {
  png_in *r = png_get_io_ptr(p);
  size_t done = 0;
  while (done < n) {
    ssize_t k = read(r->fd, dst + done, n - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) png_error(p, k < 0 ? "read failed" : "the file ends early");
    done += (size_t)k;
  }
}

/* The pixels of an open file.  Everything it allocates is in *r or *out
 * (not in this frame), so the caller frees it after a longjmp too. */
static sessile_status decode(const char *path, png_in *r, png_structp png, png_infop info, uint32_t max_side,
                             sessile_image_in *out) {
  png_uint_32 w, h;
  int depth, colour, interlace;
  png_read_info(png, info);
  png_get_IHDR(png, info, &w, &h, &depth, &colour, &interlace, NULL, NULL);
  SESSILE_CHECK(colour == PNG_COLOR_TYPE_GRAY, SESSILE_ERR_USAGE,
                "'%.200s' is not a greyscale PNG (colour type %d): a heightfield needs one grey channel", path, colour);
  SESSILE_CHECK(depth == 16, SESSILE_ERR_USAGE,
                "'%.200s' is a %d-bit PNG: a heightfield needs 16 bits (256 levels make terraces)", path, depth);
  SESSILE_CHECK(w >= 2 && h >= 2, SESSILE_ERR_USAGE, "'%.200s' is %u x %u pixels: a heightfield needs at least 2 x 2",
                path, (unsigned)w, (unsigned)h);
  SESSILE_CHECK(w <= max_side && h <= max_side, SESSILE_ERR_USAGE,
                "'%.200s' is %u x %u pixels (%.0f MiB of heights): more than %u a side", path, (unsigned)w,
                (unsigned)h, (double)w * h * sizeof *out->v / 1048576.0, (unsigned)max_side);
  if (interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out->width = w, out->height = h;
  out->v = malloc((size_t)w * h * sizeof *out->v);
  r->rows = malloc((size_t)w * h * 2);
  r->ptr = malloc(h * sizeof *r->ptr);
  SESSILE_CHECK(out->v && r->rows && r->ptr, SESSILE_ERR_NO_MEMORY, "out of host memory for '%.200s' (%u x %u)",
                path, (unsigned)w, (unsigned)h);
  for (png_uint_32 y = 0; y < h; y++) r->ptr[y] = r->rows + (size_t)y * 2 * w;
  png_read_image(png, r->ptr);
  png_read_end(png, NULL);
  for (size_t k = 0; k < (size_t)w * h; k++) out->v[k] = (r->rows[2 * k] << 8 | r->rows[2 * k + 1]) / 65535.0;
  return SESSILE_OK;
}

sessile_status sessile_read_png_grey16(const char *path, uint32_t max_side, sessile_image_in *out) {
  memset(out, 0, sizeof *out);
  uint64_t size;
  png_in *r = calloc(1, sizeof *r); /* on the heap: what libpng's longjmp leaves must not be a local */
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status s = io_open_regular(path, "PNG", &r->fd, &size);
  if (s != SESSILE_OK) {
    free(r);
    return s;
  }
  unsigned char sig[8];
  ssize_t k = read(r->fd, sig, 8);
  png_structp png = NULL;
  png_infop info = NULL;
  if (k != 8 || png_sig_cmp(sig, 0, 8))
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%.200s' is not a PNG file (no PNG signature)", path);
  else if (!(png = png_create_read_struct(PNG_LIBPNG_VER_STRING, r, on_error, on_warning)) ||
           !(info = png_create_info_struct(png)))
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "cannot create the libpng reader (out of memory)");
  else if (setjmp(r->jb))
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%.200s' is not a PNG that libpng can read: %s", path, r->msg);
  else {
    png_set_read_fn(png, r, read_fd);
    png_set_sig_bytes(png, 8);
    s = decode(path, r, png, info, max_side, out);
  }
  if (png) png_destroy_read_struct(&png, info ? &info : NULL, NULL);
  close(r->fd);
  free(r->rows), free(r->ptr), free(r);
  if (s != SESSILE_OK) sessile_image_in_free(out);
  return s;
}

void sessile_image_in_free(sessile_image_in *m) {
  if (m) free(m->v), memset(m, 0, sizeof *m);
}
