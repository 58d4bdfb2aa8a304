/* sessile io — surfaces as binary PLY and as OBJ: the sponge's one surface,
 * or a union of several parts (one file, indices offset per part).
 *
 * PLY is the run's mesh format (compact, exact float32, any number of named
 * per-vertex values such as the probed nutrient); OBJ is for tools that read
 * nothing else.  Both are assembled in memory and written in one go. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include "io_internal.h"

static int ply_name_ok(const char *s) {
  if (!s || !s[0]) return 0;
  for (; *s; s++)
    if (!isgraph((unsigned char)*s)) return 0;
  return 1;
}

/* A part's name, or "part<k>" when it has none. */
static const char *part_name(const sessile_mesh_part *p, int k, char buf[32]) {
  if (p->name) return p->name;
  snprintf(buf, 32, "part%d", k);
  return buf;
}

sessile_status io_check_parts(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                              const char *const *names, uint32_t *tv, uint32_t *tf, int *with_normals) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a mesh: no path given");
  SESSILE_CHECK(nparts >= 1 && parts, SESSILE_ERR_USAGE, "cannot write '%s': %d surface parts (1 or more needed)",
                path, nparts);
  SESSILE_CHECK(nfields >= 0 && nfields <= 64 && (nfields == 0 || names), SESSILE_ERR_USAGE,
                "cannot write '%s': %d extra vertex properties (0..64 allowed)", path, nfields);
  for (int p = 0; p < nfields; p++) {
    SESSILE_CHECK(ply_name_ok(names[p]), SESSILE_ERR_USAGE,
                  "cannot write '%s': extra property %d needs a name without spaces", path, p);
    for (int q = 0; q < p; q++)
      SESSILE_CHECK(strcmp(names[p], names[q]) != 0, SESSILE_ERR_USAGE,
                    "cannot write '%s': extra property name '%s' appears twice", path, names[p]);
  }
  uint64_t nv = 0, nf = 0;
  int some = 0, all = 1;
  for (int k = 0; k < nparts; k++) {
    const sessile_mesh_part *m = &parts[k];
    char nb[32];
    const char *name = part_name(m, k, nb);
    SESSILE_CHECK(ply_name_ok(name), SESSILE_ERR_USAGE,
                  "cannot write '%s': part %d needs a name without spaces (or NULL)", path, k);
    SESSILE_CHECK((m->nv == 0 || m->pos) && (m->nf == 0 || m->tri), SESSILE_ERR_USAGE,
                  "cannot write '%s': part '%s' has no vertex or triangle arrays", path, name);
    SESSILE_CHECK(m->nf == 0 || m->nv > 0, SESSILE_ERR_USAGE,
                  "cannot write '%s': part '%s' has %u triangles but no vertices", path, name, m->nf);
    for (uint64_t q = 0; q < 3ull * m->nv; q++)
      SESSILE_CHECK(isfinite(m->pos[q]), SESSILE_ERR_USAGE,
                    "cannot write '%s': part '%s' vertex %llu has a non-finite coordinate (%g)", path, name,
                    (unsigned long long)(q / 3), m->pos[q]);
    for (uint64_t q = 0; q < 3ull * m->nf; q++)
      SESSILE_CHECK(m->tri[q] < m->nv, SESSILE_ERR_USAGE,
                    "cannot write '%s': part '%s' triangle %llu refers to vertex %u of %u", path, name,
                    (unsigned long long)(q / 3), m->tri[q], m->nv);
    if (m->nv > 0) {
      some |= m->normals != NULL;
      all &= m->normals != NULL;
      SESSILE_CHECK(nfields == 0 || m->fields, SESSILE_ERR_USAGE,
                    "cannot write '%s': part '%s' gives no values for the %d extra properties", path, name,
                    nfields);
      for (int p = 0; p < nfields; p++)
        SESSILE_CHECK(m->fields[p], SESSILE_ERR_USAGE,
                      "cannot write '%s': part '%s' gives no values for extra property '%s'", path, name,
                      names[p]);
    }
    nv += m->nv;
    nf += m->nf;
  }
  SESSILE_CHECK(!some || all, SESSILE_ERR_USAGE,
                "cannot write '%s': some parts have normals and others not (all or none)", path);
  SESSILE_CHECK(nv <= UINT32_MAX && nf <= UINT32_MAX, SESSILE_ERR_USAGE,
                "cannot write '%s': the union has %llu vertices and %llu triangles (2^32-1 at most)", path,
                (unsigned long long)nv, (unsigned long long)nf);
  *tv = (uint32_t)nv;
  *tf = (uint32_t)nf;
  *with_normals = some;
  return SESSILE_OK;
}

/* A raised stop flag (NULL: none), looked at when k is a multiple of 64 Ki
 * (lines or blocks: a few ms apart). */
static sessile_status stopped(const char *path, const volatile sig_atomic_t *stop, uint64_t k) {
  if (!stop || (k & 0xffff) || !*stop) return SESSILE_OK;
  return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d while writing '%s'", (int)*stop, path);
}

/* The PLY of a union: comment is the header's first comment line; with
 * part_comments, one more comment per part; then info's lines, and with its
 * main scalar, uchar red, green, blue after the floats. */
static sessile_status write_ply_union(const char *path, const char *comment, int part_comments,
                                      int nparts, const sessile_mesh_part *parts, int nextra,
                                      const char *const *extra_names, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop) {
  uint32_t tv, tf;
  int normals, main_field;
  SESSILE_CALL(io_check_parts(path, nparts, parts, nextra, extra_names, &tv, &tf, &normals));
  SESSILE_CALL(io_mesh_info_check(path, info, nextra, extra_names, &main_field));
  uint8_t *rgb = NULL;
  io_mesh_rgb_used used = {0};
  if (main_field >= 0) SESSILE_CALL(io_mesh_rgb(path, nparts, parts, tv, main_field, info->colormap, &rgb, &used));
  int nfloat = 3 + (normals ? 3 : 0) + nextra;
  size_t vbytes = (size_t)tv * (4 * (size_t)nfloat + (rgb ? 3 : 0)), fbytes = (size_t)tf * 13;
  uint8_t *buf = malloc(vbytes + fbytes + 1);
  if (!buf) free(rgb);
  SESSILE_CHECK(buf, SESSILE_ERR_NO_MEMORY, "out of memory writing '%s' (%zu bytes)", path,
                vbytes + fbytes);
  uint8_t *w = buf;
  const uint8_t *col = rgb;
  sessile_status st = SESSILE_OK;
  for (int k = 0; k < nparts && st == SESSILE_OK; k++) {
    const sessile_mesh_part *m = &parts[k];
    for (uint32_t v = 0; v < m->nv && (st = stopped(path, stop, v)) == SESSILE_OK; v++) {
      for (int a = 0; a < 3; a++) w = io_put_f32(w, m->pos[3 * (size_t)v + a]);
      if (normals)
        for (int a = 0; a < 3; a++) w = io_put_f32(w, m->normals[3 * (size_t)v + a]);
      for (int p = 0; p < nextra; p++) w = io_put_f32(w, m->fields[p][v]);
      for (int a = 0; rgb && a < 3; a++) *w++ = *col++;
    }
  }
  free(rgb);
  uint32_t base = 0;
  for (int k = 0; k < nparts && st == SESSILE_OK; k++) {
    const sessile_mesh_part *m = &parts[k];
    for (uint32_t f = 0; f < m->nf && (st = stopped(path, stop, f)) == SESSILE_OK; f++) {
      *w++ = 3;
      for (int c = 0; c < 3; c++) w = io_put_u32(w, base + m->tri[3 * (size_t)f + c]);
    }
    base += m->nv;
  }

  sessile_atomic_file af;
  if (st == SESSILE_OK) st = sessile_atomic_open(path, &af);
  if (st != SESSILE_OK) {
    free(buf);
    return st;
  }
  st = io_printf(&af, "ply\nformat binary_little_endian 1.0\ncomment %s\n", comment);
  uint32_t v0 = 0, f0 = 0;
  for (int k = 0; part_comments && k < nparts && st == SESSILE_OK; k++) {
    char nb[32];
    st = io_printf(&af, "comment part %s vertices %u %u faces %u %u\n", part_name(&parts[k], k, nb), v0,
                   parts[k].nv, f0, parts[k].nf);
    v0 += parts[k].nv;
    f0 += parts[k].nf;
  }
  if (st == SESSILE_OK) st = io_mesh_info_lines(&af, "comment", info);
  if (st == SESSILE_OK && main_field >= 0)
    st = io_printf(&af, "comment colors red green blue: %s of %s over [%.9g, %.9g] (sessile render --color-by %s)\n",
                   used.map, info->color_by, used.lo, used.hi, info->color_by);
  if (st == SESSILE_OK)
    st = io_printf(&af, "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n", tv);
  if (st == SESSILE_OK && normals)
    st = io_printf(&af, "property float nx\nproperty float ny\nproperty float nz\n");
  for (int p = 0; p < nextra && st == SESSILE_OK; p++)
    st = io_printf(&af, "property float %s\n", extra_names[p]);
  if (st == SESSILE_OK && main_field >= 0)
    st = io_printf(&af, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
  if (st == SESSILE_OK)
    st = io_printf(&af, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", tf);
  /* in 1 MiB blocks, so that a stop is seen within one; and before the fsync */
  for (size_t at = 0, n = (size_t)(w - buf); st == SESSILE_OK && at < n; at += (size_t)1 << 20) {
    st = stopped(path, stop, 0);
    if (st == SESSILE_OK) st = io_write(&af, buf + at, n - at < ((size_t)1 << 20) ? n - at : (size_t)1 << 20);
  }
  if (st == SESSILE_OK) st = stopped(path, stop, 0);
  free(buf);
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

/* The sponge's surface as a one-part union. */
static sessile_status surface_part(const char *path, const sessile_surface *s, const double *normals,
                                   const double *const *extra, sessile_mesh_part *part) {
  SESSILE_CHECK(path && path[0], SESSILE_ERR_USAGE, "cannot write a mesh: no path given");
  SESSILE_CHECK(s && (s->nv == 0 || s->pos) && (s->nf == 0 || s->tri), SESSILE_ERR_USAGE,
                "cannot write '%s': the surface has no vertex or triangle arrays", path);
  *part = (sessile_mesh_part){.name = "surface", .pos = s->pos, .nv = s->nv, .tri = s->tri, .nf = s->nf,
                              .normals = normals, .fields = extra};
  return SESSILE_OK;
}

sessile_status sessile_write_ply(const char *path, const sessile_surface *s, const double *normals,
                                 int nextra, const char *const *extra_names,
                                 const double *const *extra) {
  return sessile_write_ply_stop(path, s, normals, nextra, extra_names, extra, NULL);
}

sessile_status sessile_write_ply_stop(const char *path, const sessile_surface *s, const double *normals,
                                      int nextra, const char *const *extra_names, const double *const *extra,
                                      const volatile sig_atomic_t *stop) {
  sessile_mesh_part part;
  SESSILE_CALL(surface_part(path, s, normals, extra, &part));
  SESSILE_CHECK(nextra >= 0 && nextra <= 64 && (nextra == 0 || (extra_names && extra)),
                SESSILE_ERR_USAGE, "cannot write '%s': %d extra vertex properties (0..64 allowed)",
                path, nextra);
  for (int p = 0; p < nextra; p++)
    SESSILE_CHECK(ply_name_ok(extra_names[p]) && extra[p], SESSILE_ERR_USAGE,
                  "cannot write '%s': extra property %d needs a name without spaces and values", path, p);
  return write_ply_union(path, "sessile sponge surface", 0, 1, &part, nextra, extra_names, NULL, stop);
}

sessile_status sessile_write_ply_parts(const char *path, int nparts, const sessile_mesh_part *parts,
                                       int nfields, const char *const *field_names) {
  return sessile_write_ply_info(path, nparts, parts, nfields, field_names, NULL, NULL);
}

sessile_status sessile_write_ply_info(const char *path, int nparts, const sessile_mesh_part *parts, int nfields,
                                      const char *const *field_names, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop) {
  char comment[64];
  snprintf(comment, sizeof comment, "sessile surface: %d parts", nparts);
  return write_ply_union(path, comment, 1, nparts, parts, nfields, field_names, info, stop);
}

/* The shortest of %.15g..%.17g that reads back as the same double, so OBJ
 * coordinates are exact yet stay short ("0.1", not "0.10000000000000001"). */
static void fmt_exact(char *out, size_t n, double v) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(out, n, "%.*g", prec, v);
    if (strtod(out, NULL) == v) return;
  }
}

/* The three coordinates of p as OBJ text in the convention: sessile's own
 * (z up, cm), or y up in metres through the glTF writer's rotation. */
static void fmt_vec(char x[3][32], const double *p, sessile_obj_axes axes, double scale) {
  double q[3] = {p[0], p[1], p[2]};
  if (axes == SESSILE_OBJ_YUP_M) {
    io_dir_yup(p, q);
    for (int a = 0; a < 3; a++) q[a] = q[a] / scale + 0.0; /* + 0.0: no "-0" for -y = -0 */
  }
  for (int a = 0; a < 3; a++) fmt_exact(x[a], sizeof x[a], q[a]);
}

/* One part's v, vn and f lines; base: vertices written before it. */
static sessile_status obj_part(sessile_atomic_file *af, const sessile_mesh_part *m, int normals, sessile_obj_axes axes,
                               uint64_t base, const volatile sig_atomic_t *stop) {
  sessile_status st = SESSILE_OK;
  char x[3][32];
  for (uint32_t v = 0; v < m->nv && st == SESSILE_OK && (st = stopped(af->path, stop, v)) == SESSILE_OK; v++) {
    fmt_vec(x, m->pos + 3 * (size_t)v, axes, 100); /* cm to m */
    st = io_printf(af, "v %s %s %s\n", x[0], x[1], x[2]);
  }
  for (uint32_t v = 0; normals && v < m->nv && st == SESSILE_OK; v++) {
    fmt_vec(x, m->normals + 3 * (size_t)v, axes, 1);
    st = io_printf(af, "vn %s %s %s\n", x[0], x[1], x[2]);
  }
  for (uint32_t f = 0; f < m->nf && st == SESSILE_OK && (st = stopped(af->path, stop, f)) == SESSILE_OK; f++) {
    const uint32_t *t = m->tri + 3 * (size_t)f;
    unsigned long long a = base + t[0] + 1, b = base + t[1] + 1, c = base + t[2] + 1;
    if (normals) st = io_printf(af, "f %llu//%llu %llu//%llu %llu//%llu\n", a, a, b, b, c, c);
    else st = io_printf(af, "f %llu %llu %llu\n", a, b, c);
  }
  return st;
}

sessile_status sessile_write_obj(const char *path, const sessile_surface *s, const double *normals) {
  return sessile_write_obj_stop(path, s, normals, NULL);
}

sessile_status sessile_write_obj_stop(const char *path, const sessile_surface *s, const double *normals,
                                      const volatile sig_atomic_t *stop) {
  return sessile_write_obj_styled(path, s, normals, NULL, stop);
}

sessile_status sessile_write_obj_styled(const char *path, const sessile_surface *s, const double *normals,
                                        const sessile_obj_style *style, const volatile sig_atomic_t *stop) {
  return sessile_write_obj_info(path, s, normals, style, NULL, stop);
}

sessile_status sessile_write_obj_info(const char *path, const sessile_surface *s, const double *normals,
                                      const sessile_obj_style *style, const sessile_mesh_info *info,
                                      const volatile sig_atomic_t *stop) {
  sessile_mesh_part part;
  SESSILE_CALL(surface_part(path, s, normals, NULL, &part));
  uint32_t tv, tf;
  int with_normals;
  SESSILE_CALL(io_check_parts(path, 1, &part, 0, NULL, &tv, &tf, &with_normals));
  sessile_obj_style plain = {SESSILE_OBJ_ZUP_CM, NULL, NULL};
  if (!style) style = &plain;
  SESSILE_CALL(io_obj_style_check(path, style));
  sessile_mesh_info lines = info ? *info : (sessile_mesh_info){0}; /* OBJ has no colours */
  lines.color_by = NULL;
  int no_field;
  SESSILE_CALL(io_mesh_info_check(path, &lines, 0, NULL, &no_field));
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "# sessile sponge surface: %u vertices, %u triangles\n", s->nv, s->nf);
  if (st == SESSILE_OK && info) st = io_mesh_info_lines(&af, "#", &lines);
  if (st == SESSILE_OK) st = io_obj_style_lines(&af, style);
  if (st == SESSILE_OK) st = obj_part(&af, &part, normals != NULL, style->axes, 0, stop);
  if (st == SESSILE_OK) st = stopped(path, stop, 0); /* before the fsync */
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}

sessile_status sessile_write_obj_parts(const char *path, int nparts, const sessile_mesh_part *parts) {
  uint32_t tv, tf;
  int normals;
  SESSILE_CALL(io_check_parts(path, nparts, parts, 0, NULL, &tv, &tf, &normals));
  sessile_atomic_file af;
  SESSILE_CALL(sessile_atomic_open(path, &af));
  sessile_status st = io_printf(&af, "# sessile surface: %d parts, %u vertices, %u triangles\n", nparts, tv, tf);
  uint64_t base = 0;
  for (int k = 0; k < nparts && st == SESSILE_OK; k++) {
    char nb[32];
    const char *name = part_name(&parts[k], k, nb);
    st = io_printf(&af, "o %s\ng %s\n", name, name);
    if (st == SESSILE_OK) st = obj_part(&af, &parts[k], normals, SESSILE_OBJ_ZUP_CM, base, NULL);
    base += parts[k].nv;
  }
  if (st != SESSILE_OK) {
    sessile_atomic_abort(&af);
    return st;
  }
  return sessile_atomic_commit(&af);
}
