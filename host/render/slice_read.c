/* sessile render — reads one of sessile's EXR slices (docs/io.md "Slices"):
 * part "slice", float channels, sessile:plane/origin/spacing/iteration and,
 * for a general plane, sessile:axis_u/axis_v.  Any other EXR is refused with
 * a message saying so, rather than drawn with made-up axes. */
#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "slice_internal.h"

static _Thread_local char exr_msg[256];

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  (void)ctxt;
  if (!exr_msg[0]) snprintf(exr_msg, sizeof exr_msg, "%s (%s)", msg ? msg : "", exr_get_error_code_as_string(code));
}

void slice_image_free(slice_image *im) {
  free(im->val);
  free(im->aux);
  im->val = im->aux = NULL;
}

/* The channel list as "a, b, c" for messages. */
static void channel_list(const exr_attr_chlist_t *cl, char *buf, size_t n) {
  buf[0] = 0;
  for (int c = 0; cl && c < cl->num_channels; c++) {
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s%s", c ? ", " : "", cl->entries[c].name.str);
  }
}

static int find_channel(const exr_attr_chlist_t *cl, const char *name) {
  for (int c = 0; cl && name && c < cl->num_channels; c++)
    if (!strcmp(cl->entries[c].name.str, name)) return c;
  return -1;
}

/* The in-plane axes of a box slice "x=..", "y=..", "z=.." (exr_slice.c). */
static int box_axes(const char *plane, int *normal, int *u, int *v) {
  if (!plane || (plane[0] != 'x' && plane[0] != 'y' && plane[0] != 'z') || plane[1] != '=') return 0;
  *normal = plane[0] - 'x';
  *u = *normal == 0 ? 1 : 0;
  *v = *normal == 2 ? 1 : 2;
  return 1;
}

#define FAIL(status, ...)                              \
  do {                                                 \
    st = sessile_error_set((status), __VA_ARGS__);     \
    goto done;                                         \
  } while (0)

sessile_status slice_read(const char *path, const char *channel, const sessile_render2d_opts *o, slice_image *im) {
  memset(im, 0, sizeof *im);
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "no slice file given");
  SESSILE_CHECK(channel && channel[0], SESSILE_ERR_USAGE, "no channel given for '%s'", path);
  SESSILE_CHECK(access(path, R_OK) == 0, SESSILE_ERR_USAGE, "cannot read '%s': %s", path, strerror(errno));
  sessile_status st = SESSILE_OK;
  exr_context_t ctx = NULL;
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int dec_live = 0;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = on_exr_error; /* OpenEXR's words go into our message, not to stderr */
  exr_msg[0] = 0;
  if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
    ctx = NULL;
    FAIL(SESSILE_ERR_USAGE, "'%s' is not an EXR file that OpenEXR can read: %s", path, exr_msg);
  }
  int parts = 0;
  const char *pname = NULL;
  exr_storage_t storage;
  exr_get_count(ctx, &parts);
  if (parts != 1 || exr_get_name(ctx, 0, &pname) != EXR_ERR_SUCCESS || !pname || strcmp(pname, "slice") ||
      exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE)
    FAIL(SESSILE_ERR_USAGE, "'%s' is not a sessile slice (one scanline part named 'slice' expected)", path);
  const char *plane = NULL;
  int32_t plen = 0;
  exr_attr_v3f_t org, au, av;
  exr_attr_v2f_t sp;
  if (exr_attr_get_string(ctx, 0, "sessile:plane", &plen, &plane) != EXR_ERR_SUCCESS ||
      exr_attr_get_v3f(ctx, 0, "sessile:origin", &org) != EXR_ERR_SUCCESS ||
      exr_attr_get_v2f(ctx, 0, "sessile:spacing", &sp) != EXR_ERR_SUCCESS)
    FAIL(SESSILE_ERR_USAGE, "'%s' is not a sessile slice (no sessile:plane, sessile:origin or sessile:spacing)", path);
  snprintf(im->plane, sizeof im->plane, "%.*s", (int)plen, plane);
  int32_t it = -1;
  if (exr_attr_get_int(ctx, 0, "sessile:iteration", &it) == EXR_ERR_SUCCESS) im->iteration = it;
  else im->iteration = -1;
  if (!(sp.x > 0 && sp.y > 0 && isfinite(sp.x) && isfinite(sp.y)))
    FAIL(SESSILE_ERR_USAGE, "'%s': sessile:spacing (%g, %g) is not positive", path, sp.x, sp.y);
  im->su = sp.x, im->sv = sp.y;
  double o3[3] = {org.x, org.y, org.z};
  memcpy(im->origin, o3, sizeof o3);
  int nu, u, v;
  if (exr_attr_get_v3f(ctx, 0, "sessile:axis_u", &au) == EXR_ERR_SUCCESS &&
      exr_attr_get_v3f(ctx, 0, "sessile:axis_v", &av) == EXR_ERR_SUCCESS) {
    double a[3] = {au.x, au.y, au.z}, b[3] = {av.x, av.y, av.z};
    memcpy(im->axis_u, a, sizeof a);
    memcpy(im->axis_v, b, sizeof b);
    strcpy(im->uname, "u");
    strcpy(im->vname, "v");
    im->u0 = im->v0 = 0; /* distances from the plane's origin along its axes */
  } else if (box_axes(im->plane, &nu, &u, &v)) {
    im->axis_u[u] = 1;
    im->axis_v[v] = 1;
    snprintf(im->uname, sizeof im->uname, "%c", 'x' + u);
    snprintf(im->vname, sizeof im->vname, "%c", 'x' + v);
    im->u0 = o3[u], im->v0 = o3[v]; /* world coordinates along the two axes */
  } else
    FAIL(SESSILE_ERR_USAGE, "'%s' is not a sessile slice (plane '%s' without sessile:axis_u/axis_v)", path, im->plane);
  im->normal[0] = im->axis_u[1] * im->axis_v[2] - im->axis_u[2] * im->axis_v[1];
  im->normal[1] = im->axis_u[2] * im->axis_v[0] - im->axis_u[0] * im->axis_v[2];
  im->normal[2] = im->axis_u[0] * im->axis_v[1] - im->axis_u[1] * im->axis_v[0];

  const exr_attr_chlist_t *cl = NULL;
  exr_get_channels(ctx, 0, &cl);
  char names[1024];
  channel_list(cl, names, sizeof names);
  int want = find_channel(cl, channel);
  if (want < 0) FAIL(SESSILE_ERR_USAGE, "'%s' has no channel '%s' (channels: %s)", path, channel, names);
  /* the outline channel: asked for, or a known name when present */
  int aux = -1;
  if (o && o->outline_channel && o->outline_channel[0] && !(o->outline_ply && o->outline_ply[0])) {
    aux = find_channel(cl, o->outline_channel);
    if (aux < 0)
      FAIL(SESSILE_ERR_USAGE, "'%s' has no outline channel '%s' (channels: %s)", path, o->outline_channel, names);
    im->aux_level = o->outline_level;
  } else if (!(o && o->outline_ply && o->outline_ply[0])) {
    static const char *known[4] = {"solid", "mask", "phi", "sdf"};
    static const double level[4] = {0.5, 0.5, 0, 0};
    for (int k = 0; k < 4 && aux < 0; k++)
      if ((aux = find_channel(cl, known[k])) >= 0) im->aux_level = level[k];
  }
  if (aux >= 0) snprintf(im->aux_name, sizeof im->aux_name, "%s", cl->entries[aux].name.str);
  for (int c = 0; c < cl->num_channels; c++)
    if ((c == want || c == aux) && cl->entries[c].pixel_type != EXR_PIXEL_FLOAT &&
        cl->entries[c].pixel_type != EXR_PIXEL_HALF)
      FAIL(SESSILE_ERR_USAGE, "'%s': channel '%s' is not a float channel", path, cl->entries[c].name.str);

  exr_attr_box2i_t dw;
  if (exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS) FAIL(SESSILE_ERR_USAGE, "'%s': no data window", path);
  int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
  if (w < 1 || h < 1 || w > 65536 || h > 65536 || w * h > (1ll << 28))
    FAIL(SESSILE_ERR_USAGE, "'%s': a slice of %lld x %lld pixels is outside what sessile renders (65536 a side, 2^28 in all)",
         path, (long long)w, (long long)h);
  im->w = (int)w, im->h = (int)h;
  im->val = malloc((size_t)w * h * sizeof(float));
  if (aux >= 0) im->aux = malloc((size_t)w * h * sizeof(float));
  if (!im->val || (aux >= 0 && !im->aux))
    FAIL(SESSILE_ERR_NO_MEMORY, "out of memory reading '%s' (%.0f MB)", path, 8.0 * w * h / 1e6);

  int32_t lines = 1;
  exr_get_scanlines_per_chunk(ctx, 0, &lines);
  for (int y = 0; y < im->h; y += lines) {
    exr_chunk_info_t ci;
    exr_result_t r = exr_read_scanline_chunk_info(ctx, 0, dw.min.y + y, &ci);
    if (r == EXR_ERR_SUCCESS && !dec_live) {
      r = exr_decoding_initialize(ctx, 0, &ci, &dec);
      dec_live = r == EXR_ERR_SUCCESS;
    } else if (r == EXR_ERR_SUCCESS)
      r = exr_decoding_update(ctx, 0, &ci, &dec);
    if (r != EXR_ERR_SUCCESS) FAIL(SESSILE_ERR_USAGE, "cannot decode '%s': %s", path, exr_msg[0] ? exr_msg : exr_get_error_code_as_string(r));
    for (int k = 0; k < dec.channel_count; k++) {
      exr_coding_channel_info_t *ch = &dec.channels[k];
      float *dst = !strcmp(ch->channel_name, channel) ? im->val
                   : (aux >= 0 && !strcmp(ch->channel_name, cl->entries[aux].name.str)) ? im->aux
                                                                                         : NULL;
      /* EXR row 0 is the slice's row 0 (the low end of v) */
      ch->decode_to_ptr = dst ? (uint8_t *)(dst + (size_t)(ci.start_y - dw.min.y) * w) : NULL;
      ch->user_pixel_stride = 4;
      ch->user_line_stride = 4 * (int32_t)w;
      ch->user_bytes_per_element = 4;
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    r = exr_decoding_choose_default_routines(ctx, 0, &dec);
    if (r == EXR_ERR_SUCCESS) r = exr_decoding_run(ctx, 0, &dec);
    if (r != EXR_ERR_SUCCESS) FAIL(SESSILE_ERR_USAGE, "cannot decode '%s': %s", path, exr_msg[0] ? exr_msg : exr_get_error_code_as_string(r));
  }
done:
  if (dec_live) exr_decoding_destroy(ctx, &dec);
  if (ctx) exr_finish(&ctx);
  if (st != SESSILE_OK) slice_image_free(im);
  return st;
}

sessile_status sessile_render_slice_channels(const char *path, char *names, size_t n) {
  SESSILE_CHECK(names && n > 0, SESSILE_ERR_INTERNAL, "no room for the channel names");
  names[0] = 0;
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "no slice file given");
  SESSILE_CHECK(access(path, R_OK) == 0, SESSILE_ERR_USAGE, "cannot read '%s': %s", path, strerror(errno));
  sessile_status st = SESSILE_OK;
  exr_context_t ctx = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = on_exr_error;
  exr_msg[0] = 0;
  if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
    ctx = NULL;
    FAIL(SESSILE_ERR_USAGE, "'%s' is not an EXR file that OpenEXR can read: %s", path, exr_msg);
  }
  int parts = 0;
  const char *pname = NULL, *plane = NULL;
  int32_t plen = 0;
  exr_get_count(ctx, &parts);
  if (parts != 1 || exr_get_name(ctx, 0, &pname) != EXR_ERR_SUCCESS || !pname || strcmp(pname, "slice") ||
      exr_attr_get_string(ctx, 0, "sessile:plane", &plen, &plane) != EXR_ERR_SUCCESS)
    FAIL(SESSILE_ERR_USAGE, "'%s' is not a sessile slice (one part named 'slice' with sessile:plane expected)", path);
  const exr_attr_chlist_t *cl = NULL;
  exr_get_channels(ctx, 0, &cl);
  if (!cl || cl->num_channels < 1) FAIL(SESSILE_ERR_USAGE, "'%s' has no channel", path);
  channel_list(cl, names, n);
done:
  if (ctx) exr_finish(&ctx);
  return st;
}
