/* A PLY surface as a .glb (sessile/io/gltf.h): what every generator's
 * --glb writes beside its final.ply, so the two hold the same vertices,
 * triangles and per-vertex values. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/gltf.h"
#include "sessile/io/io_read.h"

char *sessile_gltf_attribute_name(const char *ply) {
  size_t n = strlen(ply);
  char *a = malloc(n + 2);
  if (!a) return NULL;
  a[0] = '_';
  for (size_t i = 0; i <= n; i++) {
    unsigned char c = (unsigned char)ply[i];
    a[i + 1] = (char)(!c ? 0 : isalnum(c) ? toupper(c) : '_');
  }
  return a;
}

static sessile_status write_mesh(const char *glb, const sessile_mesh_in *in, const sessile_gltf_material *mat,
                                 double mpu, const char *generator, char **names, double *normal) {
  for (int p = 0; p < in->nprops; p++)
    SESSILE_CHECK(names[p] = sessile_gltf_attribute_name(in->prop_names[p]), SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint64_t i = 0; normal && i < 3ull * in->nv; i++) normal[i] = in->normal[i];
  sessile_gltf_mesh mesh = {.name = "surface", .nv = in->nv, .nt = in->nf, .pos = in->pos, .tri = in->tri,
                            .normal = normal, .nscalars = (uint32_t)in->nprops,
                            .scalar_names = (const char *const *)names, .scalars = (const float *const *)in->props};
  sessile_gltf_scene s = {.meshes = &mesh, .nmeshes = 1, .materials = mat, .nmaterials = mat ? 1 : 0,
                          .metres_per_unit = mpu, .generator = generator};
  return sessile_gltf_write(glb, &s);
}

sessile_status sessile_gltf_write_ply(const char *glb_path, const char *ply_path, const sessile_gltf_material *m,
                                      double metres_per_unit, const char *generator) {
  sessile_mesh_read_opts o = {.triangles_only = 1, .keep_props = 1};
  sessile_mesh_in in = {0};
  SESSILE_CALL(sessile_read_ply(ply_path, &o, &in));
  char **names = calloc((size_t)in.nprops + 1, sizeof *names);
  double *normal = in.normal ? malloc(3 * ((size_t)in.nv + 1) * sizeof *normal) : NULL;
  sessile_status st = names && (normal || !in.normal)
                          ? write_mesh(glb_path, &in, m, metres_per_unit, generator, names, normal)
                          : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory reading '%s'", ply_path);
  for (int p = 0; names && p < in.nprops; p++) free(names[p]);
  free(names), free(normal);
  sessile_mesh_in_free(&in);
  return st;
}
