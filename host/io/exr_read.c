/* The EXR slice reader (sessile/io/io_read.h), through OpenEXR's C API.  The
 * file is opened here (O_NONBLOCK, regular files only: a FIFO named as a
 * slice is refused, never waited on) and OpenEXR reads it through pread on
 * that descriptor; OpenEXR's messages go into ours, not to stderr. */
#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "io_internal.h"

struct sessile_exr_in {
  const char *path;
  int fd;
  uint64_t size;
  exr_context_t ctx;
  const exr_attr_chlist_t *cl;
  exr_attr_box2i_t dw;
  sessile_slice_header h;
};

static _Thread_local char exr_msg[256];

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  (void)ctxt;
  if (!exr_msg[0]) snprintf(exr_msg, sizeof exr_msg, "%s (%s)", msg ? msg : "", exr_get_error_code_as_string(code));
}

static int64_t read_fd(exr_const_context_t ctxt, void *user, void *buffer, uint64_t sz, uint64_t offset,
                       exr_stream_error_func_ptr_t error_cb) {
  const sessile_exr_in *x = user;
  uint64_t done = 0;
  while (done < sz) {
    ssize_t k = pread(x->fd, (char *)buffer + done, sz - done, (off_t)(offset + done));
    if (k < 0 && errno == EINTR) continue;
    if (k < 0) {
      error_cb(ctxt, EXR_ERR_READ_IO, "read failed: %s", strerror(errno));
      return -1;
    }
    if (k == 0) break;
    done += (uint64_t)k;
  }
  return (int64_t)done;
}

static int64_t size_fd(exr_const_context_t ctxt, void *user) {
  (void)ctxt;
  return (int64_t)((const sessile_exr_in *)user)->size;
}

/* The sessile attributes into the header (absent ones flagged). */
static void read_attributes(sessile_exr_in *x) {
  sessile_slice_header *h = &x->h;
  exr_attr_v3f_t o, au, av;
  exr_attr_v2f_t sp;
  int32_t it = -1;
  exr_storage_t storage;
  h->scanline = exr_get_storage(x->ctx, 0, &storage) == EXR_ERR_SUCCESS && storage == EXR_STORAGE_SCANLINE;
  if ((h->has_origin = exr_attr_get_v3f(x->ctx, 0, "sessile:origin", &o) == EXR_ERR_SUCCESS))
    h->origin[0] = o.x, h->origin[1] = o.y, h->origin[2] = o.z;
  if ((h->has_spacing = exr_attr_get_v2f(x->ctx, 0, "sessile:spacing", &sp) == EXR_ERR_SUCCESS))
    h->spacing[0] = sp.x, h->spacing[1] = sp.y;
  h->has_axes = exr_attr_get_v3f(x->ctx, 0, "sessile:axis_u", &au) == EXR_ERR_SUCCESS &&
                exr_attr_get_v3f(x->ctx, 0, "sessile:axis_v", &av) == EXR_ERR_SUCCESS;
  if (h->has_axes) {
    h->axis_u[0] = au.x, h->axis_u[1] = au.y, h->axis_u[2] = au.z;
    h->axis_v[0] = av.x, h->axis_v[1] = av.y, h->axis_v[2] = av.z;
  }
  h->iteration = exr_attr_get_int(x->ctx, 0, "sessile:iteration", &it) == EXR_ERR_SUCCESS ? it : -1;
  /* slices written before the row order was recorded are bottom-up */
  const char *s = NULL;
  int32_t n = 0;
  h->top_down = exr_attr_get_string(x->ctx, 0, "sessile:row_order", &n, &s) == EXR_ERR_SUCCESS &&
                n == 8 && !strncmp(s, "top-down", 8);
  h->has_view = exr_attr_get_string(x->ctx, 0, "sessile:view_channel", &n, &s) == EXR_ERR_SUCCESS;
  if (exr_get_data_window(x->ctx, 0, &x->dw) == EXR_ERR_SUCCESS) {
    h->width = (int64_t)x->dw.max.x - x->dw.min.x + 1;
    h->height = (int64_t)x->dw.max.y - x->dw.min.y + 1;
  }
  exr_get_channels(x->ctx, 0, &x->cl);
  h->nchannels = x->cl ? x->cl->num_channels : 0;
}

/* Opens path (io_open_regular) and OpenEXR's context on it; slice: also
 * requires a sessile slice.  `what` names the file's role in messages. */
static sessile_status exr_open(const char *path, const char *what, int slice, sessile_exr_in **out) {
  *out = NULL;
  sessile_exr_in *x = calloc(1, sizeof *x);
  SESSILE_CHECK(x, SESSILE_ERR_NO_MEMORY, "out of host memory");
  x->path = path;
  sessile_status st = io_open_regular(path, what, &x->fd, &x->size);
  if (st != SESSILE_OK) {
    free(x);
    return st;
  }
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = on_exr_error;
  init.user_data = x;
  init.read_fn = read_fd;
  init.size_fn = size_fd;
  exr_msg[0] = 0;
  int parts = 0;
  const char *pname = NULL, *plane = NULL;
  int32_t plen = 0;
  if (exr_start_read(&x->ctx, path, &init) != EXR_ERR_SUCCESS) {
    x->ctx = NULL;
    st = sessile_error_set(SESSILE_ERR_USAGE, "'%s' is not an EXR file that OpenEXR can read: %s", path, exr_msg);
  } else if (!slice) {
    if (exr_get_count(x->ctx, &parts) != EXR_ERR_SUCCESS || parts != 1)
      st = sessile_error_set(SESSILE_ERR_USAGE, "'%s' has %d parts: one image expected", path, parts);
    else
      read_attributes(x);
  } else if (exr_get_count(x->ctx, &parts) != EXR_ERR_SUCCESS || parts != 1 ||
             exr_get_name(x->ctx, 0, &pname) != EXR_ERR_SUCCESS || !pname || strcmp(pname, "slice") ||
             exr_attr_get_string(x->ctx, 0, "sessile:plane", &plen, &plane) != EXR_ERR_SUCCESS) {
    st = sessile_error_set(SESSILE_ERR_USAGE,
                           "'%s' is not a sessile slice (one part named 'slice' with sessile:plane expected)", path);
  } else {
    snprintf(x->h.plane, sizeof x->h.plane, "%.*s", (int)plen, plane);
    read_attributes(x);
  }
  if (st != SESSILE_OK) {
    sessile_exr_close(x);
    return st;
  }
  *out = x;
  return SESSILE_OK;
}

sessile_status sessile_exr_open(const char *path, sessile_exr_in **out) { return exr_open(path, "slice", 1, out); }

const sessile_slice_header *sessile_exr_header(const sessile_exr_in *x) { return &x->h; }

const char *sessile_exr_channel_name(const sessile_exr_in *x, int c) {
  return x->cl && c >= 0 && c < x->cl->num_channels ? x->cl->entries[c].name.str : "";
}

int sessile_exr_channel_is_float(const sessile_exr_in *x, int c) {
  if (!x->cl || c < 0 || c >= x->cl->num_channels) return 0;
  exr_pixel_type_t t = x->cl->entries[c].pixel_type;
  return t == EXR_PIXEL_FLOAT || t == EXR_PIXEL_HALF;
}

int sessile_exr_find_channel(const sessile_exr_in *x, const char *name) {
  for (int c = 0; x->cl && name && c < x->cl->num_channels; c++)
    if (!strcmp(x->cl->entries[c].name.str, name)) return c;
  return -1;
}

/* Whether channel c is one of the colour view's R, G, B. */
static int is_view(const sessile_exr_in *x, int c) {
  const char *s = x->cl->entries[c].name.str;
  return x->h.has_view && (!strcmp(s, "R") || !strcmp(s, "G") || !strcmp(s, "B"));
}

void sessile_exr_channel_list(const sessile_exr_in *x, char *buf, size_t n) {
  buf[0] = 0;
  for (int c = 0; x->cl && c < x->cl->num_channels; c++) {
    size_t len = strlen(buf);
    if (!is_view(x, c)) snprintf(buf + len, n - len, "%s%s", len ? ", " : "", x->cl->entries[c].name.str);
  }
}

/* The channel of dst that decoded channel `name` goes to, or NULL. */
static float *target(int n, const char *const *names, float *const *dst, const char *name) {
  for (int k = 0; k < n; k++)
    if (names[k] && !strcmp(names[k], name)) return dst[k];
  return NULL;
}

sessile_status sessile_exr_read_channels(sessile_exr_in *x, int n, const char *const *names, float *const *dst) {
  const char *path = x->path;
  int64_t w = x->h.width, h = x->h.height;
  SESSILE_CHECK(x->h.scanline && w >= 1 && h >= 1, SESSILE_ERR_USAGE, "'%s': no scanline image to read", path);
  for (int k = 0; k < n; k++)
    SESSILE_CHECK(sessile_exr_channel_is_float(x, sessile_exr_find_channel(x, names[k])), SESSILE_ERR_USAGE,
                  "'%s': channel '%s' is not a float channel", path, names[k]);
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int dec_live = 0;
  int32_t lines = 1;
  exr_get_scanlines_per_chunk(x->ctx, 0, &lines);
  exr_result_t r = EXR_ERR_SUCCESS;
  exr_msg[0] = 0;
  for (int64_t y = 0; y < h && r == EXR_ERR_SUCCESS; y += lines) {
    exr_chunk_info_t ci;
    r = exr_read_scanline_chunk_info(x->ctx, 0, x->dw.min.y + (int)y, &ci);
    if (r == EXR_ERR_SUCCESS && !dec_live) {
      r = exr_decoding_initialize(x->ctx, 0, &ci, &dec);
      dec_live = r == EXR_ERR_SUCCESS;
    } else if (r == EXR_ERR_SUCCESS)
      r = exr_decoding_update(x->ctx, 0, &ci, &dec);
    if (r != EXR_ERR_SUCCESS) break;
    for (int k = 0; k < dec.channel_count; k++) {
      exr_coding_channel_info_t *ch = &dec.channels[k];
      float *d = target(n, names, dst, ch->channel_name);
      /* EXR rows in file order: a top-down file is flipped after */
      ch->decode_to_ptr = d ? (uint8_t *)(d + (size_t)(ci.start_y - x->dw.min.y) * (size_t)w) : NULL;
      ch->user_pixel_stride = 4;
      ch->user_line_stride = 4 * (int32_t)w;
      ch->user_bytes_per_element = 4;
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    r = exr_decoding_choose_default_routines(x->ctx, 0, &dec);
    if (r == EXR_ERR_SUCCESS) r = exr_decoding_run(x->ctx, 0, &dec);
  }
  if (dec_live) exr_decoding_destroy(x->ctx, &dec);
  SESSILE_CHECK(r == EXR_ERR_SUCCESS, SESSILE_ERR_USAGE, "cannot decode '%s': %s", path,
                exr_msg[0] ? exr_msg : exr_get_error_code_as_string(r));
  for (int k = 0; x->h.top_down && k < n; k++) io_flip_rows(dst[k], (size_t)w, (size_t)h); /* row 0 at low v */
  return SESSILE_OK;
}

void sessile_exr_close(sessile_exr_in *x) {
  if (!x) return;
  if (x->ctx) exr_finish(&x->ctx);
  if (x->fd >= 0) close(x->fd);
  free(x);
}

sessile_status sessile_read_exr_grey(const char *path, uint32_t max_side, sessile_image_in *out) {
  memset(out, 0, sizeof *out);
  sessile_exr_in *x = NULL;
  SESSILE_CALL(exr_open(path, "EXR", 0, &x));
  const sessile_slice_header *h = &x->h;
  char list[256];
  sessile_exr_channel_list(x, list, sizeof list);
  sessile_status s = SESSILE_OK;
  if (h->nchannels != 1)
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' has %d channels (%s): a heightfield needs one", path,
                          h->nchannels, list);
  else if (!sessile_exr_channel_is_float(x, 0))
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s': channel '%s' is not a float channel", path, list);
  else if (h->width < 2 || h->height < 2)
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' is %lld x %lld pixels: a heightfield needs at least 2 x 2", path,
                          (long long)h->width, (long long)h->height);
  else if (h->width > max_side || h->height > max_side)
    s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' is %lld x %lld pixels (%.0f MiB of heights): more than %u a side",
                          path, (long long)h->width, (long long)h->height,
                          (double)h->width * (double)h->height * sizeof *out->v / 1048576.0, (unsigned)max_side);
  float *f = NULL;
  size_t n = (size_t)h->width * (size_t)h->height;
  if (s == SESSILE_OK && !((f = malloc(n * sizeof *f)) && (out->v = malloc(n * sizeof *out->v))))
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for '%s'", path);
  const char *name = sessile_exr_channel_name(x, 0);
  if (s == SESSILE_OK) s = sessile_exr_read_channels(x, 1, &name, &f);
  for (size_t k = 0; s == SESSILE_OK && k < n; k++) {
    if (!isfinite(f[k]))
      s = sessile_error_set(SESSILE_ERR_USAGE, "'%s': pixel (%zu, %zu) is not finite", path,
                            k % (size_t)h->width, k / (size_t)h->width);
    out->v[k] = f[k];
  }
  if (s == SESSILE_OK) out->width = (uint32_t)h->width, out->height = (uint32_t)h->height;
  free(f);
  sessile_exr_close(x);
  if (s != SESSILE_OK) sessile_image_in_free(out);
  return s;
}
