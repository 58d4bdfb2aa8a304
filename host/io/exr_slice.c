/* sessile io — EXR slices through OpenEXR's C API (Core 3.1): of box fields
 * on an axis-aligned plane (sessile_write_slice_exr), or of any field on any
 * plane, given as a sampler callback or as precomputed pixels.  All three
 * share one encoder.
 *
 * One scanline part, float32 data channels plus half R, G, B of the first
 * channel through a colour map (exr_view.c), ZIP compression (16 lines per
 * zlib block: lossless, deterministic, and read by every EXR tool).  Rows
 * are stored top-down as EXR expects (row 0 is the top of the image), so
 * the plane's v axis points up in every viewer; "sessile:row_order" says
 * so.  The slice is sampled on the box's own node grid, so between the two
 * node layers the
 * plane falls between the value is the linear blend of the layers; on the
 * Kuhn mesh the node-layer edges are tet edges, so this is exactly the P1
 * interpolant (sessile_box_interpolate) at those points.
 *
 * OpenEXR writes through our callback into the atomic file's descriptor, so
 * the usual temp + fsync + rename covers EXR too. */
#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <stdlib.h>
#include <unistd.h>
#include "exr_view.h"
#include "io_internal.h"

typedef struct exr_sink {
  int fd;
  int err; /* errno of the first failed write */
} exr_sink;

static _Thread_local char exr_msg[256];

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  (void)ctxt;
  if (!exr_msg[0]) snprintf(exr_msg, sizeof exr_msg, "%s (%s)", msg ? msg : "", exr_get_error_code_as_string(code));
}

static int64_t on_exr_write(exr_const_context_t ctxt, void *ud, const void *buf, uint64_t sz,
                            uint64_t offset, exr_stream_error_func_ptr_t error_cb) {
  exr_sink *s = ud;
  const uint8_t *p = buf;
  uint64_t done = 0;
  while (done < sz) {
    ssize_t w = pwrite(s->fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      if (!s->err) s->err = w < 0 ? errno : EIO;
      error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed: %s", strerror(s->err));
      return -1;
    }
    done += (uint64_t)w;
  }
  return (int64_t)sz;
}

/* The two in-plane axes of a slice normal to `axis`, in (width, height) order. */
static void plane_axes(sessile_axis axis, int *u, int *v) {
  *u = axis == SESSILE_AXIS_X ? 1 : 0;
  *v = axis == SESSILE_AXIS_Z ? 1 : 2;
}

/* Fills img[c][x + w y] with the slice values as float32. */
static void sample_slice(const sessile_box *b, int axis, double value, int nchan,
                         const sessile_slice_channel *chan, float **img) {
  int u, v;
  plane_axes((sessile_axis)axis, &u, &v);
  double t = (value - b->origin[axis]) / b->h;
  double layers = (double)(b->n[axis] - 1);
  if (t < 0) t = 0;
  if (t > layers) t = layers;
  uint32_t k0 = (uint32_t)floor(t);
  if (k0 > b->n[axis] - 2) k0 = b->n[axis] - 2;
  double f = t - k0;
  uint32_t w = b->n[u], h = b->n[v];
  for (uint32_t y = 0; y < h; y++)
    for (uint32_t x = 0; x < w; x++) {
      uint32_t ijk[3];
      ijk[u] = x;
      ijk[v] = y;
      ijk[axis] = k0;
      uint32_t n0 = sessile_box_index(b, ijk[0], ijk[1], ijk[2]);
      ijk[axis] = k0 + 1;
      uint32_t n1 = sessile_box_index(b, ijk[0], ijk[1], ijk[2]);
      for (int c = 0; c < nchan; c++)
        img[c][(size_t)y * w + x] = (float)((1.0 - f) * chan[c].field[n0] + f * chan[c].field[n1]);
    }
}

#define EXR_TRY(call, what)                                                                       \
  do {                                                                                            \
    exr_result_t r_ = (call);                                                                     \
    if (r_ != EXR_ERR_SUCCESS) {                                                                  \
      st = sink.err ? sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", path,            \
                                        strerror(sink.err))                                       \
                    : sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': OpenEXR %s failed: %s", \
                                        path, what,                                               \
                                        exr_msg[0] ? exr_msg : exr_get_error_code_as_string(r_)); \
      goto done;                                                                                  \
    }                                                                                             \
  } while (0)

/* Header attributes: the box slice writes the first four, a general plane
 * also the two axes. */
typedef struct exr_attrs {
  const char *plane;
  double origin[3], spacing[2];
  int iteration;
  int has_axes;
  double axis_u[3], axis_v[3];
} exr_attrs;

/* nchan float images of w x h pixels (freed with free_images). */
static float **alloc_images(const char *path, int nchan, uint32_t w, uint32_t h) {
  float **img = calloc((size_t)nchan, sizeof *img);
  for (int c = 0; img && c < nchan; c++) {
    img[c] = malloc((size_t)w * h * sizeof(float));
    if (!img[c]) {
      for (int d = 0; d < c; d++) free(img[d]);
      free(img);
      img = NULL;
    }
  }
  if (!img) sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  return img;
}

static void free_images(float **img, int nchan) {
  for (int c = 0; img && c < nchan; c++) free(img[c]);
  free(img);
}

/* The colour view's channels, after the data's; half is enough for colours. */
static const char *const view_names[3] = {"R", "G", "B"};

/* The file: nchan float channels names[c], then the three half view
 * channels, from img[c] (rows already top-down). */
static sessile_status encode(const char *path, uint32_t w, uint32_t h, int nchan, const char *const *names,
                             float *const *img, const exr_attrs *at, const exr_view *view) {
  sessile_status st = SESSILE_OK;
  exr_sink sink = {-1, 0};
  exr_context_t ctx = NULL;
  exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
  int enc_live = 0;

  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sink.fd = fileno(af.f);
  exr_msg[0] = 0;

  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.user_data = &sink;
  init.write_fn = on_exr_write;
  init.error_handler_fn = on_exr_error;
  /* the name is informational with a write_fn; give the temporary so that
   * nothing OpenEXR does on failure can touch an existing file at path */
  EXR_TRY(exr_start_write(&ctx, af.tmp, EXR_WRITE_FILE_DIRECTLY, &init), "start_write");
  int part = 0;
  EXR_TRY(exr_add_part(ctx, "slice", EXR_STORAGE_SCANLINE, &part), "add_part");
  EXR_TRY(exr_initialize_required_attr_simple(ctx, part, (int32_t)w, (int32_t)h, EXR_COMPRESSION_ZIP),
          "initialize_required_attr");
  /* explicit level: the library default can be changed process-wide */
  EXR_TRY(exr_set_zip_compression_level(ctx, part, 6), "set_zip_compression_level");
  for (int c = 0; c < nchan + 3; c++)
    EXR_TRY(exr_add_channel(ctx, part, names[c], c < nchan ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF,
                            EXR_PERCEPTUALLY_LINEAR, 1, 1),
            "add_channel");
  EXR_TRY(exr_attr_set_string(ctx, part, "sessile:plane", at->plane), "set sessile:plane");
  exr_attr_v3f_t origin = {.x = (float)at->origin[0], .y = (float)at->origin[1], .z = (float)at->origin[2]};
  EXR_TRY(exr_attr_set_v3f(ctx, part, "sessile:origin", &origin), "set sessile:origin");
  exr_attr_v2f_t spacing = {.x = (float)at->spacing[0], .y = (float)at->spacing[1]};
  EXR_TRY(exr_attr_set_v2f(ctx, part, "sessile:spacing", &spacing), "set sessile:spacing");
  EXR_TRY(exr_attr_set_int(ctx, part, "sessile:iteration", at->iteration), "set sessile:iteration");
  EXR_TRY(exr_attr_set_string(ctx, part, "sessile:row_order", "top-down"), "set sessile:row_order");
  EXR_TRY(exr_attr_set_string(ctx, part, "sessile:view_channel", names[0]), "set sessile:view_channel");
  EXR_TRY(exr_attr_set_string(ctx, part, "sessile:view_colormap", view->map), "set sessile:view_colormap");
  exr_attr_v2d_t range = {.x = view->lo, .y = view->hi};
  EXR_TRY(exr_attr_set_v2d(ctx, part, "sessile:view_range", &range), "set sessile:view_range");
  if (at->has_axes) {
    exr_attr_v3f_t au = {.x = (float)at->axis_u[0], .y = (float)at->axis_u[1], .z = (float)at->axis_u[2]};
    exr_attr_v3f_t av = {.x = (float)at->axis_v[0], .y = (float)at->axis_v[1], .z = (float)at->axis_v[2]};
    EXR_TRY(exr_attr_set_v3f(ctx, part, "sessile:axis_u", &au), "set sessile:axis_u");
    EXR_TRY(exr_attr_set_v3f(ctx, part, "sessile:axis_v", &av), "set sessile:axis_v");
  }
  EXR_TRY(exr_write_header(ctx), "write_header");

  int32_t lines = 1;
  EXR_TRY(exr_get_scanlines_per_chunk(ctx, part, &lines), "get_scanlines_per_chunk");
  for (int32_t y = 0; y < (int32_t)h; y += lines) {
    exr_chunk_info_t ci;
    EXR_TRY(exr_write_scanline_chunk_info(ctx, part, y, &ci), "write_scanline_chunk_info");
    if (!enc_live) {
      EXR_TRY(exr_encoding_initialize(ctx, part, &ci, &enc), "encoding_initialize");
      enc_live = 1;
    } else EXR_TRY(exr_encoding_update(ctx, part, &ci, &enc), "encoding_update");
    for (int k = 0; k < enc.channel_count; k++) {
      exr_coding_channel_info_t *ch = &enc.channels[k];
      int c = 0;
      while (c < nchan + 3 && strcmp(names[c], ch->channel_name) != 0) c++;
      if (c == nchan + 3) {
        st = sessile_error_set(SESSILE_ERR_INTERNAL, "writing '%s': OpenEXR reports channel '%s'",
                               path, ch->channel_name);
        goto done;
      }
      ch->user_pixel_stride = 4;
      ch->user_line_stride = 4 * (int32_t)w;
      ch->user_bytes_per_element = 4;
      ch->user_data_type = EXR_PIXEL_FLOAT;
      ch->encode_from_ptr = (const uint8_t *)(img[c] + (size_t)y * w);
    }
    if (y == 0) EXR_TRY(exr_encoding_choose_default_routines(ctx, part, &enc), "choose_default_routines");
    EXR_TRY(exr_encoding_run(ctx, part, &enc), "encoding_run");
  }
  if (enc_live) exr_encoding_destroy(ctx, &enc);
  enc_live = 0;
  {
    exr_result_t r = exr_finish(&ctx);
    ctx = NULL;
    if (r != EXR_ERR_SUCCESS) {
      st = sessile_error_set(SESSILE_ERR_IO, "cannot write '%s': %s", path,
                             sink.err ? strerror(sink.err) : exr_get_error_code_as_string(r));
      goto done;
    }
  }
done:
  if (enc_live) exr_encoding_destroy(ctx, &enc);
  if (ctx) exr_finish(&ctx);
  if (st == SESSILE_OK) st = sessile_atomic_commit(&af);
  else sessile_atomic_abort(&af);
  return st;
}

/* The shared encoder: img[c][x + w j] (float32, row j = 0 at the plane's
 * low v) for channels names[c], plus the colour view of img[0], into one
 * ZIP scanline part "slice", top row first, atomically.  Flips img's rows. */
static sessile_status write_exr_image(const char *path, uint32_t w, uint32_t h, int nchan,
                                      const char *const *names, float *const *img, const exr_attrs *at) {
  float **all = calloc((size_t)nchan + 3, sizeof *all), **rgb = NULL;
  if (all) rgb = alloc_images(path, 3, w, h);
  if (!rgb) {
    free(all);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  }
  exr_view view;
  exr_view_pick(img[0], (size_t)w * h, &view);
  exr_view_fill(&view, img[0], (size_t)w * h, rgb[0], rgb[1], rgb[2]);
  const char *nm[64 + 3];
  for (int c = 0; c < nchan + 3; c++) {
    all[c] = c < nchan ? img[c] : rgb[c - nchan];
    nm[c] = c < nchan ? names[c] : view_names[c - nchan];
    io_flip_rows(all[c], w, h); /* plane row j to EXR row h - 1 - j */
  }
  sessile_status st = encode(path, w, h, nchan, nm, all, at, &view);
  free_images(rgb, 3);
  free(all);
  return st;
}

/* Channel names: 1..64, non-empty, unique. */
static sessile_status check_channels(const char *path, int nchan, const char *const *names) {
  SESSILE_CHECK(nchan >= 1 && nchan <= 64 && names, SESSILE_ERR_USAGE,
                "cannot write '%s': a slice needs 1..64 channels (got %d)", path, nchan);
  for (int c = 0; c < nchan; c++) {
    SESSILE_CHECK(names[c] && names[c][0], SESSILE_ERR_USAGE, "cannot write '%s': channel %d needs a name",
                  path, c);
    SESSILE_CHECK(strcmp(names[c], "R") && strcmp(names[c], "G") && strcmp(names[c], "B"), SESSILE_ERR_USAGE,
                  "cannot write '%s': channel names R, G and B are the colour view's", path);
    for (int d = 0; d < c; d++)
      SESSILE_CHECK(strcmp(names[c], names[d]) != 0, SESSILE_ERR_USAGE,
                    "cannot write '%s': channel name '%s' appears twice", path, names[c]);
  }
  return SESSILE_OK;
}

sessile_status sessile_write_slice_exr(const char *path, const sessile_box *box, sessile_axis axis,
                                       double value, int nchan, const sessile_slice_channel *chan,
                                       int iteration) {
  static const char axis_name[3] = {'x', 'y', 'z'};
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a slice: no path given");
  SESSILE_CHECK(box && axis >= SESSILE_AXIS_X && axis <= SESSILE_AXIS_Z, SESSILE_ERR_USAGE,
                "cannot write '%s': slice axis must be x, y or z", path);
  SESSILE_CHECK(nchan >= 1 && nchan <= 64 && chan, SESSILE_ERR_USAGE,
                "cannot write '%s': a slice needs 1..64 channels (got %d)", path, nchan);
  const char *names[64];
  for (int c = 0; c < nchan; c++) {
    SESSILE_CHECK(chan[c].name && chan[c].name[0] && chan[c].field, SESSILE_ERR_USAGE,
                  "cannot write '%s': channel %d needs a name and a field", path, c);
    names[c] = chan[c].name;
  }
  SESSILE_CALL(check_channels(path, nchan, names));
  double mx[3];
  sessile_box_max(box, mx);
  double lo = box->origin[axis], hi = mx[axis], tol = 1e-9 * box->h;
  SESSILE_CHECK(value >= lo - tol && value <= hi + tol, SESSILE_ERR_USAGE,
                "cannot write '%s': plane %c=%g is outside the box (%c from %g to %g)", path,
                axis_name[axis], value, axis_name[axis], lo, hi);
  int u, v;
  plane_axes(axis, &u, &v);
  uint32_t w = box->n[u], h = box->n[v];
  SESSILE_CHECK(w <= INT32_MAX && h <= INT32_MAX, SESSILE_ERR_TOO_LARGE,
                "cannot write '%s': slice of %u x %u pixels is too large for EXR", path, w, h);

  float **img = alloc_images(path, nchan, w, h);
  if (!img) return SESSILE_ERR_NO_MEMORY;
  sample_slice(box, axis, value, nchan, chan, img);
  exr_attrs at = {.spacing = {box->h, box->h}, .iteration = iteration};
  char plane[64];
  snprintf(plane, sizeof plane, "%c=%.9g", axis_name[axis], value);
  at.plane = plane;
  for (int a = 0; a < 3; a++) at.origin[a] = box->origin[a];
  at.origin[axis] = value;
  sessile_status st = write_exr_image(path, w, h, nchan, names, img, &at);
  free_images(img, nchan);
  return st;
}

/* Checks the plane and fills the header attributes (unit axes). */
static sessile_status check_plane(const char *path, const sessile_plane *pl, const char *label,
                                  exr_attrs *at) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a slice: no path given");
  SESSILE_CHECK(pl, SESSILE_ERR_USAGE, "cannot write '%s': no plane given", path);
  SESSILE_CHECK(pl->width >= 1 && pl->height >= 1, SESSILE_ERR_USAGE,
                "cannot write '%s': the plane has %u x %u pixels (at least 1 x 1 needed)", path, pl->width,
                pl->height);
  SESSILE_CHECK(pl->width <= INT32_MAX && pl->height <= INT32_MAX &&
                    (uint64_t)pl->width * pl->height <= (1ull << 31),
                SESSILE_ERR_USAGE, "cannot write '%s': slice of %u x %u pixels is too large", path,
                pl->width, pl->height);
  int finite = 1;
  for (int a = 0; a < 3; a++)
    finite &= isfinite(pl->origin[a]) && isfinite(pl->axis_u[a]) && isfinite(pl->axis_v[a]);
  SESSILE_CHECK(finite, SESSILE_ERR_USAGE, "cannot write '%s': the plane's origin or axes are not finite", path);
  SESSILE_CHECK(isfinite(pl->spacing[0]) && isfinite(pl->spacing[1]) && pl->spacing[0] > 0 && pl->spacing[1] > 0,
                SESSILE_ERR_USAGE, "cannot write '%s': the pixel spacing (%g, %g) must be positive", path,
                pl->spacing[0], pl->spacing[1]);
  double lu = 0, lv = 0, dot = 0;
  for (int a = 0; a < 3; a++) {
    lu += pl->axis_u[a] * pl->axis_u[a];
    lv += pl->axis_v[a] * pl->axis_v[a];
    dot += pl->axis_u[a] * pl->axis_v[a];
  }
  lu = sqrt(lu), lv = sqrt(lv);
  SESSILE_CHECK(lu > 0 && lv > 0 && isfinite(lu) && isfinite(lv), SESSILE_ERR_USAGE,
                "cannot write '%s': the plane's axes must be non-zero", path);
  SESSILE_CHECK(fabs(dot / lu / lv) <= 1e-6, SESSILE_ERR_USAGE,
                "cannot write '%s': the plane's axes are not perpendicular (cos %g)", path, dot / lu / lv);
  SESSILE_CHECK(!label || strlen(label) < 1024, SESSILE_ERR_USAGE,
                "cannot write '%s': the plane label is longer than 1023 characters", path);
  *at = (exr_attrs){.plane = label ? label : "plane", .has_axes = 1};
  for (int a = 0; a < 3; a++) {
    at->origin[a] = pl->origin[a];
    at->axis_u[a] = pl->axis_u[a] / lu;
    at->axis_v[a] = pl->axis_v[a] / lv;
  }
  at->spacing[0] = pl->spacing[0];
  at->spacing[1] = pl->spacing[1];
  return SESSILE_OK;
}

sessile_status sessile_write_plane_exr(const char *path, const sessile_plane *plane, const char *label,
                                       int nchan, const char *const *names,
                                       sessile_plane_sampler sample, void *user, int iteration) {
  exr_attrs at;
  SESSILE_CALL(check_plane(path, plane, label, &at));
  SESSILE_CALL(check_channels(path, nchan, names));
  SESSILE_CHECK(sample, SESSILE_ERR_USAGE, "cannot write '%s': no sampler given", path);
  at.iteration = iteration;
  uint32_t w = plane->width, h = plane->height;
  float **img = alloc_images(path, nchan, w, h);
  if (!img) return SESSILE_ERR_NO_MEMORY;
  for (uint32_t j = 0; j < h; j++)
    for (uint32_t i = 0; i < w; i++) {
      double p[3];
      for (int a = 0; a < 3; a++)
        p[a] = at.origin[a] + i * at.spacing[0] * at.axis_u[a] + j * at.spacing[1] * at.axis_v[a];
      for (int c = 0; c < nchan; c++) img[c][(size_t)j * w + i] = (float)sample(user, c, p);
    }
  sessile_status st = write_exr_image(path, w, h, nchan, names, img, &at);
  free_images(img, nchan);
  return st;
}

sessile_status sessile_write_plane_exr_values(const char *path, const sessile_plane *plane,
                                              const char *label, int nchan, const char *const *names,
                                              const double *const *values, int iteration) {
  exr_attrs at;
  SESSILE_CALL(check_plane(path, plane, label, &at));
  SESSILE_CALL(check_channels(path, nchan, names));
  SESSILE_CHECK(values, SESSILE_ERR_USAGE, "cannot write '%s': no pixel values given", path);
  for (int c = 0; c < nchan; c++)
    SESSILE_CHECK(values[c], SESSILE_ERR_USAGE, "cannot write '%s': channel '%s' has no values", path, names[c]);
  at.iteration = iteration;
  uint32_t w = plane->width, h = plane->height;
  float **img = alloc_images(path, nchan, w, h);
  if (!img) return SESSILE_ERR_NO_MEMORY;
  for (int c = 0; c < nchan; c++)
    for (size_t q = 0; q < (size_t)w * h; q++) img[c][q] = (float)values[c][q];
  sessile_status st = write_exr_image(path, w, h, nchan, names, img, &at);
  free_images(img, nchan);
  return st;
}
