/* The table of embedded grammars, generated at configure time
 * (cmake/EmbedTexts.cmake) from host/coral/grammars/ *.lsys. */
#ifndef SESSILE_LSYS_BUILTIN_H
#define SESSILE_LSYS_BUILTIN_H
#include "sessile/embedded_text.h"
extern const embedded_text lsys_builtins[]; /* ends with a NULL name */
#endif
