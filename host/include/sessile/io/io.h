/* sessile — the run directory's files: every file is written to a temporary
 * name in the same folder and renamed into place, so a failed or interrupted
 * run never leaves a half-written file that looks whole.
 *
 * Formats: PLY (binary little-endian) and OBJ meshes; OpenEXR slices (float32
 * channels, through OpenEXR's C API, openexr.h) with plane origin, spacing and
 * iteration as header attributes; VTK XML UnstructuredGrid (.vtu, the box's
 * or any tetrahedral mesh, with point and cell data) and ParaView's .pvd
 * series; JSON through cJSON.  Every writer takes plain arrays, so any
 * generator (the sponge's box and surface, multi-part surfaces, general tet
 * meshes) can use them. */
#ifndef SESSILE_IO_H
#define SESSILE_IO_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "sessile/mesh/box.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- atomic files ------------------------------------------------------------ */
/* An output file being written: data goes to ".<name>.sessile-tmp.<random>"
 * in the same folder, created with O_CREAT|O_EXCL|O_NOFOLLOW (never through a
 * planted symlink, FIFO or file), until commit renames it to path (after
 * fflush + fsync, then an fsync of the folder); abort removes the temporary.
 * Errors are SESSILE_ERR_IO with the file's name and errno's text.  After
 * commit or abort the struct holds nothing (both free everything). */
typedef struct sessile_atomic_file {
  FILE *f;
  char *path, *tmp; /* tmp: the temporary's name inside the folder */
  int dirfd;        /* the folder, opened once: the rename happens where the file was made */
} sessile_atomic_file;
/* Whether a file name (no folder) is one of these temporaries: the run
 * framework removes such leftovers of a killed run at the next start. */
int sessile_is_temp_name(const char *name);
sessile_status sessile_atomic_open(const char *path, sessile_atomic_file *af);
sessile_status sessile_atomic_commit(sessile_atomic_file *af); /* closes; removes tmp on failure */
void sessile_atomic_abort(sessile_atomic_file *af);           /* closes and removes tmp; NULL-safe */
/* Whole buffer to path, atomically. */
sessile_status sessile_write_file_atomic(const char *path, const void *data, size_t bytes);
/* A small input file read whole (text[len] = 0; caller frees): a regular
 * file of at most max bytes, opened so that a FIFO or device cannot hang
 * (SESSILE_ERR_USAGE naming `what` and the path otherwise). */
sessile_status sessile_read_small_file(const char *path, size_t max, const char *what, char **text, size_t *len);
/* The same for `name` inside the folder open at dfd, never through a
 * symlink (O_NOFOLLOW); a missing file is SESSILE_OK with *text NULL.
 * `shown` names the file in messages (e.g. "'manifest.json' in the run
 * directory"). */
sessile_status sessile_read_small_file_at(int dfd, const char *name, const char *shown, size_t max, char **text,
                                          size_t *len);
/* mkdir -p; fails with SESSILE_ERR_IO naming the folder and errno's text. */
sessile_status sessile_mkdirs(const char *path);

/* --- meshes --------------------------------------------------------------------- */
/* Binary little-endian PLY: float x,y,z per vertex (plus float nx,ny,nz when
 * normals != NULL, and any extra float vertex properties named in extra_names
 * with values extra[p][v]), uchar-count uint-index faces. */
sessile_status sessile_write_ply(const char *path, const sessile_surface *s, const double *normals,
                                 int nextra, const char *const *extra_names,
                                 const double *const *extra);
sessile_status sessile_write_obj(const char *path, const sessile_surface *s, const double *normals);
/* The same two, abandoned (the temporary removed, SESSILE_ERR_INTERRUPTED)
 * when *stop (may be NULL) turns nonzero: a mesh of millions of triangles
 * takes seconds (PLY) to tens of seconds (OBJ), and a signal must stop it
 * within a fraction of one (the flag is looked at every MiB or 64 Ki lines
 * and before the final fsync). */
sessile_status sessile_write_ply_stop(const char *path, const sessile_surface *s, const double *normals,
                                      int nextra, const char *const *extra_names, const double *const *extra,
                                      const volatile sig_atomic_t *stop);
sessile_status sessile_write_obj_stop(const char *path, const sessile_surface *s, const double *normals,
                                      const volatile sig_atomic_t *stop);

/* OBJ's axes and unit (docs/io.md "OBJ conventions").  ZUP_CM is sessile's
 * own frame (z up, centimetres: the PLY's numbers).  YUP_M is for DCC tools
 * (Blender, Maya, Houdini): +Y up, right-handed, metres, the glTF writer's
 * frame: a point (x, y, z) cm is written (x, z, -y) / 100, a normal
 * (x, z, -y); a rotation, so windings keep their orientation. */
typedef enum sessile_obj_axes { SESSILE_OBJ_ZUP_CM = 0, SESSILE_OBJ_YUP_M = 1 } sessile_obj_axes;
/* "zup-cm" or "yup-m" into *out: 0, else -1 (*out untouched). */
int sessile_obj_axes_parse(const char *name, sessile_obj_axes *out);
/* "zup-cm", "yup-m" (NULL for anything else). */
const char *sessile_obj_axes_name(sessile_obj_axes axes);
typedef struct sessile_obj_style {
  sessile_obj_axes axes;
  const char *mtllib;   /* NULL: no material; else "mtllib <mtllib>" (a .mtl beside the OBJ) */
  const char *material; /* "usemtl <material>" (with mtllib) */
} sessile_obj_style;
/* sessile_write_obj_stop in a convention, with a material (style NULL:
 * sessile_write_obj_stop's bytes).  Names holding white space, or empty,
 * are SESSILE_ERR_USAGE. */
sessile_status sessile_write_obj_styled(const char *path, const sessile_surface *s, const double *normals,
                                        const sessile_obj_style *style, const volatile sig_atomic_t *stop);
/* A material library of one material `name`: diffuse colour Kd = rgb
 * (linear, 0..1, clamped), no specular highlight, opaque. */
sessile_status sessile_write_mtl(const char *path, const char *name, const float rgb[3]);

/* A surface made of several parts (e.g. the tubes of a branching coral),
 * written as one file: the parts' vertices are concatenated in order, and
 * each part's triangle indices (local to the part, 0..nv-1) are offset by the
 * vertices of the parts before it.  Empty parts (nv == nf == 0) are allowed.
 * Normals are per part: either every non-empty part has them or none does.
 * Fields are named once for the whole union; each part gives its own values
 * (fields[p][v] for field p, local vertex v; NULL when there are no fields). */
typedef struct sessile_mesh_part {
  const char *name;            /* OBJ o/g name and PLY comment; NULL: "part<k>" (no spaces) */
  const double *pos;           /* 3 nv */
  uint32_t nv;
  const uint32_t *tri;         /* 3 nf, counter-clockwise from outside */
  uint32_t nf;
  const double *normals;       /* 3 nv, or NULL */
  const double *const *fields; /* nfields arrays of nv values, or NULL when nfields == 0 */
} sessile_mesh_part;
/* Binary little-endian PLY of the union: float x,y,z (+ nx,ny,nz) + one float
 * property per field; header comments "sessile surface: N parts" and, per
 * part, "part <name> vertices <first> <count> faces <first> <count>".
 * Invalid input (non-finite positions, an index out of its part's range,
 * mixed normals, a total above 2^32-1 vertices or faces, bad names) is
 * SESSILE_ERR_USAGE and writes nothing. */
sessile_status sessile_write_ply_parts(const char *path, int nparts, const sessile_mesh_part *parts,
                                       int nfields, const char *const *field_names);
/* OBJ of the union: "o <name>" and "g <name>" per part, then its v (and vn)
 * lines and its faces with 1-based indices into the whole file.  Fields are
 * not written (OBJ has no per-vertex values). */
sessile_status sessile_write_obj_parts(const char *path, int nparts, const sessile_mesh_part *parts);

/* --- what a mesh file says about itself (docs/io.md, "Mesh headers") --------- */
/* Written as PLY "comment" lines, OBJ "#" lines and VTP field data; strings
 * are one line each (no newline).  color_by names the main scalar, one of
 * the fields: a PLY then carries uchar red, green, blue per vertex, that
 * field through the colour map `sessile render --color-by` would use
 * (sessile/io/mesh_colors.h). */
typedef struct sessile_mesh_info {
  const char *generator;   /* "grow", "sds run", ... (NULL: not said) */
  const char *version;     /* sessile's version (NULL: not said) */
  const char *commit;      /* the commit it was built from (NULL: unknown) */
  const char *seed;        /* as text, 64 bits exact (NULL: none) */
  const char *length_unit; /* of the coordinates: "cm", "u" (NULL: not said) */
  const char *time_unit;   /* of time: "iteration", "s" (NULL: no time) */
  double time;             /* the simulated time of this state, in time_unit */
  int iteration;           /* the iteration (frame) of this state, -1: none */
  const char *state;       /* which state the surface is, in words (NULL: none) */
  const char *color_by;    /* the main scalar (NULL: no colours) */
  const char *colormap;    /* NULL: viridis, or coolwarm for a range across 0 */
} sessile_mesh_info;
/* sessile_write_ply_parts with the info's header lines and colours (info
 * NULL: exactly sessile_write_ply_parts' file); a color_by that names no
 * field, or a string with a newline, is SESSILE_ERR_USAGE. */
sessile_status sessile_write_ply_info(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                                      const char *const *field_names, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop);
/* sessile_write_obj_styled with the info's header lines (info NULL:
 * exactly sessile_write_obj_styled's file). */
sessile_status sessile_write_obj_info(const char *path, const sessile_surface *s, const double *normals,
                                      const sessile_obj_style *style, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop);
/* The same union as VTK XML PolyData (.vtp, for ParaView and VTK): Float32
 * points, "Normals" and every field as a Float32 point array (the PLY's very
 * values), the main scalar as the active scalars, triangles as Polys (Int32
 * connectivity and offsets, Int64 past 2^31-1), compressed like the .vtu;
 * field data: TimeValue (the time, which VTK's readers take as the data
 * set's time), iteration, and generator, version, commit, seed,
 * length_unit, time_unit, state, main_scalar as strings. */
sessile_status sessile_write_vtp(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                                 const char *const *field_names, const sessile_mesh_info *info);

/* --- slices --------------------------------------------------------------------- */
typedef enum sessile_axis { SESSILE_AXIS_X = 0, SESSILE_AXIS_Y = 1, SESSILE_AXIS_Z = 2 } sessile_axis;
/* A slice: the axis-aligned plane axis = value through the box, sampled on
 * the box's own node grid of the other two axes (P1 interpolation between
 * node layers).  Channel values are float32, width = nodes along the first
 * remaining axis, height = along the second (x,y for a z-plane; x,z for a
 * y-plane; y,z for an x-plane), row j counted from the low end of the
 * second axis; the file stores rows top-down (EXR row 0 = the plane's row
 * height - 1), so that axis points up in image tools. */
typedef struct sessile_slice_channel {
  const char *name;     /* e.g. "c", "ux" */
  const double *field;  /* one value per box node */
} sessile_slice_channel;
/* Writes an EXR with float32 channels and a colour view of the first: half
 * R, G, B through the map `render --color-by` picks, linear light (so R, G,
 * B are refused as channel names); header attributes "sessile:plane"
 * (string, e.g. "z=3.5"), "sessile:origin" (v3f: the world position of pixel
 * (0,0), the image's bottom-left), "sessile:spacing" (v2f: cm per pixel
 * along width, height), "sessile:iteration" (int), "sessile:row_order"
 * ("top-down"), "sessile:view_channel", "sessile:view_colormap" (strings),
 * "sessile:view_range" (v2d).  One scanline part named "slice", ZIP
 * compression (level 6).  A plane outside the box is SESSILE_ERR_USAGE. */
sessile_status sessile_write_slice_exr(const char *path, const sessile_box *box, sessile_axis axis,
                                       double value, int nchan, const sessile_slice_channel *chan,
                                       int iteration);

/* A slice of any field on any plane: pixel (i, j) (i < width along u, j <
 * height along v; stored top-down: v points up in the image) sits at
 * origin + i spacing[0] u + j spacing[1] v,
 * with u, v the unit vectors of axis_u, axis_v (which must be perpendicular,
 * |cos| <= 1e-6).  The header has the same attributes as the box slice
 * ("sessile:plane" holds label, or "plane" when label is NULL; "sessile:origin";
 * "sessile:spacing"; "sessile:iteration") plus "sessile:axis_u" and
 * "sessile:axis_v" (v3f, the unit vectors). */
typedef struct sessile_plane {
  double origin[3];            /* world position of pixel (0, 0), cm */
  double axis_u[3], axis_v[3]; /* in-plane directions of width and height (any length > 0) */
  double spacing[2];           /* cm per pixel along u and v (> 0) */
  uint32_t width, height;      /* pixels (>= 1) */
} sessile_plane;
/* Value of channel `channel` at world point p (NaN is stored as NaN). */
typedef double (*sessile_plane_sampler)(void *user, int channel, const double p[3]);
sessile_status sessile_write_plane_exr(const char *path, const sessile_plane *plane, const char *label,
                                       int nchan, const char *const *names,
                                       sessile_plane_sampler sample, void *user, int iteration);
/* The same with precomputed pixels: values[c][i + width * j]. */
sessile_status sessile_write_plane_exr_values(const char *path, const sessile_plane *plane,
                                              const char *label, int nchan, const char *const *names,
                                              const double *const *values, int iteration);

/* --- volume fields -------------------------------------------------------------- */
/* VTK XML UnstructuredGrid of the box's tetrahedra (cell type 10, the 6 Kuhn
 * tets of each cube as sessile_box_tet orders them) with point data: Float64
 * scalars or 3-vectors, or UInt8 (e.g. the solid mask).  Appended binary,
 * zlib-compressed blocks (vtkZLibDataCompressor, header_type UInt64, level 1),
 * Float64 points, Int32 connectivity/offsets (Int64 when 4 * tets > 2^31-1),
 * UInt8 types.  Output is byte-identical for the same input, whatever the
 * number of OpenMP threads compressing it.  Sizes: docs/io.md. */
typedef struct sessile_point_data {
  const char *name;
  const double *f64; /* one per node, or NULL */
  const uint8_t *u8; /* one per node, when f64 is NULL */
  int components;    /* 1 or 3 (f64 only) */
} sessile_point_data;
sessile_status sessile_write_vtu(const char *path, const sessile_box *box, int ndata,
                                 const sessile_point_data *data);

/* Any tetrahedral mesh (e.g. sessile_tetmesh: xyz, nnodes, tet, ntets):
 * nv points xyz[3 nv], nt tets tets[4 nt] (VTK_TETRA node order), with point
 * data (one tuple per point) and cell data (one tuple per tet).  A field has a
 * name, exactly one of f64 / u8 / i32 (Float64, UInt8, Int32 in the file)
 * and 1 or 3 components; names are unique within point data and within cell
 * data.  Same encoding as sessile_write_vtu (sessile_write_vtu is this writer
 * with the box's tets generated on the fly, and gives the same bytes as this
 * writer given the box's points and tets).  Zero points or tets, non-finite
 * coordinates or an index >= nv is SESSILE_ERR_USAGE; nothing is written. */
enum { SESSILE_VTU_MAX_FIELDS = 256 };
typedef struct sessile_vtu_field {
  const char *name;
  const double *f64;  /* components per tuple, or NULL */
  const uint8_t *u8;  /* components per tuple, or NULL */
  const int32_t *i32; /* components per tuple, or NULL */
  int components;     /* 1 or 3 */
} sessile_vtu_field;
sessile_status sessile_write_vtu_tets(const char *path, const double *xyz, uint32_t nv,
                                      const uint32_t *tets, uint32_t nt, int npoint,
                                      const sessile_vtu_field *pf, int ncell,
                                      const sessile_vtu_field *cf);
/* ParaView collection listing (timestep, file) pairs; files relative to the .pvd. */
sessile_status sessile_write_pvd(const char *path, int n, const int *timesteps,
                                 const char *const *files);
/* The same with each entry's simulated time as its timestep (exact: %.17g). */
sessile_status sessile_write_pvd_times(const char *path, int n, const double *times,
                                       const char *const *files);

#ifdef __cplusplus
}
#endif
#endif
