/* The rules' bytecode as GLSL, for the generated rules kernel
 * (rules_glsl.c; docs/sds_rules.md, "Generated kernel"). */
#ifndef SESSILE_SDS_RULES_GLSL_H
#define SESSILE_SDS_RULES_GLSL_H
#include <stddef.h>
#include "rules_vm.h"
#include "sessile/sds/sds_process.h"

/* The body of a kernel (sessile_kernel_create_glsl's): the shader file
 * `shell` ("rules_vm.glsl" for the declaration of rules_vm,
 * "rules_morph.glsl" for rules_morph's) with evaluate_gen(c), the rules of p
 * written out.  malloc'ed; NULL with *why set for bytecode it does not know
 * (the interpreter runs any that the compiler wrote, so a NULL here is a
 * fault of ours) or out of memory. */
char *sds_rules_glsl(const sds_prog *p, const char *shell, char *why, size_t nwhy);
#endif
