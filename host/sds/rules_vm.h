/* The rules compiled to bytecode at model load (docs/sds_rules.md,
 * "Bytecode"): one word array that both the plain-C interpreter
 * (rules_vm.c) and the kernel (shaders/sds/rules_vm.glsl) read, and the
 * constants it refers to.  The compiler (rules_compile.c) rebuilds
 * muparser's own bytecode, its optimiser included, so that both evaluate
 * the same operations in the same order as the host's muparser. */
#ifndef SESSILE_SDS_RULES_VM_H
#define SESSILE_SDS_RULES_VM_H
#include <stddef.h>
#include <stdint.h>
#include "sds_kernels.h"

/* One instruction is two words: op | a << 8, then b. */
enum sds_vm_op {
  VM_END = 0,
  VM_VAL,    /* push k[b] */
  VM_VAR,    /* push slot a */
  VM_VARMUL, /* push slot a * k[b] + k[b + 1] (muparser's cmVARMUL) */
  VM_POW2,   /* push slot a squared, cubed, to the 4th (x * x * x ...) */
  VM_POW3,
  VM_POW4,
  VM_ADD, VM_SUB, VM_MUL, VM_DIV, VM_POW,
  VM_LT, VM_GT, VM_LE, VM_GE, VM_NE, VM_EQ, VM_AND, VM_OR,
  VM_IF,  /* pop; jump to b when 0 */
  VM_JMP, /* jump to b */
  VM_FUN, /* function a of fixed arity (sds_vm_fun) */
  VM_SUM, /* a arguments */
  VM_AVG,
  VM_MIN,
  VM_MAX,
  VM_OPS
};

/* muparser's functions; those after VM_F_DEVICE have no fp64 version on
 * the device (GLSL has no double exp, log, pow or trigonometry). */
enum sds_vm_fun {
  VM_F_NEG = 0, VM_F_ABS, VM_F_SIGN, VM_F_RINT, VM_F_SQRT,
  VM_F_DEVICE,
  VM_F_SIN = VM_F_DEVICE, VM_F_COS, VM_F_TAN, VM_F_ASIN, VM_F_ACOS, VM_F_ATAN, VM_F_SINH, VM_F_COSH,
  VM_F_TANH, VM_F_ASINH, VM_F_ACOSH, VM_F_ATANH, VM_F_LOG2, VM_F_LOG10, VM_F_LOG, VM_F_EXP, VM_F_ATAN2,
  VM_F_COUNT
};

/* SDS_VM_STACK (shaders/sds/kernels.def): the stack an expression may use,
 * checked by the compiler, so neither interpreter checks it at run time
 * (the kernel's array has this size). */
#define SDS_VM_SLOTS 52 /* SDS_SLOTS: radius, volume, time, surface, 16 morphogens, 32 states */

/* prog[0] = rules; prog[1 + r] = where rule r's record starts:
 *   cond_pc, nact, then per action (kind | target << 8 | (sign < 0) << 16, value_pc)
 * value_pc is 0 for divide and reset (no value); code follows the records. */
typedef struct sds_prog {
  uint32_t *w;
  uint32_t nw;
  double *k;
  uint32_t nk;
  int depth;      /* the deepest stack of any expression */
  int device;     /* 1: every operation has a device version */
  char why[320];  /* when device is 0: the first operation that has none, with its rule */
} sds_prog;

struct sessile_sds_model;
/* Compiles every rule of a parsed model.  NULL with *why set when an
 * expression uses what the bytecode does not rebuild (the host evaluates
 * such a model; a device run refuses it with the message). */
sds_prog *sds_prog_compile(const struct sessile_sds_model *m, char *why, size_t nwhy);
void sds_prog_free(sds_prog *p);
/* Runs the expression at pc over slots (SDS_VM_SLOTS values). */
double sds_vm_run(const sds_prog *p, uint32_t pc, const double *slots);
/* A function of the list, as muparser computes it (also for folding). */
double sds_vm_fun1(int f, double v);
#endif
