/* sessile io — helpers shared by the writers (not public). */
#ifndef SESSILE_IO_INTERNAL_H
#define SESSILE_IO_INTERNAL_H
#include <stdint.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sessile/io/io_read.h"

/* Little-endian stores, independent of the host's byte order. */
static inline uint8_t *io_put_u32(uint8_t *p, uint32_t v) {
  for (int b = 0; b < 4; b++) p[b] = (uint8_t)(v >> (8 * b));
  return p + 4;
}
static inline uint8_t *io_put_u64(uint8_t *p, uint64_t v) {
  for (int b = 0; b < 8; b++) p[b] = (uint8_t)(v >> (8 * b));
  return p + 8;
}
static inline uint8_t *io_put_f32(uint8_t *p, double v) {
  float f = (float)v;
  uint32_t u;
  memcpy(&u, &f, 4);
  return io_put_u32(p, u);
}
static inline uint8_t *io_put_f64(uint8_t *p, double v) {
  uint64_t u;
  memcpy(&u, &v, 8);
  return io_put_u64(p, u);
}

/* Reverses the order of the h rows of w floats, in place: the plane's
 * rows (low v first) to an EXR slice's (top first) and back. */
static inline void io_flip_rows(float *img, size_t w, size_t h) {
  for (size_t j = 0; j < h / 2; j++) {
    float *a = img + j * w, *b = img + (h - 1 - j) * w;
    for (size_t x = 0; x < w; x++) {
      float t = a[x];
      a[x] = b[x], b[x] = t;
    }
  }
}

/* sessile (x, y, z), z up -> (x, z, -y), +Y up, right-handed: the frame of
 * the glTF writer and of OBJ's y-up convention (a rotation: windings and
 * handedness kept). */
static inline void io_dir_yup(const double *v, double *o) {
  o[0] = v[0], o[1] = v[2], o[2] = -v[1];
}

/* fwrite that records a SESSILE_ERR_IO naming the (final) file on failure. */
sessile_status io_write(sessile_atomic_file *af, const void *data, size_t bytes);
/* fprintf-like; same error reporting. */
sessile_status io_printf(sessile_atomic_file *af, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Writes s with XML's five special characters escaped (for attribute values). */
sessile_status io_xml_escaped(sessile_atomic_file *af, const char *s);

/* --- meshes being written (mesh_write.c) ------------------------------------- */
/* Checks a list of parts (and nfields field arrays per part); on success
 * *tv, *tf hold the union's vertex and face counts and *with_normals whether
 * normals are written. */
sessile_status io_check_parts(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                              const char *const *names, uint32_t *tv, uint32_t *tf, int *with_normals);

/* --- mesh headers (mesh_info.c) -------------------------------------------- */
/* Checks info (NULL: nothing to say) and finds its color_by among the field
 * names: *main_field its index, -1 without colours. */
sessile_status io_mesh_info_check(const char *path, const sessile_mesh_info *info, int nfields,
                                  const char *const *names, int *main_field);
/* The info's header lines, each starting with lead ("comment", "#"). */
sessile_status io_mesh_info_lines(sessile_atomic_file *af, const char *lead, const sessile_mesh_info *info);
/* Colours (3 tv bytes, caller frees) of the union's field `field` (tv
 * vertices in all) through map (NULL: by the sign), with the map and range used. */
typedef struct io_mesh_rgb_used {
  const char *map;
  double lo, hi;
} io_mesh_rgb_used;
sessile_status io_mesh_rgb(const char *path, int nparts, const sessile_mesh_part *parts, uint32_t tv, int field,
                           const char *map, uint8_t **rgb, io_mesh_rgb_used *used);

/* --- VTK XML arrays (vtu.c; vtp.c uses them too) ----------------------------- */
/* What the mesh arrays are generated from: the structured box (its Kuhn
 * tets, never stored), or explicit coordinates and tets. */
typedef struct vtu_mesh {
  const sessile_box *box;
  const double *xyz;
  const uint32_t *tets;
} vtu_mesh;

/* One appended array: ntuples tuples of tuple_bytes bytes, produced by fill. */
typedef struct vtu_array {
  const char *xml_type, *name; /* name may be NULL (Points) */
  int components;
  uint64_t ntuples;
  size_t tuple_bytes;
  void (*fill)(const struct vtu_array *a, uint64_t first, uint64_t count, uint8_t *dst);
  const vtu_mesh *mesh;
  const sessile_vtu_field *field;
  int wide; /* Int64 connectivity / offsets */
  /* result: header + compressed blocks */
  uint8_t *blob;
  size_t blob_bytes;
  const void *user; /* what another writer's fill reads (vtp.c) */
} vtu_array;

/* Compresses array a into a->blob: the UInt64 header (blocks, block size,
 * size of a partial last block or 0, compressed size of each block) followed
 * by the zlib streams (vtkZLibDataCompressor, level 1). */
sessile_status io_vtk_compress(const char *path, vtu_array *a);
/* The array's <DataArray .../> tag, format appended at offset. */
sessile_status io_vtk_array_tag(sessile_atomic_file *af, const vtu_array *a, uint64_t offset);

/* --- OBJ conventions (obj_style.c) ------------------------------------------ */
/* SESSILE_ERR_USAGE naming path for an unknown convention or a material
 * name or mtllib that is empty or holds white space. */
sessile_status io_obj_style_check(const char *path, const sessile_obj_style *st);
/* The comment naming a y-up convention, and the mtllib and usemtl lines. */
sessile_status io_obj_style_lines(sessile_atomic_file *af, const sessile_obj_style *st);

/* --- reading (read_stream.c) ------------------------------------------------ */
/* Opens path for reading: O_NONBLOCK (a FIFO or device cannot hang the
 * open), then refused unless fstat says a regular file; *size its length.
 * `what` names the kind of file in messages ("mesh", "slice"). */
sessile_status io_open_regular(const char *path, const char *what, int *fd, uint64_t *size);

/* A file read in chunks of IO_CHUNK bytes (memory bounded whatever the
 * file's size); line counts lines for text formats. */
enum { IO_CHUNK = 1 << 16 };
typedef struct io_in {
  const char *path;
  int fd;
  uint64_t size, off; /* off: bytes consumed */
  uint64_t line;      /* 1-based line of the next byte */
  size_t at, n;       /* the unread window of buf */
  unsigned char buf[IO_CHUNK];
} io_in;
sessile_status io_in_open(io_in *r, const char *path, const char *what);
void io_in_close(io_in *r);
/* Bytes that can be read now (refilling the window); 0 at the end. */
sessile_status io_in_more(io_in *r, size_t *avail);
/* The next line without its "\n" (and "\r") into line (cap bytes, NUL-ended):
 * *got 0 at the end of the file.  A line of cap bytes or more stops there
 * with *len = cap (the rest unread: refuse it, or io_in_skip_line).  A NUL
 * byte is refused (not text). */
sessile_status io_in_line(io_in *r, char *line, size_t cap, size_t *len, int *got);
/* The rest of the current line, consumed (NUL bytes refused). */
sessile_status io_in_skip_line(io_in *r);

/* --- meshes being read (mesh_in.c) ------------------------------------------ */
/* Appends the fan (0, k, k+1) of an n-corner face (n >= 3) to m->tri, *cap
 * triangles allocated; refuses more than max triangles. */
sessile_status io_mesh_add_face(sessile_mesh_in *m, size_t *cap, const uint32_t *poly, uint32_t n,
                                uint64_t max, const char *path);
/* The options with their defaults filled in. */
sessile_mesh_read_opts io_mesh_opts(const sessile_mesh_read_opts *o);
/* n bytes into dst; *got 0 when the file ends first. */
sessile_status io_in_bytes(io_in *r, void *dst, size_t n, int *got);

#endif
