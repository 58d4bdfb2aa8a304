/* The PLY reader (sessile/io/io_read.h; ascii, binary little- and big-endian).
 *
 * The header is parsed and checked whole before anything is allocated: the
 * vertex and face counts against the caller's limits, and every element's
 * count against the bytes after the header (each record takes at least its
 * scalar sizes in binary, two bytes in ascii).  The body is then read in
 * chunks, element by element in the declared order; ascii records are one
 * line each, so a short or long record is named by its line. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "io_internal.h"

enum { MAXPROP = 64, MAXELEM = 16, NAMELEN = 64, HLINE = 4096, BLINE = 1 << 16 };
enum { HEADER_MAX = 1 << 20, MAX_CORNERS = 256, MAX_LIST = 65535 };
typedef enum { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 } ptype;

typedef struct prop {
  char name[NAMELEN];
  ptype type;       /* scalar type, or the item type of a list */
  ptype count_type; /* T_NONE for a scalar */
} prop;

typedef struct elem {
  char name[NAMELEN];
  uint64_t count;     /* UINT64_MAX when the text overflows */
  char count_text[32];
  unsigned long long line;
  int nprop;
  prop p[MAXPROP];
} elem;

typedef struct ply {
  io_in in;
  sessile_mesh_read_opts o;
  int format; /* 0 ascii, 1 little-endian, 2 big-endian */
  int nel;
  elem el[MAXELEM];
  char line[BLINE]; /* the ascii record being read */
  char *cur;        /* its next token */
  char tok[80];     /* the last value as written (for messages) */
} ply;

static ptype type_of(const char *s) {
  static const struct { const char *n; ptype t; } tab[] = {
      {"char", T_I8},    {"int8", T_I8},     {"uchar", T_U8},   {"uint8", T_U8},
      {"short", T_I16},  {"int16", T_I16},   {"ushort", T_U16}, {"uint16", T_U16},
      {"int", T_I32},    {"int32", T_I32},   {"uint", T_U32},   {"uint32", T_U32},
      {"float", T_F32},  {"float32", T_F32}, {"double", T_F64}, {"float64", T_F64}};
  for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++)
    if (strcmp(s, tab[i].n) == 0) return tab[i].t;
  return T_NONE;
}

static size_t type_size(ptype t) {
  static const size_t sz[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
  return sz[t];
}

#define BAD(...) return sessile_error_set(SESSILE_ERR_USAGE, __VA_ARGS__)

static sessile_status element_line(ply *r, const char *line, int nw, const char *w1, const char *w2) {
  const char *path = r->in.path;
  unsigned long long ln = (unsigned long long)r->in.line - 1;
  if (nw != 3) BAD("%s: line %llu: bad element line '%s'", path, ln, line);
  if (r->nel >= MAXELEM) BAD("%s: line %llu: more than %d elements", path, ln, MAXELEM);
  char *end = NULL;
  errno = 0;
  unsigned long long c = strtoull(w2, &end, 10);
  if (w2[0] < '0' || w2[0] > '9' || !end || *end) BAD("%s: line %llu: bad element count in '%s'", path, ln, line);
  elem *e = &r->el[r->nel++];
  memset(e, 0, sizeof *e);
  snprintf(e->name, sizeof e->name, "%s", w1);
  snprintf(e->count_text, sizeof e->count_text, "%.*s", (int)sizeof e->count_text - 1, w2);
  e->count = errno == ERANGE ? UINT64_MAX : c;
  e->line = ln;
  return SESSILE_OK;
}

static sessile_status property_line(ply *r, const char *line, int nw, char w[5][NAMELEN]) {
  const char *path = r->in.path;
  unsigned long long ln = (unsigned long long)r->in.line - 1;
  if (!r->nel) BAD("%s: line %llu: a property before any element", path, ln);
  elem *e = &r->el[r->nel - 1];
  if (e->nprop >= MAXPROP) BAD("%s: line %llu: element %s has more than %d properties", path, ln, e->name, MAXPROP);
  prop *p = &e->p[e->nprop++];
  if (strcmp(w[1], "list") == 0) {
    if (nw != 5) BAD("%s: line %llu: bad list property '%s'", path, ln, line);
    p->count_type = type_of(w[2]);
    p->type = type_of(w[3]);
    snprintf(p->name, sizeof p->name, "%s", w[4]);
    if (p->count_type == T_NONE || p->type == T_NONE || p->count_type == T_F32 || p->count_type == T_F64)
      BAD("%s: line %llu: bad list types in '%s'", path, ln, line);
  } else {
    if (nw != 3 || type_of(w[1]) == T_NONE) BAD("%s: line %llu: bad property '%s'", path, ln, line);
    p->type = type_of(w[1]);
    p->count_type = T_NONE;
    snprintf(p->name, sizeof p->name, "%s", w[2]);
  }
  return SESSILE_OK;
}

static sessile_status parse_header(ply *r) {
  const char *path = r->in.path;
  size_t avail;
  SESSILE_CALL(io_in_more(&r->in, &avail));
  /* the first bytes decide: a file of anything else is refused at once */
  const char *b = (const char *)r->in.buf;
  if (!((avail >= 4 && memcmp(b, "ply\n", 4) == 0) || (avail >= 5 && memcmp(b, "ply\r\n", 5) == 0)))
    BAD("%s: not a PLY file (the first line is not 'ply')", path);
  char line[HLINE];
  size_t len;
  int got;
  SESSILE_CALL(io_in_line(&r->in, line, sizeof line, &len, &got));
  r->format = -1;
  for (;;) {
    SESSILE_CALL(io_in_line(&r->in, line, sizeof line, &len, &got));
    unsigned long long ln = (unsigned long long)r->in.line - 1;
    if (!got) BAD("%s: the PLY header has no end_header line", path);
    if (len >= sizeof line) BAD("%s: line %llu: a header line of %zu characters or more", path, ln + 1, sizeof line - 1);
    if (r->in.off > HEADER_MAX) BAD("%s: line %llu: the header is longer than %d bytes", path, ln, HEADER_MAX);
    char w[5][NAMELEN] = {"", "", "", "", ""};
    int nw = sscanf(line, "%63s %63s %63s %63s %63s", w[0], w[1], w[2], w[3], w[4]);
    if (nw <= 0 || strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0) continue;
    if (strcmp(w[0], "end_header") == 0) break;
    if (strcmp(w[0], "format") == 0) {
      if (nw != 3 || strcmp(w[2], "1.0") != 0) BAD("%s: line %llu: unsupported PLY format line '%s'", path, ln, line);
      if (strcmp(w[1], "ascii") == 0) r->format = 0;
      else if (strcmp(w[1], "binary_little_endian") == 0) r->format = 1;
      else if (strcmp(w[1], "binary_big_endian") == 0) r->format = 2;
      else BAD("%s: line %llu: unknown PLY format '%s'", path, ln, w[1]);
    } else if (strcmp(w[0], "element") == 0) {
      SESSILE_CALL(element_line(r, line, nw, w[1], w[2]));
    } else if (strcmp(w[0], "property") == 0) {
      SESSILE_CALL(property_line(r, line, nw, w));
    } else {
      BAD("%s: line %llu: unknown PLY header line '%s'", path, ln, line);
    }
  }
  if (r->format < 0) BAD("%s: the PLY header has no format line", path);
  return SESSILE_OK;
}

static int find_prop(const elem *e, const char *name) {
  for (int i = 0; i < e->nprop; i++)
    if (strcmp(e->p[i].name, name) == 0) return i;
  return -1;
}

static const elem *first_elem(const ply *r, const char *name) {
  for (int i = 0; i < r->nel; i++)
    if (strcmp(r->el[i].name, name) == 0) return &r->el[i];
  return NULL;
}

/* The fewest bytes one record of e can take. */
static uint64_t min_record(const ply *r, const elem *e) {
  if (r->format == 0) return 2; /* one character and a newline */
  uint64_t s = 0;
  for (int i = 0; i < e->nprop; i++)
    s += e->p[i].count_type != T_NONE ? type_size(e->p[i].count_type) : type_size(e->p[i].type);
  return s ? s : 1;
}

/* The counts against the limits and against the bytes after the header. */
static sessile_status check_counts(ply *r, const elem *ev, const elem *ef) {
  const char *path = r->in.path;
  if (ev && ev->count > r->o.max_vertices)
    BAD("%s: line %llu: declares %s vertices (at most %llu)", path, ev->line, ev->count_text,
        (unsigned long long)r->o.max_vertices);
  if (ef && ef->count > r->o.max_faces)
    BAD("%s: line %llu: declares %s faces (at most %llu)", path, ef->line, ef->count_text,
        (unsigned long long)r->o.max_faces);
  uint64_t left = r->in.size > r->in.off ? r->in.size - r->in.off : 0;
  uint64_t budget = left + (r->format == 0); /* the last ascii line may lack its newline */
  for (int i = 0; i < r->nel; i++) {
    const elem *e = &r->el[i];
    uint64_t m = min_record(r, e);
    if (e->count > budget / m)
      BAD("%s: line %llu: element %s declares %s records but only %llu bytes follow the header", path, e->line,
          e->name, e->count_text, (unsigned long long)left);
    budget -= e->count * m;
  }
  return SESSILE_OK;
}

/* The next ascii record: the next non-blank line; 0 at the end of the file. */
static sessile_status next_record(ply *r, int *got) {
  size_t len;
  for (;;) {
    SESSILE_CALL(io_in_line(&r->in, r->line, sizeof r->line, &len, got));
    if (!*got) return SESSILE_OK;
    if (len >= sizeof r->line)
      BAD("%s: line %llu: a record of %zu characters or more", r->in.path, (unsigned long long)r->in.line,
          sizeof r->line - 1);
    r->cur = r->line + strspn(r->line, " \t\r");
    if (*r->cur) return SESSILE_OK;
  }
}

/* One scalar of type t; *ok 0 when it is missing or malformed.  r->tok
 * holds it as written. */
static sessile_status read_value(ply *r, ptype t, double *v, int *ok) {
  *ok = 0;
  if (r->format == 0) {
    char *s = r->cur + strspn(r->cur, " \t\r");
    size_t n = strcspn(s, " \t\r");
    snprintf(r->tok, sizeof r->tok, "%.*s", (int)(n < 64 ? n : 64), s);
    r->cur = s + n;
    if (n == 0 || n >= 64) return SESSILE_OK;
    char *end = NULL;
    *v = strtod(r->tok, &end);
    *ok = end && *end == 0;
    return SESSILE_OK;
  }
  size_t sz = type_size(t);
  unsigned char b[8];
  SESSILE_CALL(io_in_bytes(&r->in, b, sz, ok));
  if (!*ok) return SESSILE_OK;
  if (r->format == 2)
    for (size_t i = 0; i < sz / 2; i++) {
      unsigned char x = b[i];
      b[i] = b[sz - 1 - i];
      b[sz - 1 - i] = x;
    }
  uint64_t u = 0;
  for (size_t i = 0; i < sz; i++) u |= (uint64_t)b[i] << (8 * i);
  switch (t) {
  case T_I8: *v = (int8_t)u; break;
  case T_U8: *v = (uint8_t)u; break;
  case T_I16: *v = (int16_t)u; break;
  case T_U16: *v = (uint16_t)u; break;
  case T_I32: *v = (int32_t)u; break;
  case T_U32: *v = (uint32_t)u; break;
  case T_F32: { uint32_t w = (uint32_t)u; float f; memcpy(&f, &w, 4); *v = f; break; }
  default: memcpy(v, &u, 8); break;
  }
  snprintf(r->tok, sizeof r->tok, "%.17g", *v);
  return SESSILE_OK;
}

/* Where a record is, for messages: "line 12 (vertex 3 of 5)" or "vertex 3 of 5". */
static const char *where(ply *r, const elem *e, uint64_t k, char *buf, size_t n) {
  if (r->format == 0)
    snprintf(buf, n, "line %llu (%s %llu of %s)", (unsigned long long)r->in.line - 1, e->name,
             (unsigned long long)k, e->count_text);
  else
    snprintf(buf, n, "%s %llu of %s", e->name, (unsigned long long)k, e->count_text);
  return buf;
}

static sessile_status missing(ply *r, const elem *e, uint64_t k, const prop *p) {
  char at[160];
  where(r, e, k, at, sizeof at);
  if (r->format != 0) BAD("%s: %s: the file ends inside %s", r->in.path, at, p->name);
  if (r->tok[0]) BAD("%s: %s: '%s' is not a number (%s)", r->in.path, at, r->tok, p->name);
  BAD("%s: %s: a short record (no value for %s)", r->in.path, at, p->name);
}

/* A list's item count, checked. */
static sessile_status list_count(ply *r, const elem *e, uint64_t k, const prop *p, int max, int *c) {
  double x;
  int ok;
  SESSILE_CALL(read_value(r, p->count_type, &x, &ok));
  if (!ok) return missing(r, e, k, p);
  char at[160];
  if (!(x >= 0 && x <= max && x == floor(x)))
    BAD("%s: %s: list %s has %s items (at most %d)", r->in.path, where(r, e, k, at, sizeof at), p->name, r->tok, max);
  *c = (int)x;
  return SESSILE_OK;
}

/* The end of an ascii record: nothing may follow its last value. */
static sessile_status record_end(ply *r, const elem *e, uint64_t k) {
  if (r->format != 0) return SESSILE_OK;
  char *s = r->cur + strspn(r->cur, " \t\r");
  char at[160];
  if (*s) BAD("%s: %s: more values than the header declares ('%.40s' after the last)", r->in.path,
              where(r, e, k, at, sizeof at), s);
  return SESSILE_OK;
}

static sessile_status record_start(ply *r, const elem *e, uint64_t k) {
  if (r->format != 0) return SESSILE_OK;
  int got;
  SESSILE_CALL(next_record(r, &got));
  if (!got)
    BAD("%s: the file ends after %llu of the %s %s records", r->in.path, (unsigned long long)k, e->count_text,
        e->name);
  return SESSILE_OK;
}

/* Skips the items of a list or the scalar p. */
static sessile_status skip_prop(ply *r, const elem *e, uint64_t k, const prop *p) {
  int c = 1, ok;
  double x;
  if (p->count_type != T_NONE) SESSILE_CALL(list_count(r, e, k, p, MAX_LIST, &c));
  for (int j = 0; j < c; j++) {
    SESSILE_CALL(read_value(r, p->type, &x, &ok));
    if (!ok) return missing(r, e, k, p);
  }
  return SESSILE_OK;
}

/* uchar red/green/blue/alpha are display colours (sessile's own are a colour
 * map of the main scalar, docs/io.md), not data: not kept as scalars */
static int is_colour(const prop *p) {
  static const char *const names[] = {"red", "green", "blue", "alpha"};
  if (p->type != T_U8) return 0;
  for (int i = 0; i < 4; i++)
    if (!strcmp(p->name, names[i])) return 1;
  return 0;
}

static sessile_status read_vertices(ply *r, const elem *e, sessile_mesh_in *m) {
  const char *path = r->in.path;
  int ix = find_prop(e, "x"), iy = find_prop(e, "y"), iz = find_prop(e, "z");
  if (ix < 0 || iy < 0 || iz < 0) BAD("%s: the vertex element has no x, y and z properties", path);
  int in[3] = {find_prop(e, "nx"), find_prop(e, "ny"), find_prop(e, "nz")};
  int has_n = r->o.keep_props && in[0] >= 0 && in[1] >= 0 && in[2] >= 0;
  int slot[MAXPROP]; /* property index -> kept property, -1 */
  int nkeep = 0;
  for (int i = 0; i < e->nprop; i++) {
    slot[i] = -1;
    if (e->p[i].count_type != T_NONE && (i == ix || i == iy || i == iz))
      BAD("%s: vertex coordinate %s is a list", path, e->p[i].name);
    if (!r->o.keep_props || e->p[i].count_type != T_NONE || i == ix || i == iy || i == iz) continue;
    if (has_n && (i == in[0] || i == in[1] || i == in[2])) continue;
    if (is_colour(&e->p[i])) continue;
    slot[i] = nkeep++;
  }
  size_t nv = (size_t)e->count;
  m->pos = malloc(nv * 3 * sizeof(double) + 1);
  if (has_n) m->normal = malloc(nv * 3 * sizeof(float) + 1);
  m->prop_names = calloc((size_t)nkeep + 1, sizeof(char *));
  m->props = calloc((size_t)nkeep + 1, sizeof(float *));
  SESSILE_CHECK(m->pos && (!has_n || m->normal) && m->prop_names && m->props, SESSILE_ERR_NO_MEMORY,
                "%s: out of host memory for %zu vertices", path, nv);
  m->nprops = nkeep;
  for (int i = 0; i < e->nprop; i++) {
    if (slot[i] < 0) continue;
    m->prop_names[slot[i]] = strdup(e->p[i].name);
    m->props[slot[i]] = malloc(nv * sizeof(float) + 1);
    SESSILE_CHECK(m->prop_names[slot[i]] && m->props[slot[i]], SESSILE_ERR_NO_MEMORY,
                  "%s: out of host memory for vertex properties", path);
  }
  for (size_t v = 0; v < nv; v++) {
    SESSILE_CALL(record_start(r, e, v));
    for (int i = 0; i < e->nprop; i++) {
      const prop *p = &e->p[i];
      double x;
      int ok;
      if (p->count_type != T_NONE) { /* a list in the vertex element: skipped */
        SESSILE_CALL(skip_prop(r, e, v, p));
        continue;
      }
      SESSILE_CALL(read_value(r, p->type, &x, &ok));
      if (!ok) return missing(r, e, v, p);
      int k = i == ix ? 0 : i == iy ? 1 : i == iz ? 2 : -1;
      if (k >= 0) {
        char at[160];
        if (!isfinite(x)) BAD("%s: %s: coordinate %s is %s (not finite)", path, where(r, e, v, at, sizeof at), p->name, r->tok);
        m->pos[3 * v + (size_t)k] = x;
      } else if (has_n && (i == in[0] || i == in[1] || i == in[2])) {
        m->normal[3 * v + (size_t)(i == in[0] ? 0 : i == in[1] ? 1 : 2)] = (float)x;
      } else if (slot[i] >= 0) {
        m->props[slot[i]][v] = (float)x;
      }
    }
    SESSILE_CALL(record_end(r, e, v));
  }
  m->nv = (uint32_t)nv;
  return SESSILE_OK;
}

static sessile_status read_faces(ply *r, const elem *e, uint64_t nv, sessile_mesh_in *m) {
  const char *path = r->in.path;
  int il = find_prop(e, "vertex_indices");
  if (il < 0) il = find_prop(e, "vertex_index");
  if (il < 0 || e->p[il].count_type == T_NONE) BAD("%s: the face element has no vertex_indices list", path);
  uint32_t poly[MAX_CORNERS];
  size_t cap = 0;
  char at[160];
  for (uint64_t f = 0; f < e->count; f++) {
    SESSILE_CALL(record_start(r, e, f));
    for (int i = 0; i < e->nprop; i++) {
      const prop *p = &e->p[i];
      if (i != il) {
        SESSILE_CALL(skip_prop(r, e, f, p));
        continue;
      }
      int c, ok;
      SESSILE_CALL(list_count(r, e, f, p, MAX_LIST, &c));
      if (c > MAX_CORNERS) BAD("%s: %s: %d corners (at most %d)", path, where(r, e, f, at, sizeof at), c, MAX_CORNERS);
      if (r->o.triangles_only && c != 3)
        BAD("%s: %s: %d corners (only triangles are read)", path, where(r, e, f, at, sizeof at), c);
      for (int k = 0; k < c; k++) {
        double x;
        SESSILE_CALL(read_value(r, p->type, &x, &ok));
        if (!ok) return missing(r, e, f, p);
        if (!(x >= 0 && x < (double)nv && x == floor(x)))
          BAD("%s: %s: vertex index %s names no vertex (%llu vertices)", path, where(r, e, f, at, sizeof at), r->tok,
              (unsigned long long)nv);
        poly[k] = (uint32_t)x;
      }
      if (c >= 3) SESSILE_CALL(io_mesh_add_face(m, &cap, poly, (uint32_t)c, UINT32_MAX / 3, path));
    }
    SESSILE_CALL(record_end(r, e, f));
  }
  return SESSILE_OK;
}

static sessile_status skip_element(ply *r, const elem *e) {
  for (uint64_t k = 0; k < e->count; k++) {
    SESSILE_CALL(record_start(r, e, k));
    for (int i = 0; i < e->nprop; i++) SESSILE_CALL(skip_prop(r, e, k, &e->p[i]));
    SESSILE_CALL(record_end(r, e, k));
  }
  return SESSILE_OK;
}

/* Nothing after the last element but blank lines (ascii). */
static sessile_status check_end(ply *r) {
  if (r->format == 0) {
    int got;
    SESSILE_CALL(next_record(r, &got));
    if (got)
      BAD("%s: line %llu: data after the last element (the header declares fewer records)", r->in.path,
          (unsigned long long)r->in.line - 1);
    return SESSILE_OK;
  }
  size_t avail;
  SESSILE_CALL(io_in_more(&r->in, &avail));
  if (avail)
    BAD("%s: %llu bytes after the last element (the header declares fewer records)", r->in.path,
        (unsigned long long)(r->in.size > r->in.off ? r->in.size - r->in.off : avail));
  return SESSILE_OK;
}

static sessile_status read_body(ply *r, sessile_mesh_in *m) {
  const elem *ev = first_elem(r, "vertex"), *ef = first_elem(r, "face");
  if (!ev) BAD("%s: the PLY file has no vertex element", r->in.path);
  SESSILE_CALL(check_counts(r, ev, ef));
  for (int i = 0; i < r->nel; i++) {
    const elem *e = &r->el[i];
    if (e == ev) SESSILE_CALL(read_vertices(r, e, m));
    else if (e == ef) SESSILE_CALL(read_faces(r, e, ev->count, m));
    else SESSILE_CALL(skip_element(r, e));
  }
  return check_end(r);
}

sessile_status sessile_read_ply(const char *path, const sessile_mesh_read_opts *opts, sessile_mesh_in *out) {
  *out = (sessile_mesh_in){0};
  ply *r = malloc(sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  r->nel = 0;
  r->o = io_mesh_opts(opts);
  r->tok[0] = 0;
  sessile_status s = io_in_open(&r->in, path, "mesh");
  if (s == SESSILE_OK) {
    s = parse_header(r);
    if (s == SESSILE_OK) s = read_body(r, out);
    io_in_close(&r->in);
  }
  free(r);
  if (s != SESSILE_OK) sessile_mesh_in_free(out);
  return s;
}
