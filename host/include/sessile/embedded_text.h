/* Shipped text files embedded in the binary (cmake/EmbedTexts.cmake writes
 * one table per folder: the L-system grammars, the SDS models): name (the
 * file's name without its extension), bytes, length; a NULL name ends it. */
#ifndef SESSILE_EMBEDDED_TEXT_H
#define SESSILE_EMBEDDED_TEXT_H
#include <stddef.h>
#include <string.h>
typedef struct embedded_text {
  const char *name, *text;
  size_t len;
} embedded_text;
/* The entry named name, or NULL. */
static inline const embedded_text *embedded_text_find(const embedded_text *table, const char *name) {
  for (; table->name; table++)
    if (!strcmp(table->name, name)) return table;
  return NULL;
}
#endif
