/* sessile io — the sponge surface as binary PLY and as OBJ.
 *
 * PLY is the run's mesh format (compact, exact float32, any number of named
 * per-vertex values such as the probed nutrient); OBJ is for tools that read
 * nothing else.  Both are assembled in memory and written in one go. */
#include <ctype.h>
#include <stdlib.h>
#include "io_internal.h"

static int ply_name_ok(const char *s) {
  if (!s || !s[0]) return 0;
  for (; *s; s++)
    if (!isgraph((unsigned char)*s)) return 0;
  return 1;
}

static sessile_status check_surface(const char *path, const sessile_surface *s) {
  SESSILE_CHECK(s && (s->nv == 0 || s->pos) && (s->nf == 0 || s->tri), SESSILE_ERR_USAGE,
                "cannot write '%s': the surface has no vertex or triangle arrays", path);
  for (uint64_t q = 0; q < 3ull * s->nf; q++)
    SESSILE_CHECK(s->tri[q] < s->nv, SESSILE_ERR_USAGE,
                  "cannot write '%s': triangle %llu refers to vertex %u of %u", path,
                  (unsigned long long)(q / 3), s->tri[q], s->nv);
  return SESSILE_OK;
}

sessile_status sessile_write_ply(const char *path, const sessile_surface *s, const double *normals,
                                 int nextra, const char *const *extra_names,
                                 const double *const *extra) {
  SESSILE_CALL(check_surface(path, s));
  SESSILE_CHECK(nextra >= 0 && nextra <= 64 && (nextra == 0 || (extra_names && extra)),
                SESSILE_ERR_USAGE, "cannot write '%s': %d extra vertex properties (0..64 allowed)",
                path, nextra);
  for (int p = 0; p < nextra; p++)
    SESSILE_CHECK(ply_name_ok(extra_names[p]) && extra[p], SESSILE_ERR_USAGE,
                  "cannot write '%s': extra property %d needs a name without spaces and values", path, p);
  int nfloat = 3 + (normals ? 3 : 0) + nextra;
  size_t vbytes = (size_t)s->nv * 4 * (size_t)nfloat, fbytes = (size_t)s->nf * 13;
  uint8_t *buf = malloc(vbytes + fbytes + 1);
  SESSILE_CHECK(buf, SESSILE_ERR_NO_MEMORY, "out of memory writing '%s' (%zu bytes)", path,
                vbytes + fbytes);
  uint8_t *w = buf;
  for (uint32_t v = 0; v < s->nv; v++) {
    for (int a = 0; a < 3; a++) w = io_put_f32(w, s->pos[3 * (size_t)v + a]);
    if (normals)
      for (int a = 0; a < 3; a++) w = io_put_f32(w, normals[3 * (size_t)v + a]);
    for (int p = 0; p < nextra; p++) w = io_put_f32(w, extra[p][v]);
  }
  for (uint32_t f = 0; f < s->nf; f++) {
    *w++ = 3;
    for (int c = 0; c < 3; c++) w = io_put_u32(w, s->tri[3 * (size_t)f + c]);
  }

  sessile_atomic_file af;
  sessile_status st = sessile_atomic_open(path, &af);
  if (st != SESSILE_OK) {
    free(buf);
    return st;
  }
  st = io_printf(&af, "ply\nformat binary_little_endian 1.0\ncomment sessile sponge surface\n"
                      "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n",
                 s->nv);
  if (st == SESSILE_OK && normals)
    st = io_printf(&af, "property float nx\nproperty float ny\nproperty float nz\n");
  for (int p = 0; p < nextra && st == SESSILE_OK; p++)
    st = io_printf(&af, "property float %s\n", extra_names[p]);
  if (st == SESSILE_OK)
    st = io_printf(&af, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", s->nf);
  if (st == SESSILE_OK) st = io_write(&af, buf, (size_t)(w - buf));
  free(buf);
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

/* The shortest of %.15g..%.17g that reads back as the same double, so OBJ
 * coordinates are exact yet stay short ("0.1", not "0.10000000000000001"). */
static void fmt_exact(char *out, size_t n, double v) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(out, n, "%.*g", prec, v);
    if (strtod(out, NULL) == v) return;
  }
}

sessile_status sessile_write_obj(const char *path, const sessile_surface *s, const double *normals) {
  SESSILE_CALL(check_surface(path, s));
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "# sessile sponge surface: %u vertices, %u triangles\n", s->nv, s->nf);
  char x[3][32];
  for (uint32_t v = 0; v < s->nv && st == SESSILE_OK; v++) {
    for (int a = 0; a < 3; a++) fmt_exact(x[a], sizeof x[a], s->pos[3 * (size_t)v + a]);
    st = io_printf(&af, "v %s %s %s\n", x[0], x[1], x[2]);
  }
  for (uint32_t v = 0; normals && v < s->nv && st == SESSILE_OK; v++) {
    for (int a = 0; a < 3; a++) fmt_exact(x[a], sizeof x[a], normals[3 * (size_t)v + a]);
    st = io_printf(&af, "vn %s %s %s\n", x[0], x[1], x[2]);
  }
  for (uint32_t f = 0; f < s->nf && st == SESSILE_OK; f++) {
    const uint32_t *t = s->tri + 3 * (size_t)f;
    if (normals)
      st = io_printf(&af, "f %u//%u %u//%u %u//%u\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1,
                     t[2] + 1, t[2] + 1);
    else st = io_printf(&af, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}
