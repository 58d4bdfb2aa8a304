/* sessile — PNG output (host/io/png_write.c), through libpng.
 *
 * Atomic (temporary + fsync + rename, like every sessile file) and
 * deterministic: the same pixels give the same bytes (no time chunk, fixed
 * compression level and filters). */
#ifndef SESSILE_PNG_H
#define SESSILE_PNG_H
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes w x h pixels of 8-bit RGBA (row 0 at the top, 4 bytes a pixel, rows
 * packed) to path as an 8-bit RGBA PNG.  Returns 0 (SESSILE_OK) or a
 * sessile_status code with a one-line message in err (when err is not NULL)
 * and in sessile_error_message(); on failure nothing is left at path. */
int sessile_png_write_rgba8(const char *path, int w, int h, const unsigned char *rgba, char *err,
                            size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
