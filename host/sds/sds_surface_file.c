/* A model's starting surface from a PLY file (`surface = "FILE.ply"`,
 * docs/sds_rules.md): ASCII or binary little-endian, a `vertex` element with
 * x, y, z and a `face` element with a vertex_indices list of triangles;
 * other properties and elements are skipped.  Read whole through
 * sessile_read_small_file (a regular file, bounded); every count and index
 * checked against the bytes there are. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_surface_file.h"
#include "sessile/io.h"

#define MAX_PROPS 32
#define MAX_ELEMS 8

typedef struct prop {
  char name[64];
  int type, list, count_type; /* type: index into TYPES; list: a list with count_type counts */
} prop;
typedef struct elem {
  char name[64];
  uint64_t n;
  int np;
  prop p[MAX_PROPS];
} elem;

static const char *const TYPES[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                    "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
static const int SIZES[] = {1, 1, 2, 2, 4, 4, 4, 8};

static int type_of(const char *t) {
  for (int i = 0; i < 16; i++)
    if (!strcmp(t, TYPES[i])) return i % 8;
  return -1;
}

typedef struct rd {
  const char *path;
  const unsigned char *b, *end;
  int ascii;
} rd;

static sessile_status bad(const rd *r, const char *why) {
  return sessile_error_set(SESSILE_ERR_USAGE, "surface '%s': %s", r->path, why);
}

/* One value of type t: a text token (ascii) or little-endian bytes. */
static sessile_status value(rd *r, int t, double *out) {
  if (r->ascii) {
    while (r->b < r->end && (*r->b == ' ' || *r->b == '\t' || *r->b == '\n' || *r->b == '\r')) r->b++;
    char tok[64];
    size_t n = 0;
    while (r->b < r->end && n < sizeof tok - 1 && *r->b > ' ') tok[n++] = (char)*r->b++;
    tok[n] = 0;
    char *e = NULL;
    *out = strtod(tok, &e);
    if (!n || *e) return bad(r, "a number is missing or malformed in the body");
    return SESSILE_OK;
  }
  int sz = SIZES[t];
  if (r->end - r->b < sz) return bad(r, "the body is shorter than its header says");
  uint64_t u = 0;
  for (int i = 0; i < sz; i++) u |= (uint64_t)r->b[i] << (8 * i);
  r->b += sz;
  switch (t) {
  case 0: *out = (int8_t)u; break;
  case 1: *out = (uint8_t)u; break;
  case 2: *out = (int16_t)u; break;
  case 3: *out = (uint16_t)u; break;
  case 4: *out = (int32_t)u; break;
  case 5: *out = (uint32_t)u; break;
  case 6: {
    uint32_t w = (uint32_t)u;
    float f;
    memcpy(&f, &w, 4);
    *out = f;
    break;
  }
  default: memcpy(out, &u, 8);
  }
  return SESSILE_OK;
}

static sessile_status header(rd *r, elem *el, int *nel) {
  *nel = 0;
  char line[256];
  int first = 1, format = 0;
  for (;;) {
    const unsigned char *nl = memchr(r->b, '\n', (size_t)(r->end - r->b));
    if (!nl) return bad(r, "the header has no end_header line");
    size_t n = (size_t)(nl - r->b);
    if (n >= sizeof line) return bad(r, "a header line is longer than 255 characters");
    memcpy(line, r->b, n);
    line[n] = 0;
    if (n && line[n - 1] == '\r') line[n - 1] = 0;
    r->b = nl + 1;
    char a[64] = "", b[64] = "", c[64] = "", d[64] = "";
    int k = sscanf(line, "%63s %63s %63s %63s", a, b, c, d);
    if (first) {
      if (strcmp(a, "ply")) return bad(r, "not a PLY file (no 'ply' line)");
      first = 0;
    } else if (!strcmp(a, "end_header")) break;
    else if (!strcmp(a, "format")) {
      if (!strcmp(b, "ascii")) r->ascii = 1;
      else if (strcmp(b, "binary_little_endian")) return bad(r, "only ascii and binary_little_endian PLY are read");
      format = 1;
    } else if (!strcmp(a, "comment") || !strcmp(a, "obj_info")) continue;
    else if (!strcmp(a, "element")) {
      char *e = NULL;
      unsigned long long cnt = k >= 3 ? strtoull(c, &e, 10) : 0;
      if (k < 3 || *e || *nel >= MAX_ELEMS || cnt > 100000000ull) return bad(r, "a malformed or too large element line");
      elem *x = &el[(*nel)++];
      memset(x, 0, sizeof *x);
      snprintf(x->name, sizeof x->name, "%s", b);
      x->n = cnt;
    } else if (!strcmp(a, "property")) {
      if (!*nel || el[*nel - 1].np >= MAX_PROPS) return bad(r, "a property outside an element, or too many");
      prop *p = &el[*nel - 1].p[el[*nel - 1].np++];
      memset(p, 0, sizeof *p);
      if (!strcmp(b, "list")) {
        p->list = 1, p->count_type = type_of(c), p->type = type_of(d);
        if (k < 4 || p->count_type < 0 || p->type < 0) return bad(r, "a malformed list property");
        char name[64] = "";
        if (sscanf(line, "%*s %*s %*s %*s %63s", name) != 1) return bad(r, "a list property without a name");
        snprintf(p->name, sizeof p->name, "%s", name);
      } else {
        p->type = type_of(b);
        if (k < 3 || p->type < 0) return bad(r, "a malformed property line");
        snprintf(p->name, sizeof p->name, "%s", c);
      }
    } else return bad(r, "an unknown header line");
  }
  return format ? SESSILE_OK : bad(r, "the header has no format line");
}

sessile_status sds_read_surface_ply(const char *path, sessile_surface *out) {
  memset(out, 0, sizeof *out);
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(sessile_read_small_file(path, (size_t)256 << 20, "surface file", &text, &len));
  rd r = {path, (const unsigned char *)text, (const unsigned char *)text + len, 0};
  elem el[MAX_ELEMS];
  int nel = 0;
  sessile_status st = header(&r, el, &nel);
  const elem *ev = NULL, *ef = NULL;
  for (int i = 0; i < nel; i++) {
    if (!strcmp(el[i].name, "vertex")) ev = &el[i];
    if (!strcmp(el[i].name, "face")) ef = &el[i];
  }
  int ix[3] = {-1, -1, -1}, fl = -1;
  for (int i = 0; ev && i < ev->np; i++)
    for (int k = 0; k < 3; k++)
      if (!ev->p[i].list && !strcmp(ev->p[i].name, (const char *[]){"x", "y", "z"}[k])) ix[k] = i;
  for (int i = 0; ef && i < ef->np; i++)
    if (ef->p[i].list && (!strcmp(ef->p[i].name, "vertex_indices") || !strcmp(ef->p[i].name, "vertex_index"))) fl = i;
  if (st == SESSILE_OK && (!ev || !ef || ix[0] < 0 || ix[1] < 0 || ix[2] < 0 || fl < 0))
    st = bad(&r, "needs a vertex element with x, y, z and a face element with vertex_indices");
  if (st == SESSILE_OK && (ev->n < 4 || ef->n < 4 || ev->n > UINT32_MAX / 4 || ef->n > UINT32_MAX / 4))
    st = bad(&r, "a closed surface needs at least 4 vertices and 4 triangles");
  if (st == SESSILE_OK) st = sessile_surface_reserve(out, (uint32_t)ev->n, (uint32_t)ef->n);
  for (int e = 0; st == SESSILE_OK && e < nel; e++) {
    const elem *x = &el[e];
    for (uint64_t i = 0; st == SESSILE_OK && i < x->n; i++)
      for (int q = 0; st == SESSILE_OK && q < x->np; q++) {
        const prop *p = &x->p[q];
        double v = 0;
        if (!p->list) {
          st = value(&r, p->type, &v);
          for (int k = 0; x == ev && k < 3; k++)
            if (q == ix[k]) {
              if (!isfinite(v)) st = bad(&r, "a vertex coordinate is not finite");
              out->pos[3 * i + (uint64_t)k] = v;
            }
          continue;
        }
        double cnt = 0;
        st = value(&r, p->count_type, &cnt);
        if (st == SESSILE_OK && x == ef && q == fl && cnt != 3) st = bad(&r, "only triangles are read (a face has not 3 vertices)");
        if (st == SESSILE_OK && !(cnt >= 0 && cnt <= 1000)) st = bad(&r, "a list longer than 1000");
        for (int j = 0; st == SESSILE_OK && j < (int)cnt; j++) {
          st = value(&r, p->type, &v);
          if (st == SESSILE_OK && x == ef && q == fl) {
            if (!(v >= 0 && v < (double)ev->n && v == floor(v))) st = bad(&r, "a face names a vertex that does not exist");
            else out->tri[3 * i + (uint64_t)j] = (uint32_t)v;
          }
        }
      }
  }
  free(text);
  if (st != SESSILE_OK) {
    sessile_surface_free(out);
    return st;
  }
  out->nv = (uint32_t)ev->n, out->nf = (uint32_t)ef->n;
  return SESSILE_OK;
}
