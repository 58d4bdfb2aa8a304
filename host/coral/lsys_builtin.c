/* The shipped grammars by name (the table is generated from
 * host/coral/grammars/ *.lsys at configure time). */
#include <string.h>
#include "coral/lsys_builtin.h"
#include "sessile/coral/lsystem.h"

int sessile_lsys_builtin_count(void) {
  int n = 0;
  while (lsys_builtins[n].name) n++;
  return n;
}
const char *sessile_lsys_builtin_name(int i) {
  return i >= 0 && i < sessile_lsys_builtin_count() ? lsys_builtins[i].name : NULL;
}
const char *sessile_lsys_builtin_text(int i, size_t *len) {
  if (i < 0 || i >= sessile_lsys_builtin_count()) return NULL;
  if (len) *len = lsys_builtins[i].len;
  return lsys_builtins[i].text;
}
const char *sessile_lsys_builtin_find(const char *name, size_t *len) {
  const embedded_text *e = embedded_text_find(lsys_builtins, name);
  if (e && len) *len = e->len;
  return e ? e->text : NULL;
}
