/* The table of embedded grammars, generated at configure time
 * (cmake/EmbedTexts.cmake) from host/coral/grammars/ *.lsys. */
#ifndef SESSILE_LSYS_BUILTIN_H
#define SESSILE_LSYS_BUILTIN_H
#include <stddef.h>
typedef struct lsys_builtin {
  const char *name, *text;
  size_t len;
} lsys_builtin;
extern const lsys_builtin lsys_builtins[]; /* ends with a NULL name */
#endif
