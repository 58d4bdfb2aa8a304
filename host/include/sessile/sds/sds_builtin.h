/* The table of embedded SDS models, generated at configure time
 * (cmake/EmbedTexts.cmake) from host/sds/models/ *.sds; public so that the
 * CLI lists them (sessile sds --list). */
#ifndef SESSILE_SDS_BUILTIN_H
#define SESSILE_SDS_BUILTIN_H
#include "sessile/embedded_text.h"
extern const embedded_text sds_builtins[]; /* ends with a NULL name */
#endif
