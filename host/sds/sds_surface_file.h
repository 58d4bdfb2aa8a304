/* A model's starting surface read from a PLY file (sds_surface_file.c). */
#ifndef SESSILE_SDS_SURFACE_FILE_H
#define SESSILE_SDS_SURFACE_FILE_H
#include "sessile/status.h"
#include "sessile/mesh/surface.h"

/* Reads the triangles of an ASCII or binary PLY file (io's reader)
 * (SESSILE_ERR_USAGE naming the file and the fault). */
sessile_status sds_read_surface_ply(const char *path, sessile_surface *out);
#endif
