/* The glTF JSON document of a checked scene (gltf_write.c lays out the
 * binary it describes).  Non-integer numbers are printed here, not by
 * cJSON: cJSON keeps %1.15g when it reads back within a relative epsilon,
 * not exactly, and the POSITION bounds must equal the data's floats. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "gltf_internal.h"

void gltf_node_matrix(const double *m, double mpu, double *out) {
  /* m = [A t; 0 1] (column-major) -> [R A R^T, mpu R t; 0 1], R the frame
   * change: the rotation part turns, the translation turns and scales. */
  double a[3][3], ra[3][3];
  for (int c = 0; c < 3; c++) {
    double col[3] = {m[4 * c], m[4 * c + 1], m[4 * c + 2]};
    gltf_dir(col, a[c]); /* a[c] = R A e_c */
  }
  /* (R A R^T) e_c = R A (R^T e_c); R^T e_0 = e_0, R^T e_1 = e_2, R^T e_2 = -e_1 */
  for (int r = 0; r < 3; r++) ra[0][r] = a[0][r], ra[1][r] = a[2][r], ra[2][r] = -a[1][r];
  double t[3];
  gltf_dir(m + 12, t);
  for (int c = 0; c < 3; c++) {
    for (int r = 0; r < 3; r++) out[4 * c + r] = ra[c][r] + 0.0; /* no -0 in the file */
    out[4 * c + 3] = 0;
  }
  for (int r = 0; r < 3; r++) out[12 + r] = mpu * t[r] + 0.0;
  out[15] = 1;
}

int gltf_is_identity(const double *m) {
  for (int k = 0; k < 16; k++)
    if (m[k] != (k % 5 == 0 ? 1.0 : 0.0)) return 0;
  return 1;
}

/* The double nearest the shortest decimal that reads back as f: material
 * factors print as written (0.8, not 0.800000011920929). */
static double short_float(float f) {
  char b[32];
  for (int p = 6; p <= 9; p++) {
    snprintf(b, sizeof b, "%.*g", p, (double)f);
    if (strtof(b, NULL) == f) break;
  }
  return strtod(b, NULL);
}

/* The shortest of %.15g..%.17g that reads back as exactly v, as raw JSON
 * (the C locale's '.', as everywhere in sessile's files). */
static cJSON *exact(double v) {
  char b[40];
  for (int p = 15; p <= 17; p++) {
    snprintf(b, sizeof b, "%.*g", p, v);
    if (strtod(b, NULL) == v) break;
  }
  return cJSON_CreateRaw(b);
}

static cJSON *numbers(const double *v, int n) {
  cJSON *a = cJSON_CreateArray();
  for (int k = 0; a && k < n; k++)
    if (!cJSON_AddItemToArray(a, exact(v[k]))) {
      cJSON_Delete(a);
      return NULL;
    }
  return a;
}

static int add_view(cJSON *views, cJSON *accs, uint64_t off, uint64_t bytes, int target, int ctype, uint32_t count,
                    const char *type) {
  cJSON *v = cJSON_CreateObject(), *a = cJSON_CreateObject();
  if (!v || !a || !cJSON_AddItemToArray(views, v) || !cJSON_AddItemToArray(accs, a)) {
    cJSON_Delete(v), cJSON_Delete(a);
    return 0;
  }
  int view = cJSON_GetArraySize(views) - 1;
  return cJSON_AddNumberToObject(v, "buffer", 0) && cJSON_AddNumberToObject(v, "byteOffset", (double)off) &&
         cJSON_AddNumberToObject(v, "byteLength", (double)bytes) && cJSON_AddNumberToObject(v, "target", target) &&
         cJSON_AddNumberToObject(a, "bufferView", view) && cJSON_AddNumberToObject(a, "componentType", ctype) &&
         cJSON_AddNumberToObject(a, "count", count) && cJSON_AddStringToObject(a, "type", type);
}

static int add_mesh(cJSON *meshes, cJSON *views, cJSON *accs, const sessile_gltf_scene *s, uint32_t k,
                    const gltf_mesh_layout *L) {
  const sessile_gltf_mesh *m = &s->meshes[k];
  uint64_t off = L->offset, v3 = 12ull * m->nv;
  cJSON *mesh = cJSON_CreateObject(), *prims = cJSON_CreateArray(), *prim = cJSON_CreateObject();
  cJSON *attr = cJSON_CreateObject();
  int ok = mesh && prims && prim && attr && cJSON_AddItemToArray(meshes, mesh);
  if (!ok) cJSON_Delete(mesh);
  ok = ok && cJSON_AddItemToObject(mesh, "primitives", prims) ? 1 : (cJSON_Delete(prims), 0);
  ok = ok && cJSON_AddItemToArray(prims, prim) ? 1 : (cJSON_Delete(prim), 0);
  ok = ok && cJSON_AddItemToObject(prim, "attributes", attr) ? 1 : (cJSON_Delete(attr), 0);
  if (!ok) return 0;
  if (m->name && !cJSON_AddStringToObject(mesh, "name", m->name)) return 0;
  uint32_t acc = L->accessor;
  ok = add_view(views, accs, off, v3, GLTF_ARRAY_BUFFER, GLTF_FLOAT, m->nv, "VEC3") &&
       cJSON_AddNumberToObject(attr, "POSITION", acc);
  cJSON *pa = cJSON_GetArrayItem(accs, (int)acc);
  ok = ok && cJSON_AddItemToObject(pa, "min", numbers(L->min, 3)) && cJSON_AddItemToObject(pa, "max", numbers(L->max, 3));
  ok = ok && add_view(views, accs, off + v3, v3, GLTF_ARRAY_BUFFER, GLTF_FLOAT, m->nv, "VEC3") &&
       cJSON_AddNumberToObject(attr, "NORMAL", acc + 1);
  off += 2 * v3;
  for (uint32_t q = 0; ok && q < m->nscalars; q++, off += 4ull * m->nv)
    ok = add_view(views, accs, off, 4ull * m->nv, GLTF_ARRAY_BUFFER, GLTF_FLOAT, m->nv, "SCALAR") &&
         cJSON_AddNumberToObject(attr, m->scalar_names[q], acc + 2 + q);
  ok = ok && add_view(views, accs, off, 12ull * m->nt, GLTF_ELEMENT_ARRAY_BUFFER, GLTF_UINT, 3 * m->nt, "SCALAR") &&
       cJSON_AddNumberToObject(prim, "indices", acc + 2 + m->nscalars);
  if (ok && s->nmaterials) ok = cJSON_AddNumberToObject(prim, "material", m->material) != NULL;
  return ok;
}

static int add_material(cJSON *mats, const sessile_gltf_material *m) {
  cJSON *o = cJSON_CreateObject(), *pbr = cJSON_CreateObject();
  if (!o || !pbr || !cJSON_AddItemToArray(mats, o)) {
    cJSON_Delete(o), cJSON_Delete(pbr);
    return 0;
  }
  if (!cJSON_AddItemToObject(o, "pbrMetallicRoughness", pbr)) return cJSON_Delete(pbr), 0;
  double rgba[4];
  for (int c = 0; c < 4; c++) rgba[c] = short_float(m->rgba[c]);
  return (!m->name || cJSON_AddStringToObject(o, "name", m->name)) &&
         cJSON_AddItemToObject(pbr, "baseColorFactor", numbers(rgba, 4)) &&
         cJSON_AddItemToObject(pbr, "metallicFactor", exact(short_float(m->metallic))) &&
         cJSON_AddItemToObject(pbr, "roughnessFactor", exact(short_float(m->roughness))) &&
         cJSON_AddFalseToObject(o, "doubleSided");
}

static int add_node(cJSON *nodes, const sessile_gltf_node *n, const char *mesh_name, double mpu) {
  cJSON *o = cJSON_CreateObject();
  if (!o || !cJSON_AddItemToArray(nodes, o)) return cJSON_Delete(o), 0;
  const char *name = n ? n->name : mesh_name;
  if (name && !cJSON_AddStringToObject(o, "name", name)) return 0;
  if (!cJSON_AddNumberToObject(o, "mesh", n ? n->mesh : (double)(cJSON_GetArraySize(nodes) - 1))) return 0;
  double m[16];
  if (n) gltf_node_matrix(n->matrix, mpu, m);
  if (!n || gltf_is_identity(m)) return 1;
  /* At float precision, the shortest decimal that reads back as the same
   * float: what engines store, and a 10 000-node reef's JSON at half the
   * size of 17 digits per number (docs/io.md). */
  for (int k = 0; k < 16; k++) m[k] = short_float((float)m[k]) + 0.0;
  return cJSON_AddItemToObject(o, "matrix", numbers(m, 16));
}

static int fill(cJSON *doc, const sessile_gltf_scene *s, const gltf_mesh_layout *lay, uint64_t bin_bytes,
                cJSON *extras) {
  cJSON *asset = cJSON_AddObjectToObject(doc, "asset");
  if (!asset || !cJSON_AddStringToObject(asset, "generator", s->generator ? s->generator : "sessile") ||
      !cJSON_AddStringToObject(asset, "version", "2.0") || !cJSON_AddNumberToObject(doc, "scene", 0))
    return 0;
  cJSON *scenes = cJSON_AddArrayToObject(doc, "scenes"), *scene = cJSON_CreateObject();
  if (!scenes || !scene || !cJSON_AddItemToArray(scenes, scene)) return cJSON_Delete(scene), 0;
  uint32_t nn = s->nodes ? s->nnodes : s->nmeshes;
  cJSON *roots = cJSON_AddArrayToObject(scene, "nodes");
  for (uint32_t k = 0; roots && k < nn; k++)
    if (!cJSON_AddItemToArray(roots, cJSON_CreateNumber(k))) return 0;
  if (!roots || (extras && !cJSON_AddItemReferenceToObject(scene, "extras", extras))) return 0;
  cJSON *nodes = cJSON_AddArrayToObject(doc, "nodes");
  for (uint32_t k = 0; nodes && k < nn; k++)
    if (!add_node(nodes, s->nodes ? &s->nodes[k] : NULL, s->meshes[k % s->nmeshes].name, s->metres_per_unit))
      return 0;
  cJSON *meshes = cJSON_AddArrayToObject(doc, "meshes");
  cJSON *mats = s->nmaterials ? cJSON_AddArrayToObject(doc, "materials") : NULL;
  for (uint32_t k = 0; mats && k < s->nmaterials; k++)
    if (!add_material(mats, &s->materials[k])) return 0;
  cJSON *accs = cJSON_AddArrayToObject(doc, "accessors"), *views = cJSON_AddArrayToObject(doc, "bufferViews");
  if (!nodes || !meshes || (s->nmaterials && !mats) || !accs || !views) return 0;
  for (uint32_t k = 0; k < s->nmeshes; k++)
    if (!add_mesh(meshes, views, accs, s, k, &lay[k])) return 0;
  cJSON *bufs = cJSON_AddArrayToObject(doc, "buffers"), *buf = cJSON_CreateObject();
  if (!bufs || !buf || !cJSON_AddItemToArray(bufs, buf)) return cJSON_Delete(buf), 0;
  return cJSON_AddNumberToObject(buf, "byteLength", (double)bin_bytes) != NULL;
}

cJSON *gltf_document(const sessile_gltf_scene *s, const gltf_mesh_layout *lay, uint64_t bin_bytes, cJSON *extras) {
  cJSON *doc = cJSON_CreateObject();
  if (doc && !fill(doc, s, lay, bin_bytes, extras)) {
    cJSON_Delete(doc);
    return NULL;
  }
  return doc;
}
