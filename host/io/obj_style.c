/* sessile io — OBJ's conventions and its material library: the axes and
 * unit an OBJ is written in (sessile's z-up centimetres, or y-up metres for
 * DCC tools), and the one-material .mtl beside it (docs/io.md "OBJ
 * conventions"). */
#include <ctype.h>
#include "io_internal.h"

static const char *const axes_names[2] = {"zup-cm", "yup-m"};

int sessile_obj_axes_parse(const char *name, sessile_obj_axes *out) {
  for (int k = 0; name && k < 2; k++)
    if (!strcmp(name, axes_names[k])) {
      *out = (sessile_obj_axes)k;
      return 0;
    }
  return -1;
}

const char *sessile_obj_axes_name(sessile_obj_axes axes) {
  return axes == SESSILE_OBJ_ZUP_CM || axes == SESSILE_OBJ_YUP_M ? axes_names[axes] : NULL;
}

/* Non-empty, no white space or control characters: one OBJ/MTL token. */
static int token_ok(const char *s) {
  if (!s || !s[0]) return 0;
  for (; *s; s++)
    if (!isgraph((unsigned char)*s)) return 0;
  return 1;
}

sessile_status io_obj_style_check(const char *path, const sessile_obj_style *st) {
  SESSILE_CHECK(sessile_obj_axes_name(st->axes), SESSILE_ERR_USAGE, "cannot write '%s': unknown OBJ axes %d", path,
                (int)st->axes);
  SESSILE_CHECK(!st->mtllib || (token_ok(st->mtllib) && token_ok(st->material)), SESSILE_ERR_USAGE,
                "cannot write '%s': the material library and material need names without spaces", path);
  return SESSILE_OK;
}

sessile_status io_obj_style_lines(sessile_atomic_file *af, const sessile_obj_style *st) {
  sessile_status s = SESSILE_OK;
  if (st->axes == SESSILE_OBJ_YUP_M)
    s = io_printf(af, "# y up, metres (for DCC tools): sessile's (x, y, z) cm written as (x, z, -y) / 100\n");
  if (s == SESSILE_OK && st->mtllib) s = io_printf(af, "mtllib %s\nusemtl %s\n", st->mtllib, st->material);
  return s;
}

sessile_status sessile_write_mtl(const char *path, const char *name, const float rgb[3]) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a material library: no path given");
  SESSILE_CHECK(token_ok(name) && rgb, SESSILE_ERR_USAGE,
                "cannot write '%s': the material needs a name without spaces and a colour", path);
  double c[3];
  for (int k = 0; k < 3; k++) c[k] = rgb[k] > 0 ? (rgb[k] < 1 ? rgb[k] : 1) : 0; /* NaN: 0 */
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  /* Ka 0 and Ks 0: lit by the scene, no highlight; illum 1: diffuse only */
  sessile_status s = io_printf(&af,
                               "# sessile material library\n"
                               "newmtl %s\nKa 0 0 0\nKd %.6g %.6g %.6g\nKs 0 0 0\nd 1\nillum 1\n",
                               name, c[0], c[1], c[2]);
  if (s != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return s;
  }
  return sessile_atomic_commit(&af);
}
