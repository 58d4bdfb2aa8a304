/* The table of embedded SDS models, generated at configure time
 * (cmake/EmbedTexts.cmake) from host/sds/models/ *.sds. */
#ifndef SESSILE_SDS_BUILTIN_H
#define SESSILE_SDS_BUILTIN_H
#include <stddef.h>
typedef struct sds_builtin {
  const char *name, *text;
  size_t len;
} sds_builtin;
extern const sds_builtin sds_builtins[]; /* ends with a NULL name */
#endif
