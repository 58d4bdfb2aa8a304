/* sessile — the readers: one per format (PLY, OBJ, sessile's EXR slices, and
 * one-channel PNG and EXR heightfields), used by every layer that reads such a
 * file (render, the SDS model's surface, the reef's seabed).  docs/io.md
 * "Readers" lists their limits.
 *
 * Every reader treats its file as hostile: it is opened O_NONBLOCK and
 * refused unless it is a regular file (a FIFO never blocks), its header is
 * checked before anything is allocated (a count above the caller's limit or
 * larger than the bytes that follow is refused at once), and its body is
 * read in bounded chunks (a huge file of zeros costs one chunk, not its
 * size).  Every refusal is SESSILE_ERR_USAGE with one line naming the file,
 * the line or element, and the fault, the text quoted as the file holds it. */
#ifndef SESSILE_IO_READ_H
#define SESSILE_IO_READ_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- meshes ------------------------------------------------------------------- */
/* A mesh read from a file.  Positions in double (as the file holds them:
 * exact for ascii numbers up to double); normals and other per-vertex
 * properties in float (they are drawn, not simulated). */
typedef struct sessile_mesh_in {
  uint32_t nv, nf;
  double *pos;        /* 3 nv */
  uint32_t *tri;      /* 3 nf, indices < nv; polygons split into fans (0, k, k+1) */
  float *normal;      /* 3 nv when the file has nx ny nz (PLY, keep_props), else NULL */
  int nprops;         /* other scalar vertex properties (PLY, keep_props; uchar colours excluded) */
  char **prop_names;  /* nprops names */
  float **props;      /* props[p][v] */
} sessile_mesh_in;

typedef struct sessile_mesh_read_opts {
  uint64_t max_vertices; /* 0: 2^32 - 2 */
  uint64_t max_faces;    /* faces declared (PLY) or triangles read (OBJ); 0: 2^32 / 3 */
  int triangles_only;    /* 1: a face of other than 3 corners is refused; 0: polygons are
                            split into fans and faces of fewer than 3 corners skipped */
  int keep_props;        /* 1: keep the PLY's normals and other scalar vertex properties */
} sessile_mesh_read_opts;

/* PLY 1.0: ascii (one record a line), binary_little_endian and
 * binary_big_endian; any scalar types.  The first element "vertex" must have
 * x, y, z (finite), the first element "face" a vertex_indices (or
 * vertex_index) list of indices < the vertex count, at most 256 corners;
 * other elements and properties are skipped (lists up to 65535 items).
 * Refused: a malformed header, counts above the limits or the file, a short
 * or long record, data after the last element, a non-finite coordinate, an
 * index out of range.  opts may be NULL (defaults).  Free with
 * sessile_mesh_in_free. */
sessile_status sessile_read_ply(const char *path, const sessile_mesh_read_opts *opts, sessile_mesh_in *out);
/* OBJ: "v x y z [more]" and "f a b c ..." lines (a as v, v/t, v//n or v/t/n;
 * negative indices count back from the last vertex); every other line is
 * ignored.  Refused: a NUL byte (not text), a v or f line over 64 KiB, a
 * vertex without 3 finite numbers, an index that names no vertex (quoted as
 * written), more than 256 corners, counts above the limits. */
sessile_status sessile_read_obj(const char *path, const sessile_mesh_read_opts *opts, sessile_mesh_in *out);
void sessile_mesh_in_free(sessile_mesh_in *m); /* NULL-safe; leaves m zeroed */

/* --- EXR slices (written by sessile_write_slice_exr / _plane_exr) ------------- */
/* An open slice: one part named "slice" with a "sessile:plane" string. */
typedef struct sessile_exr_in sessile_exr_in;
typedef struct sessile_slice_header {
  char plane[128];             /* sessile:plane */
  int has_origin, has_spacing, has_axes, scanline;
  double origin[3], spacing[2]; /* sessile:origin, sessile:spacing */
  double axis_u[3], axis_v[3];  /* sessile:axis_u/axis_v (a general plane) */
  int iteration;                /* sessile:iteration, -1 when absent */
  int64_t width, height;        /* the data window */
  int nchannels;                /* every channel, the colour view's R, G, B included */
  int top_down;                 /* sessile:row_order "top-down" (absent: an older, bottom-up file) */
  int has_view;                 /* sessile:view_channel: R, G, B are a colour view, not data */
} sessile_slice_header;
/* Opens path (regular files only, never blocking) and reads its header
 * through OpenEXR's C API; anything but a sessile slice is refused. */
sessile_status sessile_exr_open(const char *path, sessile_exr_in **out);
const sessile_slice_header *sessile_exr_header(const sessile_exr_in *x);
/* Channel c's name ("" out of range); whether it holds float or half pixels. */
const char *sessile_exr_channel_name(const sessile_exr_in *x, int c);
int sessile_exr_channel_is_float(const sessile_exr_in *x, int c);
/* Index of channel `name`, or -1. */
int sessile_exr_find_channel(const sessile_exr_in *x, const char *name);
/* The data channels "a, b, c" (cut to n - 1 characters): the colour view's
 * R, G, B left out. */
void sessile_exr_channel_list(const sessile_exr_in *x, char *buf, size_t n);
/* Decodes the n channels `names` into dst[k] (width * height floats each)
 * in the plane's order: row 0 at the low end of v, whichever order the file
 * stores (top-down since sessile:row_order, bottom-up before); a slice over
 * 65536 a side or 2^28 pixels is refused. */
sessile_status sessile_exr_read_channels(sessile_exr_in *x, int n, const char *const *names, float *const *dst);
void sessile_exr_close(sessile_exr_in *x); /* NULL-safe */

/* --- one-channel images (heightfields) --------------------------------------- */
/* width x height values, row 0 first (the image's top row), each row left
 * to right. */
typedef struct sessile_image_in {
  uint32_t width, height;
  double *v;
} sessile_image_in;
/* A 16-bit greyscale PNG (libpng): values sample / 65535, in [0, 1].
 * Refused: not a PNG, another colour type (colour, palette, alpha), another
 * depth (8 bits), fewer than 2 or more than max_side pixels a side (the
 * message gives the memory it would take), damaged data. */
sessile_status sessile_read_png_grey16(const char *path, uint32_t max_side, sessile_image_in *out);
/* A one-part scanline EXR of one float or half channel (any name): values
 * as stored.  Refused: not an EXR, more parts or channels (the message
 * names them), an integer channel, a size as for PNG, a non-finite value. */
sessile_status sessile_read_exr_grey(const char *path, uint32_t max_side, sessile_image_in *out);
void sessile_image_in_free(sessile_image_in *m); /* NULL-safe; leaves m zeroed */

#ifdef __cplusplus
}
#endif
#endif
