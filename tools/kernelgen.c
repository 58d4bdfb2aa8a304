/* kernelgen: shaders/<layer>/kernels.def -> <layer>_kernels.{h,c,glsl}.
 *
 *   kernelgen DEF LAYER OUTDIR
 *
 * One definition per kernel (bindings, push constants, local size, precision)
 * and the constants shared by host and shaders; both the C side (descriptor
 * table, push structs with static asserts, enums) and the GLSL side (push
 * blocks with explicit offsets, binding declarations, #defines) are written
 * from it, so they cannot drift.  The format is in docs/design.md ("Declaring
 * a kernel").  Built as a host tool: no Python or other dependency at build
 * time.  No heap use, so it runs clean under the sanitizer build too. */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { NAME = 64, MAXTOK = 8, MAXF = 32, MAXB = 24, /* SESSILE_MAX_BINDINGS */ MAXP = 32, MAXK = 64, MAXC = 256 };

typedef struct { char type[8], name[NAME]; unsigned off; } field;
typedef struct { char cname[NAME], gname[NAME]; field f[MAXF]; int nf; unsigned size; } push_t;
typedef struct { int texel; char name[NAME], elem[16], access[4], fmt[16]; } binding;
typedef struct {
  char id[NAME], name[NAME];
  int per_prec, push; /* push: index into pushes, -1 for none */
  unsigned local;
  binding b[MAXB];
  int nb;
} kernel_t;
typedef struct { char name[NAME], type[8], value[NAME], note[160]; } const_t;

static push_t pushes[MAXP];
static kernel_t kernels[MAXK];
static const_t consts[MAXC];
static int npush, nkern, nconst;
static char enum_type[NAME], enum_count[NAME];
static const char *def_path, *layer;
static int lineno;

static void die(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "%s:%d: ", def_path, lineno);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  exit(1);
}

static void copy(char *dst, size_t n, const char *src) {
  if (strlen(src) >= n) die("\"%s\" is too long", src);
  memcpy(dst, src, strlen(src) + 1);
}

/* Size and alignment of a push field; "real" is 8-byte aligned in both
 * precisions (sessile_push_real), so its offset is the same in f32 and f64. */
static unsigned field_size(const char *t) {
  if (!strcmp(t, "uint") || !strcmp(t, "int") || !strcmp(t, "float")) return 4;
  if (!strcmp(t, "double") || !strcmp(t, "real")) return 8;
  die("unknown push field type \"%s\" (uint, int, float, double, real)", t);
  return 0;
}

static const char *c_type(const char *t) {
  return !strcmp(t, "uint") ? "uint32_t" : !strcmp(t, "int") ? "int32_t" : !strcmp(t, "float") ? "float"
       : !strcmp(t, "double") ? "double" : "sessile_push_real";
}

static const char *glsl_type(const char *t) { return !strcmp(t, "real") ? "REAL" : t; }

static int find_push(const char *cname) {
  for (int i = 0; i < npush; i++)
    if (!strcmp(pushes[i].cname, cname)) return i;
  return -1;
}

static const const_t *find_const(const char *name) {
  for (int i = 0; i < nconst; i++)
    if (!strcmp(consts[i].name, name)) return &consts[i];
  return NULL;
}

static int is_ident(const char *s) {
  if (!isalpha((unsigned char)*s) && *s != '_') return 0;
  for (; *s; s++)
    if (!isalnum((unsigned char)*s) && *s != '_') return 0;
  return 1;
}

static void close_push(push_t *p) {
  unsigned off = 0, align = 4;
  for (int i = 0; i < p->nf; i++) {
    unsigned sz = field_size(p->f[i].type);
    off = (off + sz - 1) / sz * sz;
    p->f[i].off = off;
    off += sz;
    if (sz > align) align = sz;
  }
  p->size = (off + align - 1) / align * align;
  if (p->size > 128) die("push block %s is %u bytes (at most 128)", p->cname, p->size);
}

/* Splits a line into tokens; the text after '#' goes to *note. */
static int tokens(char *line, char *tok[MAXTOK], const char **note) {
  char *hash = strchr(line, '#');
  *note = "";
  if (hash) {
    *hash = 0;
    for (*note = hash + 1; **note == ' '; (*note)++) {}
    hash[1 + strcspn(hash + 1, "\r\n")] = 0;
  }
  int n = 0;
  for (char *t = strtok(line, " \t\r\n"); t; t = strtok(NULL, " \t\r\n")) {
    if (n == MAXTOK) die("too many words on one line");
    tok[n++] = t;
  }
  return n;
}

static void parse(FILE *f) {
  char line[512], *tok[MAXTOK];
  const char *note;
  push_t *p = NULL;
  kernel_t *k = NULL;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    int n = tokens(line, tok, &note);
    if (n == 0) continue;
    if (p) { /* inside push ... end */
      if (n == 1 && !strcmp(tok[0], "end")) { close_push(p); p = NULL; continue; }
      if (n != 2 || !is_ident(tok[1])) die("push field: TYPE NAME, or end");
      if (p->nf == MAXF) die("too many push fields");
      field_size(tok[0]);
      copy(p->f[p->nf].type, 8, tok[0]);
      copy(p->f[p->nf++].name, NAME, tok[1]);
    } else if (k) { /* inside kernel ... end */
      if (n == 1 && !strcmp(tok[0], "end")) { k = NULL; continue; }
      if (k->nb == MAXB) die("kernel %s: more than %d bindings", k->id, MAXB);
      binding *b = &k->b[k->nb++];
      if (n == 4 && !strcmp(tok[0], "storage")) {
        if (strcmp(tok[3], "ro") && strcmp(tok[3], "wo") && strcmp(tok[3], "rw") && strcmp(tok[3], "rwc"))
          die("storage access must be ro, wo, rw or rwc (rw and coherent)");
        copy(b->elem, sizeof b->elem, tok[2]);
        copy(b->access, sizeof b->access, tok[3]);
      } else if (n == 3 && !strcmp(tok[0], "texel")) {
        if (strcmp(tok[2], "r32ui") && strcmp(tok[2], "rg32ui") && strcmp(tok[2], "rgba32ui") &&
            strcmp(tok[2], "real"))
          die("texel format must be r32ui, rg32ui, rgba32ui or real");
        b->texel = 1;
        copy(b->fmt, sizeof b->fmt, tok[2]);
      } else {
        die("binding: storage NAME ELEMTYPE ro|wo|rw, texel NAME FORMAT, or end");
      }
      if (!is_ident(tok[1])) die("binding name \"%s\" is not an identifier", tok[1]);
      copy(b->name, NAME, tok[1]);
    } else if (!strcmp(tok[0], "enum") && n == 3) {
      copy(enum_type, NAME, tok[1]);
      copy(enum_count, NAME, tok[2]);
    } else if (!strcmp(tok[0], "const") && n == 4) {
      if (nconst == MAXC) die("too many constants");
      if (strcmp(tok[2], "int") && strcmp(tok[2], "uint") && strcmp(tok[2], "real"))
        die("constant type must be int, uint or real");
      if (find_const(tok[1])) die("constant %s declared twice", tok[1]);
      const_t *c = &consts[nconst++];
      copy(c->name, NAME, tok[1]);
      copy(c->type, 8, tok[2]);
      copy(c->value, NAME, tok[3]);
      copy(c->note, sizeof c->note, note);
    } else if (!strcmp(tok[0], "push") && n == 3) {
      if (npush == MAXP) die("too many push blocks");
      if (find_push(tok[1]) >= 0) die("push block %s declared twice", tok[1]);
      p = &pushes[npush++];
      copy(p->cname, NAME, tok[1]);
      copy(p->gname, NAME, tok[2]);
    } else if (!strcmp(tok[0], "kernel") && n == 6) {
      if (nkern == MAXK) die("too many kernels");
      k = &kernels[nkern++];
      copy(k->id, NAME, tok[1]);
      copy(k->name, NAME, tok[2]);
      if (strcmp(tok[3], "real") && strcmp(tok[3], "once")) die("precision must be real or once");
      k->per_prec = !strcmp(tok[3], "real");
      const const_t *lc = find_const(tok[4]);
      k->local = (unsigned)strtoul(lc ? lc->value : tok[4], NULL, 0);
      if (k->local == 0) die("kernel %s: local size \"%s\" is not a positive number", k->id, tok[4]);
      k->push = -1;
      if (strcmp(tok[5], "-") && (k->push = find_push(tok[5])) < 0)
        die("kernel %s: no push block %s declared above", k->id, tok[5]);
    } else {
      die("expected enum TYPE COUNT, const NAME TYPE VALUE, push CTYPE GLSLNAME, or "
          "kernel ID NAME real|once LOCAL PUSH|-");
    }
  }
  if (p || k) die("missing end");
  if (!enum_type[0]) die("missing the line: enum TYPE COUNT");
}

static FILE *open_out(const char *dir, const char *ext) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s_kernels.%s", dir, layer, ext);
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "kernelgen: cannot write %s\n", path);
    exit(1);
  }
  return f;
}

static const char *kind_of(const binding *b) {
  if (!b->texel) return "SESSILE_BINDING_STORAGE";
  return !strcmp(b->fmt, "r32ui") ? "SESSILE_TEXEL_R32UI" : !strcmp(b->fmt, "rg32ui") ? "SESSILE_TEXEL_RG32UI"
       : !strcmp(b->fmt, "rgba32ui") ? "SESSILE_TEXEL_RGBA32UI" : "SESSILE_TEXEL_REAL";
}

static void write_h(FILE *f) {
  fprintf(f, "/* Generated by tools/kernelgen.c from shaders/%s/kernels.def: edit that file. */\n"
             "#ifndef SESSILE_%s_KERNELS_H\n#define SESSILE_%s_KERNELS_H\n\n"
             "#include <stddef.h>\n#include <stdint.h>\n#include \"sessile/gpu/gpu.h\"\n\n",
          layer, layer, layer);
  for (int i = 0; i < nconst; i++) {
    const const_t *c = &consts[i];
    if (!strcmp(c->type, "real")) fprintf(f, "#define %s %s", c->name, c->value);
    else fprintf(f, "enum { %s = %s };", c->name, c->value);
    fprintf(f, c->note[0] ? " /* %s */\n" : "\n", c->note);
  }
  for (int i = 0; i < npush; i++) {
    const push_t *p = &pushes[i];
    fprintf(f, "\n/* GLSL: push_constant block %s */\ntypedef struct %s {\n", p->gname, p->cname);
    for (int j = 0; j < p->nf; j++) fprintf(f, "  %s %s;\n", c_type(p->f[j].type), p->f[j].name);
    fprintf(f, "} %s;\n_Static_assert(sizeof(%s) == %u, \"%s: %u bytes as in GLSL\");\n", p->cname,
            p->cname, p->size, p->cname, p->size);
    for (int j = 0; j < p->nf; j++)
      fprintf(f, "_Static_assert(offsetof(%s, %s) == %u, \"%s.%s at offset %u as in GLSL\");\n",
              p->cname, p->f[j].name, p->f[j].off, p->cname, p->f[j].name, p->f[j].off);
  }
  fprintf(f, "\ntypedef enum {\n");
  for (int i = 0; i < nkern; i++) fprintf(f, "  %s,\n", kernels[i].id);
  fprintf(f, "  %s\n} %s;\n\n/* Every %s kernel, indexed by %s. */\n"
             "extern const sessile_kernel_decl sessile_%s_kernels[%s];\n\n#endif\n",
          enum_count, enum_type, layer, enum_type, layer, enum_count);
}

static void write_c(FILE *f) {
  fprintf(f, "/* Generated by tools/kernelgen.c from shaders/%s/kernels.def: edit that file. */\n"
             "#include \"%s_kernels.h\"\n\n", layer, layer);
  for (int i = 0; i < nkern; i++) {
    const kernel_t *k = &kernels[i];
    if (!k->nb) continue;
    fprintf(f, "static const sessile_binding_decl bind_%s[] = {\n", k->id);
    for (int j = 0; j < k->nb; j++)
      fprintf(f, "    {\"%s\", %s, %d},\n", k->b[j].name, kind_of(&k->b[j]),
              k->b[j].texel || !strcmp(k->b[j].access, "ro"));
    fprintf(f, "};\n");
  }
  fprintf(f, "\nconst sessile_kernel_decl sessile_%s_kernels[%s] = {\n", layer, enum_count);
  for (int i = 0; i < nkern; i++) {
    const kernel_t *k = &kernels[i];
    char push[NAME + 16] = "0";
    if (k->push >= 0) snprintf(push, sizeof push, "sizeof(%s)", pushes[k->push].cname);
    fprintf(f, "    [%s] = {\"%s/%s\", %d, %s%s, %s, %u, %d},\n", k->id, layer, k->name, k->nb,
            k->nb ? "bind_" : "NULL", k->nb ? k->id : "", push, k->local, k->per_prec);
  }
  fprintf(f, "};\n");
}

static void write_glsl(FILE *f) {
  fprintf(f, "// Generated by tools/kernelgen.c from shaders/%s/kernels.def: edit that file.\n"
             "// The build defines SESSILE_KERNEL_<layer>_<name> for each .comp, which\n"
             "// selects its push block and bindings below.\n"
             "#ifndef SESSILE_%s_KERNELS_GLSL\n#define SESSILE_%s_KERNELS_GLSL\n"
             "#include \"sessile.glsl\"\n\n", layer, layer, layer);
  for (int i = 0; i < nconst; i++) {
    const const_t *c = &consts[i];
    fprintf(f, "#define %s %s%s", c->name, c->value, !strcmp(c->type, "uint") ? "u" : "");
    fprintf(f, c->note[0] ? "  // %s\n" : "\n", c->note);
  }
  for (int i = 0; i < nkern; i++) {
    const kernel_t *k = &kernels[i];
    fprintf(f, "\n#if defined(SESSILE_KERNEL_%s_%s)\n#define SESSILE_KERNEL_DECLARED 1\n", layer, k->name);
    if (k->push >= 0) {
      const push_t *p = &pushes[k->push];
      fprintf(f, "layout(push_constant) uniform %s {\n", p->gname);
      for (int j = 0; j < p->nf; j++)
        fprintf(f, "  layout(offset = %u) %s %s;\n", p->f[j].off, glsl_type(p->f[j].type), p->f[j].name);
      fprintf(f, "} pc;\n");
    }
    for (int j = 0; j < k->nb; j++) {
      const binding *b = &k->b[j];
      if (b->texel) {
        fprintf(f, "layout(binding = %d) uniform usamplerBuffer %s;\n", j, b->name);
        continue;
      }
      const char *q = !strcmp(b->access, "ro")    ? "readonly "
                      : !strcmp(b->access, "wo")  ? "writeonly "
                      : !strcmp(b->access, "rwc") ? "coherent "
                                                  : "";
      fprintf(f, "layout(std430, binding = %d) %sbuffer B_%s { %s %s[]; };\n", j, q, b->name,
              b->elem, b->name);
    }
    fprintf(f, "#endif\n");
  }
  fprintf(f, "\n#ifndef SESSILE_KERNEL_DECLARED\n"
             "#error \"this kernel has no declaration in shaders/%s/kernels.def\"\n#endif\n#endif\n",
          layer);
}

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: kernelgen DEF LAYER OUTDIR\n");
    return 2;
  }
  def_path = argv[1];
  layer = argv[2];
  FILE *in = fopen(def_path, "r");
  if (!in) {
    fprintf(stderr, "kernelgen: cannot read %s\n", def_path);
    return 1;
  }
  parse(in);
  fclose(in);
  FILE *f = open_out(argv[3], "h");
  write_h(f);
  fclose(f);
  f = open_out(argv[3], "c");
  write_c(f);
  fclose(f);
  f = open_out(argv[3], "glsl");
  write_glsl(f);
  fclose(f);
  return 0;
}
