/* sessile io — the glTF writer's parts (not public): the frame change,
 * the binary layout the JSON describes, the JSON document. */
#ifndef SESSILE_GLTF_INTERNAL_H
#define SESSILE_GLTF_INTERNAL_H
#include <cjson/cJSON.h>
#include <stdint.h>
#include "io_internal.h"
#include "sessile/io/gltf.h"

/* glTF's componentType and bufferView target codes. */
enum { GLTF_FLOAT = 5126, GLTF_UINT = 5125, GLTF_ARRAY_BUFFER = 34962, GLTF_ELEMENT_ARRAY_BUFFER = 34963 };

/* sessile (x, y, z), z up -> glTF (x, z, -y), +Y up; positions also
 * scaled.  The OBJ writer's y-up convention uses the same rotation. */
static inline void gltf_dir(const double *v, double *o) { io_dir_yup(v, o); }

/* Where mesh k's arrays lie in the BIN chunk: POSITION, NORMAL, the
 * scalars, then the indices, each 4-byte aligned by construction.  Every
 * array is one bufferView and one accessor, numbered in this order. */
typedef struct gltf_mesh_layout {
  uint64_t offset;    /* first byte of the mesh's arrays in BIN */
  uint32_t accessor;  /* index of its POSITION accessor (= bufferView) */
  double min[3], max[3]; /* POSITION bounds: the float32 values, glTF frame */
} gltf_mesh_layout;

/* The conjugated node matrix C M C^-1 (glTF frame and metres). */
void gltf_node_matrix(const double *m, double mpu, double *out);
/* Whether a column-major 4x4 is exactly the identity. */
int gltf_is_identity(const double *m);
/* The JSON document (asset, scene, nodes, meshes, materials, accessors,
 * bufferViews, buffer of bin_bytes); NULL when out of memory. */
cJSON *gltf_document(const sessile_gltf_scene *s, const gltf_mesh_layout *lay, uint64_t bin_bytes,
                     cJSON *extras);

#endif
