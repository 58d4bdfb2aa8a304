/* sessile — glTF 2.0 binary (.glb) scenes: distinct meshes instanced by
 * nodes, a PBR material per colour, per-vertex scalars as custom attributes
 * (docs/io.md, "glTF").  The reef's scene and every generator's single
 * organism go through this one writer.
 *
 * Input is in sessile's frame and unit (z up, lengths in the generator's
 * unit, centimetres for the organisms); the writer converts to glTF's (+Y up,
 * metres) with metres_per_unit, on the vertices and on the node matrices, so
 * callers never think about glTF's convention.  The file is written
 * atomically; the same scene gives the same bytes. */
#ifndef SESSILE_IO_GLTF_H
#define SESSILE_IO_GLTF_H
#include <stdint.h>
#include "sessile/status.h"

typedef struct sessile_gltf_material {
  const char *name;
  float rgba[4];  /* base colour, linear, 0..1 */
  float metallic;  /* 0..1 */
  float roughness; /* 0..1 */
} sessile_gltf_material;

typedef struct sessile_gltf_mesh {
  const char *name;
  uint32_t nv, nt;
  const double *pos;    /* 3 nv, sessile frame and unit */
  const uint32_t *tri;  /* 3 nt, counter-clockwise seen from outside */
  const double *normal; /* 3 nv unit normals, or NULL (the writer then computes area-weighted ones) */
  uint32_t nscalars;
  const char *const *scalar_names; /* glTF custom attribute names: "_THICKNESS" (leading '_', upper case) */
  const float *const *scalars;     /* nscalars arrays of nv floats */
  uint32_t material;               /* index into the scene's materials */
} sessile_gltf_mesh;

typedef struct sessile_gltf_node {
  const char *name;     /* may be NULL */
  uint32_t mesh;        /* index into the scene's meshes */
  double matrix[16];    /* column-major affine transform, sessile frame and unit */
} sessile_gltf_node;

typedef struct sessile_gltf_scene {
  const sessile_gltf_mesh *meshes;
  uint32_t nmeshes;
  const sessile_gltf_material *materials;
  uint32_t nmaterials;
  const sessile_gltf_node *nodes; /* NULL with nnodes 0: one node per mesh, identity */
  uint32_t nnodes;
  double metres_per_unit; /* 0.01 for centimetres */
  const char *generator;  /* asset.generator, e.g. "sessile 0.9 (coral venation)" */
  const char *extras_json; /* a JSON object stored as the scene's extras (seed, parameters), or NULL */
} sessile_gltf_scene;

/* Writes s to path (.glb) atomically.  SESSILE_ERR_USAGE for an inconsistent
 * scene (an index out of range, a non-finite coordinate, a bad attribute
 * name), SESSILE_ERR_IO naming the file otherwise. */
sessile_status sessile_gltf_write(const char *path, const sessile_gltf_scene *s);

/* The custom attribute name of a PLY vertex property: "_" + the name in upper
 * case, other characters than A-Z, 0-9 and '_' as '_' (malloc'd; NULL when
 * out of memory).  What sessile_gltf_write_ply and the reef's meshes use. */
char *sessile_gltf_attribute_name(const char *ply_name);

/* A PLY surface (a generator's final.ply) as a one-mesh, one-node scene
 * with material m: its vertices and triangles, its normals when it has
 * nx ny nz (else computed), every other vertex property as a custom
 * attribute named "_" + the name in upper case ("c" -> "_C", other
 * characters than A-Z, 0-9 and '_' as '_').  The PLY is read with
 * sessile_read_ply (its refusals are SESSILE_ERR_USAGE). */
sessile_status sessile_gltf_write_ply(const char *glb_path, const char *ply_path, const sessile_gltf_material *m,
                                      double metres_per_unit, const char *generator);

#endif
