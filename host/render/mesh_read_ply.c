/* PLY reader (ascii 1.0, binary_little_endian 1.0, binary_big_endian 1.0).
 *
 * The header is parsed into elements and their properties; the body is read
 * element by element in the declared order.  The vertex element needs x, y,
 * z (any scalar type); nx ny nz become the normals; every other scalar
 * vertex property is kept (as float) for --color-by.  The face element's
 * vertex_indices (or vertex_index) list is split into triangle fans; other
 * elements and properties are skipped.  Every declared count is checked
 * against the bytes left before anything is allocated for it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh_internal.h"

enum { MAXPROP = 64, MAXELEM = 16, NAMELEN = 64 };
typedef enum { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 } ptype;

typedef struct prop {
  char name[NAMELEN];
  ptype type;       /* scalar type, or the item type of a list */
  ptype count_type; /* T_NONE for a scalar */
} prop;

typedef struct elem {
  char name[NAMELEN];
  uint64_t count;
  int nprop;
  prop p[MAXPROP];
} elem;

typedef struct reader {
  const char *what;
  const unsigned char *d;
  size_t n, at;
  int format; /* 0 ascii, 1 little-endian, 2 big-endian */
} reader;

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
  switch (t) {
  case T_I8: case T_U8: return 1;
  case T_I16: case T_U16: return 2;
  case T_I32: case T_U32: case T_F32: return 4;
  case T_F64: return 8;
  default: return 0;
  }
}

/* One header line into line[] (without the newline); 0 at the end of data. */
static int header_line(reader *r, char *line, size_t cap) {
  if (r->at >= r->n) return 0;
  size_t k = 0;
  while (r->at < r->n && r->d[r->at] != '\n') {
    if (k + 1 < cap) line[k++] = (char)r->d[r->at];
    r->at++;
  }
  if (r->at < r->n) r->at++; /* the newline */
  if (k > 0 && line[k - 1] == '\r') k--;
  line[k] = 0;
  return 1;
}

static sessile_status parse_header(reader *r, elem *el, int *nel) {
  char line[512];
  SESSILE_CHECK(header_line(r, line, sizeof line) && strcmp(line, "ply") == 0, SESSILE_ERR_USAGE,
                "%s: not a PLY file (the first line is not 'ply')", r->what);
  *nel = 0;
  r->format = -1;
  for (;;) {
    SESSILE_CHECK(header_line(r, line, sizeof line), SESSILE_ERR_USAGE,
                  "%s: the PLY header has no end_header line", r->what);
    char w0[NAMELEN] = "", w1[NAMELEN] = "", w2[NAMELEN] = "", w3[NAMELEN] = "", w4[NAMELEN] = "";
    int nw = sscanf(line, "%63s %63s %63s %63s %63s", w0, w1, w2, w3, w4);
    if (nw <= 0 || strcmp(w0, "comment") == 0 || strcmp(w0, "obj_info") == 0) continue;
    if (strcmp(w0, "end_header") == 0) break;
    if (strcmp(w0, "format") == 0) {
      SESSILE_CHECK(nw == 3 && strcmp(w2, "1.0") == 0, SESSILE_ERR_USAGE,
                    "%s: unsupported PLY format line '%s'", r->what, line);
      if (strcmp(w1, "ascii") == 0) r->format = 0;
      else if (strcmp(w1, "binary_little_endian") == 0) r->format = 1;
      else if (strcmp(w1, "binary_big_endian") == 0) r->format = 2;
      else return sessile_error_set(SESSILE_ERR_USAGE, "%s: unknown PLY format '%s'", r->what, w1);
    } else if (strcmp(w0, "element") == 0) {
      SESSILE_CHECK(nw == 3 && *nel < MAXELEM, SESSILE_ERR_USAGE,
                    "%s: bad PLY element line '%s' (or more than %d elements)", r->what, line, MAXELEM);
      char *end = NULL;
      unsigned long long c = strtoull(w2, &end, 10);
      SESSILE_CHECK(end && *end == 0 && w2[0] != '-', SESSILE_ERR_USAGE,
                    "%s: bad element count in '%s'", r->what, line);
      elem *e = &el[(*nel)++];
      memset(e, 0, sizeof *e);
      snprintf(e->name, sizeof e->name, "%s", w1);
      e->count = c;
    } else if (strcmp(w0, "property") == 0) {
      SESSILE_CHECK(*nel > 0, SESSILE_ERR_USAGE, "%s: PLY property before any element", r->what);
      elem *e = &el[*nel - 1];
      SESSILE_CHECK(e->nprop < MAXPROP, SESSILE_ERR_USAGE,
                    "%s: element %s has more than %d properties", r->what, e->name, MAXPROP);
      prop *p = &e->p[e->nprop++];
      if (strcmp(w1, "list") == 0) {
        SESSILE_CHECK(nw == 5, SESSILE_ERR_USAGE, "%s: bad PLY list property '%s'", r->what, line);
        p->count_type = type_of(w2);
        p->type = type_of(w3);
        snprintf(p->name, sizeof p->name, "%s", w4);
        SESSILE_CHECK(p->count_type != T_NONE && p->type != T_NONE && p->count_type != T_F32 &&
                          p->count_type != T_F64,
                      SESSILE_ERR_USAGE, "%s: bad PLY list types in '%s'", r->what, line);
      } else {
        SESSILE_CHECK(nw == 3 && type_of(w1) != T_NONE, SESSILE_ERR_USAGE,
                      "%s: bad PLY property '%s'", r->what, line);
        p->type = type_of(w1);
        p->count_type = T_NONE;
        snprintf(p->name, sizeof p->name, "%s", w2);
      }
    } else {
      return sessile_error_set(SESSILE_ERR_USAGE, "%s: unknown PLY header line '%s'", r->what, line);
    }
  }
  SESSILE_CHECK(r->format >= 0, SESSILE_ERR_USAGE, "%s: the PLY header has no format line", r->what);
  return SESSILE_OK;
}

/* One scalar of type t; 0, or -1 at the end of data or on a bad token. */
static int read_value(reader *r, ptype t, double *v) {
  if (r->format == 0) {
    while (r->at < r->n && (r->d[r->at] == ' ' || r->d[r->at] == '\t' || r->d[r->at] == '\n' ||
                            r->d[r->at] == '\r'))
      r->at++;
    char tok[64];
    size_t k = 0;
    while (r->at < r->n && k + 1 < sizeof tok && r->d[r->at] > ' ') tok[k++] = (char)r->d[r->at++];
    tok[k] = 0;
    if (k == 0) return -1;
    char *end = NULL;
    *v = strtod(tok, &end);
    return end && *end == 0 ? 0 : -1;
  }
  size_t sz = type_size(t);
  if (r->n - r->at < sz) return -1;
  unsigned char b[8];
  memcpy(b, r->d + r->at, sz);
  r->at += sz;
  if (r->format == 2)
    for (size_t i = 0; i < sz / 2; i++) {
      unsigned char x = b[i];
      b[i] = b[sz - 1 - i];
      b[sz - 1 - i] = x;
    }
  /* The host is little-endian (x86, arm64 as Debian builds them). */
  switch (t) {
  case T_I8: { int8_t x; memcpy(&x, b, 1); *v = x; break; }
  case T_U8: *v = b[0]; break;
  case T_I16: { int16_t x; memcpy(&x, b, 2); *v = x; break; }
  case T_U16: { uint16_t x; memcpy(&x, b, 2); *v = x; break; }
  case T_I32: { int32_t x; memcpy(&x, b, 4); *v = x; break; }
  case T_U32: { uint32_t x; memcpy(&x, b, 4); *v = x; break; }
  case T_F32: { float x; memcpy(&x, b, 4); *v = x; break; }
  case T_F64: { double x; memcpy(&x, b, 8); *v = x; break; }
  default: return -1;
  }
  return 0;
}

/* The fewest bytes one record of e can take: a count too large for the
 * file is refused before allocating. */
static size_t min_record(const reader *r, const elem *e) {
  if (r->format == 0) return 2; /* one character and a separator per record at least */
  size_t s = 0;
  for (int i = 0; i < e->nprop; i++)
    s += e->p[i].count_type != T_NONE ? type_size(e->p[i].count_type) : type_size(e->p[i].type);
  return s ? s : 1;
}

static int find_prop(const elem *e, const char *name) {
  for (int i = 0; i < e->nprop; i++)
    if (strcmp(e->p[i].name, name) == 0) return i;
  return -1;
}

static sessile_status read_vertices(reader *r, const elem *e, sessile_render_mesh *m) {
  int ix = find_prop(e, "x"), iy = find_prop(e, "y"), iz = find_prop(e, "z");
  SESSILE_CHECK(ix >= 0 && iy >= 0 && iz >= 0, SESSILE_ERR_USAGE,
                "%s: the vertex element has no x, y and z properties", r->what);
  int in[3] = {find_prop(e, "nx"), find_prop(e, "ny"), find_prop(e, "nz")};
  int has_n = in[0] >= 0 && in[1] >= 0 && in[2] >= 0;
  int slot[MAXPROP]; /* property index -> kept property, -1 */
  int nkeep = 0;
  for (int i = 0; i < e->nprop; i++) {
    slot[i] = -1;
    SESSILE_CHECK(e->p[i].count_type == T_NONE || (i != ix && i != iy && i != iz), SESSILE_ERR_USAGE,
                  "%s: vertex coordinate %s is a list", r->what, e->p[i].name);
    if (e->p[i].count_type != T_NONE || i == ix || i == iy || i == iz) continue;
    if (has_n && (i == in[0] || i == in[1] || i == in[2])) continue;
    slot[i] = nkeep++;
  }
  uint32_t nv = (uint32_t)e->count;
  m->nv = nv;
  m->pos = malloc((size_t)nv * 3 * sizeof(float) + 1);
  if (has_n) m->normal = malloc((size_t)nv * 3 * sizeof(float) + 1);
  m->prop_names = calloc((size_t)nkeep + 1, sizeof(char *));
  m->props = calloc((size_t)nkeep + 1, sizeof(float *));
  SESSILE_CHECK(m->pos && (!has_n || m->normal) && m->prop_names && m->props, SESSILE_ERR_NO_MEMORY,
                "%s: out of host memory for %u vertices", r->what, nv);
  m->has_file_normals = has_n;
  for (int i = 0; i < e->nprop; i++) {
    if (slot[i] < 0) continue;
    m->prop_names[slot[i]] = strdup(e->p[i].name);
    m->props[slot[i]] = malloc((size_t)nv * sizeof(float) + 1);
    m->nprops = slot[i] + 1;
    SESSILE_CHECK(m->prop_names[slot[i]] && m->props[slot[i]], SESSILE_ERR_NO_MEMORY,
                  "%s: out of host memory for vertex properties", r->what);
  }
  for (uint32_t v = 0; v < nv; v++) {
    for (int i = 0; i < e->nprop; i++) {
      const prop *p = &e->p[i];
      double x;
      if (p->count_type != T_NONE) { /* a list in the vertex element: skipped */
        double c;
        SESSILE_CHECK(read_value(r, p->count_type, &c) == 0 && c >= 0 && c <= 65535, SESSILE_ERR_USAGE,
                      "%s: vertex %u: bad list %s", r->what, v, p->name);
        for (int k = 0; k < (int)c; k++)
          SESSILE_CHECK(read_value(r, p->type, &x) == 0, SESSILE_ERR_USAGE,
                        "%s: vertex %u: the file ends inside list %s", r->what, v, p->name);
        continue;
      }
      SESSILE_CHECK(read_value(r, p->type, &x) == 0, SESSILE_ERR_USAGE,
                    "%s: vertex %u of %u: missing or malformed %s", r->what, v, nv, p->name);
      if (i == ix) m->pos[3 * v] = (float)x;
      else if (i == iy) m->pos[3 * v + 1] = (float)x;
      else if (i == iz) m->pos[3 * v + 2] = (float)x;
      else if (has_n && i == in[0]) m->normal[3 * v] = (float)x;
      else if (has_n && i == in[1]) m->normal[3 * v + 1] = (float)x;
      else if (has_n && i == in[2]) m->normal[3 * v + 2] = (float)x;
      else if (slot[i] >= 0) m->props[slot[i]][v] = (float)x;
    }
  }
  return SESSILE_OK;
}

static sessile_status read_faces(reader *r, const elem *e, tri_list *tl) {
  int il = find_prop(e, "vertex_indices");
  if (il < 0) il = find_prop(e, "vertex_index");
  SESSILE_CHECK(il >= 0 && e->p[il].count_type != T_NONE, SESSILE_ERR_USAGE,
                "%s: the face element has no vertex_indices list", r->what);
  uint32_t poly[256];
  for (uint64_t f = 0; f < e->count; f++) {
    for (int i = 0; i < e->nprop; i++) {
      const prop *p = &e->p[i];
      double x, c = 1;
      if (p->count_type != T_NONE)
        SESSILE_CHECK(read_value(r, p->count_type, &c) == 0 && c >= 0 && c <= 65535, SESSILE_ERR_USAGE,
                      "%s: face %llu: bad list count of %s", r->what, (unsigned long long)f, p->name);
      if (i != il) {
        for (int k = 0; k < (int)c; k++)
          SESSILE_CHECK(read_value(r, p->type, &x) == 0, SESSILE_ERR_USAGE,
                        "%s: face %llu: missing %s", r->what, (unsigned long long)f, p->name);
        continue;
      }
      SESSILE_CHECK(c <= 256, SESSILE_ERR_USAGE, "%s: face %llu has %d vertices (at most 256)",
                    r->what, (unsigned long long)f, (int)c);
      for (int k = 0; k < (int)c; k++) {
        SESSILE_CHECK(read_value(r, p->type, &x) == 0, SESSILE_ERR_USAGE,
                      "%s: face %llu: missing or malformed vertex index", r->what,
                      (unsigned long long)f);
        SESSILE_CHECK(x >= 0 && x < 4294967295.0 && x == floor(x), SESSILE_ERR_USAGE,
                      "%s: face %llu: vertex index %g is not a valid index", r->what,
                      (unsigned long long)f, x);
        poly[k] = (uint32_t)x;
      }
      if (c >= 3)
        SESSILE_CHECK(tri_list_fan(tl, poly, (uint32_t)c) == 0, SESSILE_ERR_NO_MEMORY,
                      "%s: out of host memory for faces", r->what);
    }
  }
  return SESSILE_OK;
}

static sessile_status skip_element(reader *r, const elem *e) {
  for (uint64_t k = 0; k < e->count; k++)
    for (int i = 0; i < e->nprop; i++) {
      double x, c = 1;
      if (e->p[i].count_type != T_NONE)
        SESSILE_CHECK(read_value(r, e->p[i].count_type, &c) == 0 && c >= 0 && c <= 65535,
                      SESSILE_ERR_USAGE, "%s: element %s: bad list", r->what, e->name);
      for (int j = 0; j < (int)c; j++)
        SESSILE_CHECK(read_value(r, e->p[i].type, &x) == 0, SESSILE_ERR_USAGE,
                      "%s: element %s ends early", r->what, e->name);
    }
  return SESSILE_OK;
}

sessile_status mesh_read_ply_(const char *what, const unsigned char *data, size_t bytes,
                              sessile_render_mesh *m) {
  reader r = {.what = what, .d = data, .n = bytes, .at = 0};
  elem *el = calloc(MAXELEM, sizeof *el);
  SESSILE_CHECK(el, SESSILE_ERR_NO_MEMORY, "out of host memory");
  int nel = 0, seen_v = 0, seen_f = 0;
  tri_list tl = {0};
  sessile_status s = parse_header(&r, el, &nel);
  for (int i = 0; s == SESSILE_OK && i < nel; i++) {
    const elem *e = &el[i];
    size_t left = r.n - r.at;
    if (e->count > 0 && e->count > left / min_record(&r, e)) {
      s = sessile_error_set(SESSILE_ERR_USAGE,
                            "%s: element %s declares %llu records but only %zu bytes follow",
                            what, e->name, (unsigned long long)e->count, left);
      break;
    }
    if (strcmp(e->name, "vertex") == 0 && !seen_v) {
      seen_v = 1;
      if (e->count >= UINT32_MAX) {
        s = sessile_error_set(SESSILE_ERR_USAGE, "%s: %llu vertices (at most 2^32 - 2)", what,
                              (unsigned long long)e->count);
        break;
      }
      s = read_vertices(&r, e, m);
    } else if (strcmp(e->name, "face") == 0 && !seen_f) {
      seen_f = 1;
      s = read_faces(&r, e, &tl);
    } else {
      s = skip_element(&r, e);
    }
  }
  if (s == SESSILE_OK && !seen_v)
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s: the PLY file has no vertex element", what);
  if (s == SESSILE_OK && tl.n > UINT32_MAX / 3)
    s = sessile_error_set(SESSILE_ERR_USAGE, "%s: %zu triangles (too many)", what, tl.n);
  if (s == SESSILE_OK) {
    m->tri = tl.tri;
    m->nf = (uint32_t)tl.n;
  } else {
    free(tl.tri);
  }
  free(el);
  return s;
}
