/* What the mesh readers share: the options' defaults, the face list, free. */
#include <stdlib.h>
#include "io_internal.h"

sessile_mesh_read_opts io_mesh_opts(const sessile_mesh_read_opts *o) {
  sessile_mesh_read_opts d = {0};
  if (o) d = *o;
  if (!d.max_vertices) d.max_vertices = UINT32_MAX - 1; /* an index fits a uint32 */
  if (!d.max_faces) d.max_faces = UINT32_MAX / 3;       /* 3 nf indices fit a uint32 */
  return d;
}

sessile_status io_mesh_add_face(sessile_mesh_in *m, size_t *cap, const uint32_t *poly, uint32_t n,
                                uint64_t max, const char *path) {
  size_t need = (size_t)m->nf + (n - 2);
  SESSILE_CHECK(need <= max, SESSILE_ERR_USAGE, "%s: more than %llu triangles", path, (unsigned long long)max);
  if (need > *cap) {
    size_t c = *cap ? *cap : 4096;
    while (c < need) c *= 2;
    uint32_t *t = realloc(m->tri, c * 3 * sizeof(uint32_t));
    SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "%s: out of host memory for %zu triangles", path, c);
    m->tri = t, *cap = c;
  }
  for (uint32_t k = 1; k + 1 < n; k++) {
    uint32_t *d = m->tri + 3 * (size_t)m->nf++;
    d[0] = poly[0], d[1] = poly[k], d[2] = poly[k + 1];
  }
  return SESSILE_OK;
}

void sessile_mesh_in_free(sessile_mesh_in *m) {
  if (!m) return;
  for (int i = 0; i < m->nprops; i++) {
    if (m->prop_names) free(m->prop_names[i]);
    if (m->props) free(m->props[i]);
  }
  free(m->prop_names);
  free(m->props);
  free(m->pos);
  free(m->tri);
  free(m->normal);
  *m = (sessile_mesh_in){0};
}
