/* GLSL compiled at run time by glslang's library (sessile_glsl_to_spirv):
 * for kernels whose source is generated from user input at load time, such
 * as an SDS model's rules (docs/design.md, "Kernels compiled at run time").
 * glslang 12's C interface takes no include callbacks, so the #include
 * lines are resolved here from the embedded include files, each file once
 * (they all carry include guards, so once is what the build's glslang
 * does too). */
#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "gpu_internal.h"

typedef struct text {
  char *s;
  size_t n, cap;
  const char *seen[64]; /* files included so far */
  int nseen;
  char *err;
  size_t nerr;
} text;

static int put(text *t, const char *s, size_t n) {
  if (t->n + n + 1 > t->cap) {
    size_t cap = t->cap ? 2 * t->cap : 16384;
    while (cap < t->n + n + 1) cap *= 2;
    char *p = realloc(t->s, cap);
    if (!p) return snprintf(t->err, t->nerr, "out of host memory"), -1;
    t->s = p, t->cap = cap;
  }
  memcpy(t->s + t->n, s, n);
  t->n += n;
  t->s[t->n] = 0;
  return 0;
}

/* Appends src, each `#include "name"` line replaced by that file (once). */
static int expand(text *t, const char *src, int depth) {
  if (depth > 16) return snprintf(t->err, t->nerr, "includes nested deeper than 16"), -1;
  for (const char *l = src; *l;) {
    const char *e = strchr(l, '\n');
    size_t n = e ? (size_t)(e - l) + 1 : strlen(l);
    const char *p = l;
    while (*p == ' ' || *p == '\t') p++;
    if (strncmp(p, "#include", 8) == 0) {
      const char *q = strchr(p, '"'), *r = q ? strchr(q + 1, '"') : NULL;
      if (!q || !r || r - q - 1 >= 128 || (e && r > e))
        return snprintf(t->err, t->nerr, "an #include line without a \"name\""), -1;
      char name[128];
      memcpy(name, q + 1, (size_t)(r - q - 1));
      name[r - q - 1] = 0;
      const char *inc = sessile_glsl_source_find(name);
      if (!inc) return snprintf(t->err, t->nerr, "no embedded include file \"%s\"", name), -1;
      int seen = 0;
      for (int i = 0; i < t->nseen; i++) seen |= t->seen[i] == inc;
      if (!seen) {
        if (t->nseen == (int)(sizeof t->seen / sizeof t->seen[0]))
          return snprintf(t->err, t->nerr, "more than 64 include files"), -1;
        t->seen[t->nseen++] = inc;
        if (expand(t, inc, depth + 1) || put(t, "\n", 1)) return -1;
      }
    } else if (strncmp(p, "#extension GL_GOOGLE_include_directive", 38) != 0 && put(t, l, n)) {
      return -1;
    }
    l += n;
  }
  return 0;
}

sessile_status sessile_glsl_to_spirv(const char *kernel_name, int f64, const char *body, uint32_t **words,
                                     size_t *nwords, char *log, size_t nlog) {
  *words = NULL, *nwords = 0;
  char dummy[8];
  if (!log) log = dummy, nlog = sizeof dummy;
  log[0] = 0;
  /* SESSILE_KERNEL_<name as a C identifier>, as cmake/EmbedShaders.cmake defines it */
  char id[96];
  size_t i = 0;
  for (; kernel_name[i] && i + 1 < sizeof id; i++) {
    char c = kernel_name[i];
    id[i] = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ? c : '_';
  }
  id[i] = 0;
  text t = {.err = log, .nerr = nlog};
  char head[256];
  int hn = snprintf(head, sizeof head, "#version 450\n#define SESSILE_F64 %d\n#define SESSILE_KERNEL_%s 1\n", f64 ? 1 : 0,
                    id);
  if (put(&t, head, (size_t)hn) || expand(&t, body, 0)) {
    free(t.s);
    return sessile_error_set(SESSILE_ERR_USAGE, "GLSL: %s", log);
  }
  glslang_input_t in = {
      .language = GLSLANG_SOURCE_GLSL,
      .stage = GLSLANG_STAGE_COMPUTE,
      .client = GLSLANG_CLIENT_VULKAN,
      .client_version = GLSLANG_TARGET_VULKAN_1_1,
      .target_language = GLSLANG_TARGET_SPV,
      .target_language_version = GLSLANG_TARGET_SPV_1_3,
      .code = t.s,
      .default_version = 450,
      .default_profile = GLSLANG_NO_PROFILE,
      .messages = GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT,
      .resource = glslang_default_resource(),
  };
  sessile_status st = SESSILE_OK;
  glslang_initialize_process();
  glslang_shader_t *sh = glslang_shader_create(&in);
  glslang_program_t *pr = NULL;
  if (!sh || !glslang_shader_preprocess(sh, &in) || !glslang_shader_parse(sh, &in)) {
    snprintf(log, nlog, "%s", sh ? glslang_shader_get_info_log(sh) : "glslang could not start");
    st = SESSILE_ERR_INTERNAL;
  } else if (!(pr = glslang_program_create())) {
    snprintf(log, nlog, "glslang could not start");
    st = SESSILE_ERR_INTERNAL;
  } else {
    glslang_program_add_shader(pr, sh);
    if (!glslang_program_link(pr, GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT)) {
      snprintf(log, nlog, "%s", glslang_program_get_info_log(pr));
      st = SESSILE_ERR_INTERNAL;
    } else {
      glslang_program_SPIRV_generate(pr, GLSLANG_STAGE_COMPUTE);
      size_t n = glslang_program_SPIRV_get_size(pr);
      uint32_t *w = n ? malloc(n * sizeof *w) : NULL;
      if (!w) {
        snprintf(log, nlog, "out of host memory for %zu SPIR-V words", n);
        st = SESSILE_ERR_NO_MEMORY;
      } else {
        glslang_program_SPIRV_get(pr, w);
        *words = w, *nwords = n;
      }
    }
  }
  if (pr) glslang_program_delete(pr);
  if (sh) glslang_shader_delete(sh);
  glslang_finalize_process();
  free(t.s);
  if (st != SESSILE_OK) return sessile_error_set(st, "GLSL: %s", log);
  return SESSILE_OK;
}
