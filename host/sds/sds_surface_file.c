/* A model's starting surface from a PLY file (`surface = "FILE.ply"`,
 * docs/sds_rules.md), read by io's PLY reader (sessile/io/io_read.h: ascii or
 * binary, hostile input refused with the line and the fault): a vertex
 * element with x, y, z and a face element of triangles; other properties
 * and elements are skipped. */
#include <stdlib.h>
#include "sds/sds_surface_file.h"
#include "sessile/io/io_read.h"

/* Counts above this are refused from the header (a model's surface is a
 * starting shape, far smaller). */
#define SURFACE_MAX 100000000ull

sessile_status sds_read_surface_ply(const char *path, sessile_surface *out) {
  *out = (sessile_surface){0};
  const sessile_mesh_read_opts o = {.max_vertices = SURFACE_MAX, .max_faces = SURFACE_MAX, .triangles_only = 1};
  sessile_mesh_in m;
  sessile_status s = sessile_read_ply(path, &o, &m);
  if (s != SESSILE_OK) return sessile_error_set(s, "surface %s", sessile_error_message());
  if (m.nv < 4 || m.nf < 4) {
    sessile_mesh_in_free(&m);
    return sessile_error_set(SESSILE_ERR_USAGE,
                             "surface '%s': %u vertices and %u triangles (a closed surface needs at least 4 of each)",
                             path, m.nv, m.nf);
  }
  out->pos = m.pos, out->tri = m.tri;
  out->nv = out->cap_v = m.nv, out->nf = out->cap_f = m.nf;
  m.pos = NULL, m.tri = NULL;
  sessile_mesh_in_free(&m);
  return SESSILE_OK;
}
