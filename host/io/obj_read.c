/* The OBJ reader (sessile/io/io_read.h): "v x y z [w]" and "f a b c ..." lines
 * (a as v, v/t, v//n or v/t/n; negative indices count back from the last
 * vertex); every other line (vn, vt, o, g, s, usemtl, mtllib, comments) is
 * ignored, however long.  Normals are not taken from vn: OBJ indexes them
 * per face corner, and a mesh has one per vertex.  Read line by line in
 * chunks: a file that is not text (a NUL byte) is refused at its first. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "io_internal.h"

enum { LINE = 1 << 16, MAX_CORNERS = 256 };

typedef struct obj {
  io_in in;
  sessile_mesh_read_opts o;
  size_t vcap, tcap;
  char line[LINE];
} obj;

static const char *skip_ws(const char *p) { return p + strspn(p, " \t\r"); }

static sessile_status vertex_line(obj *r, unsigned long long ln, const char *q, sessile_mesh_in *m) {
  const char *path = r->in.path;
  SESSILE_CHECK(m->nv < r->o.max_vertices, SESSILE_ERR_USAGE, "%s: line %llu: more than %llu vertices", path, ln,
                (unsigned long long)r->o.max_vertices);
  if (m->nv == r->vcap) {
    size_t cap = r->vcap ? 2 * r->vcap : 4096;
    double *p = realloc(m->pos, cap * 3 * sizeof(double));
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "%s: out of host memory for %zu vertices", path, cap);
    m->pos = p, r->vcap = cap;
  }
  const char *c = q + 1;
  for (int k = 0; k < 3; k++) {
    char *e = NULL;
    double x = strtod(c, &e);
    if (e == c) {
      c = skip_ws(c);
      size_t n = strcspn(c, " \t\r");
      if (n) SESSILE_CHECK(0, SESSILE_ERR_USAGE, "%s: line %llu: '%.*s' is not a number", path, ln, (int)(n < 40 ? n : 40), c);
      SESSILE_CHECK(0, SESSILE_ERR_USAGE, "%s: line %llu: a vertex needs x y z", path, ln);
    }
    const char *t = skip_ws(c);
    SESSILE_CHECK(isfinite(x), SESSILE_ERR_USAGE, "%s: line %llu: coordinate %c is '%.*s' (not finite)", path, ln,
                  'x' + k, (int)(e - t < 40 ? e - t : 40), t);
    m->pos[3 * (size_t)m->nv + (size_t)k] = x;
    c = e;
  }
  m->nv++;
  return SESSILE_OK;
}

static sessile_status face_line(obj *r, unsigned long long ln, const char *q, sessile_mesh_in *m) {
  const char *path = r->in.path;
  uint32_t poly[MAX_CORNERS], n = 0;
  const char *c = q + 1;
  for (;;) {
    c = skip_ws(c);
    if (!*c) break;
    size_t len = strcspn(c, " \t\r"), ilen = strcspn(c, "/ \t\r");
    char *e = NULL;
    errno = 0;
    long long idx = strtoll(c, &e, 10);
    if (e == c || idx == 0)
      SESSILE_CHECK(0, SESSILE_ERR_USAGE, "%s: line %llu: bad face index '%.*s'", path, ln, (int)(len < 40 ? len : 40), c);
    long long v = errno == ERANGE ? -1 : idx > 0 ? idx - 1 : (long long)m->nv + idx;
    if (v < 0 || v >= (long long)m->nv)
      SESSILE_CHECK(0, SESSILE_ERR_USAGE, "%s: line %llu: face index %.*s refers to no vertex (%u so far)", path, ln,
                    (int)(ilen < 40 ? ilen : 40), c, m->nv);
    SESSILE_CHECK(n < MAX_CORNERS, SESSILE_ERR_USAGE, "%s: line %llu: a face of more than %d vertices", path, ln,
                  MAX_CORNERS);
    poly[n++] = (uint32_t)v;
    c += len; /* past /t/n (and anything else up to the blank, as OBJ readers do) */
  }
  if (r->o.triangles_only && n != 3)
    SESSILE_CHECK(0, SESSILE_ERR_USAGE, "%s: line %llu: a face of %u corners (only triangles are read)", path, ln, n);
  if (n >= 3) SESSILE_CALL(io_mesh_add_face(m, &r->tcap, poly, n, r->o.max_faces, path));
  return SESSILE_OK;
}

static sessile_status read_lines(obj *r, sessile_mesh_in *m) {
  for (;;) {
    size_t len;
    int got;
    SESSILE_CALL(io_in_line(&r->in, r->line, sizeof r->line, &len, &got));
    if (!got) return SESSILE_OK;
    int ended = len < sizeof r->line;
    unsigned long long ln = (unsigned long long)r->in.line - ended;
    const char *q = skip_ws(r->line);
    int kind = (q[0] == 'v' || q[0] == 'f') && (q[1] == ' ' || q[1] == '\t') ? q[0] : 0;
    if (!ended) {
      SESSILE_CHECK(!kind, SESSILE_ERR_USAGE, "%s: line %llu: a '%c' line of %zu characters or more", r->in.path, ln,
                    kind, sizeof r->line - 1);
      SESSILE_CALL(io_in_skip_line(&r->in));
      continue;
    }
    if (kind == 'v') SESSILE_CALL(vertex_line(r, ln, q, m));
    else if (kind == 'f') SESSILE_CALL(face_line(r, ln, q, m));
  }
}

sessile_status sessile_read_obj(const char *path, const sessile_mesh_read_opts *opts, sessile_mesh_in *out) {
  *out = (sessile_mesh_in){0};
  obj *r = malloc(sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->o = io_mesh_opts(opts);
  r->vcap = r->tcap = 0;
  sessile_status s = io_in_open(&r->in, path, "mesh");
  if (s == SESSILE_OK) {
    s = read_lines(r, out);
    io_in_close(&r->in);
  }
  free(r);
  if (s != SESSILE_OK) sessile_mesh_in_free(out);
  return s;
}
