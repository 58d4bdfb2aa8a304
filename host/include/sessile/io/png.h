/* sessile — PNG output through libpng.
 *
 * Deterministic: the same pixels give the same bytes (no tIME or text chunk,
 * fixed zlib level and filter), so a picture can be compared byte for byte.
 * Atomic: encoded in memory, then written to a temporary in the same folder
 * and renamed into place (sessile_write_file_atomic: never through a planted
 * symlink), so a failed write leaves nothing that looks whole. */
#ifndef SESSILE_PNG_H
#define SESSILE_PNG_H
#include <stddef.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes w x h pixels of 8-bit RGBA, row 0 at the top, rows packed (4 w
 * bytes each), as an 8-bit RGBA PNG.  SESSILE_ERR_USAGE for a size outside
 * 1..1000000 a side; the write's own status (SESSILE_ERR_IO naming the path)
 * when the file cannot be written; the message starts "png: ". */
sessile_status sessile_png_write_rgba8(const char *path, int w, int h, const unsigned char *rgba);

/* The same PNG encoded into memory (*out malloc'ed, caller frees): what the
 * writer above writes, for benchmarks and callers with their own file. */
sessile_status sessile_png_encode_rgba8(int w, int h, const unsigned char *rgba, unsigned char **out,
                                        size_t *bytes);

#ifdef __cplusplus
}
#endif
#endif
