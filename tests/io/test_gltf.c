/* The glTF writer (sessile/io/gltf.h) read back here byte by byte: the GLB
 * container, the JSON document, every array of the BIN chunk against the
 * input in glTF's frame (x, z, -y) times metres_per_unit, node matrices
 * against C M C^-1 multiplied out in full, instancing, custom attributes,
 * identical bytes for the same scene, and every refusal (nothing written).
 * `test_gltf --samples DIR` writes the scenes that test_gltf_readers.sh
 * opens with readers sharing no code with sessile. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "sessile/io/gltf.h"
#include "sessile/io/io.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"

static char T[256];
static char *P(const char *name) {
  static char buf[4][512];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", T, name);
  return buf[k];
}

/* --- the sample scene: a cube (cm) with a thickness, seen three times -------- */
static double cube_pos[24];
static uint32_t cube_tri[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
static float thick[8];
static const double centre[3] = {1, 2, 3};
static const char *thick_name[] = {"_THICKNESS"};
static const float *thick_vals[] = {thick};
static sessile_gltf_mesh cube;
static sessile_gltf_material mats[2] = {{"coral", {0.9f, 0.45f, 0.4f, 1}, 0, 0.8f},
                                        {"rock", {0.3f, 0.3f, 0.3f, 1}, 0.1f, 1}};
static sessile_gltf_node nodes[3];

static void identity(double *m) {
  for (int k = 0; k < 16; k++) m[k] = k % 5 == 0;
}

static void make_scene(sessile_gltf_scene *s) {
  for (int v = 0; v < 8; v++) {
    cube_pos[3 * v] = centre[0] + ((v == 1 || v == 2 || v == 5 || v == 6) ? 1 : -1);
    cube_pos[3 * v + 1] = centre[1] + ((v == 2 || v == 3 || v == 6 || v == 7) ? 1 : -1);
    cube_pos[3 * v + 2] = centre[2] + (v >= 4 ? 1 : -1);
    thick[v] = 0.25f + 0.5f * (float)v;
  }
  cube = (sessile_gltf_mesh){.name = "cube", .nv = 8, .nt = 12, .pos = cube_pos, .tri = cube_tri, .nscalars = 1,
                             .scalar_names = thick_name, .scalars = thick_vals, .material = 1};
  identity(nodes[0].matrix), nodes[0].name = "plain";
  identity(nodes[1].matrix), nodes[1].name = "moved";
  nodes[1].matrix[12] = 10, nodes[1].matrix[13] = 20, nodes[1].matrix[14] = 30;
  double *m = nodes[2].matrix; /* 90 degrees about z, scale 2, then moved */
  identity(m), nodes[2].name = "turned";
  m[0] = 0, m[1] = 2, m[4] = -2, m[5] = 0, m[10] = 2, m[12] = -5, m[13] = 0, m[14] = 2;
  *s = (sessile_gltf_scene){.meshes = &cube, .nmeshes = 1, .materials = mats, .nmaterials = 2, .nodes = nodes,
                            .nnodes = 3, .metres_per_unit = 0.01, .generator = "sessile test",
                            .extras_json = "{\"seed\":7}"};
}

/* --- reading a .glb back ------------------------------------------------------ */
typedef struct glb {
  uint8_t *bytes;
  size_t n;
  cJSON *doc;
  const uint8_t *bin;
  uint32_t bin_len;
} glb;

static uint32_t u32(const uint8_t *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static float f32(const uint8_t *p) {
  uint32_t u = u32(p);
  float f;
  memcpy(&f, &u, 4);
  return f;
}

/* Reads and checks the container; 0 when it is not a well-formed GLB. */
static int glb_read(const char *path, glb *g) {
  memset(g, 0, sizeof *g);
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  fseek(f, 0, SEEK_END);
  long sz = ftell(f);
  fseek(f, 0, SEEK_SET);
  g->bytes = malloc((size_t)sz + 1);
  g->n = fread(g->bytes, 1, (size_t)sz, f);
  fclose(f);
  const uint8_t *b = g->bytes;
  int ok = g->n >= 28 && !memcmp(b, "glTF", 4) && u32(b + 4) == 2 && u32(b + 8) == g->n;
  t_true("GLB header: magic, version 2, length = file size", ok);
  if (!ok) return 0;
  uint32_t jl = u32(b + 12);
  ok = jl % 4 == 0 && !memcmp(b + 16, "JSON", 4) && 20 + (size_t)jl + 8 <= g->n;
  t_true("JSON chunk: type, length a multiple of 4", ok);
  if (!ok) return 0;
  const uint8_t *bh = b + 20 + jl;
  g->bin_len = u32(bh), g->bin = bh + 8;
  ok = !memcmp(bh + 4, "BIN\0", 4) && g->bin_len % 4 == 0 && 28 + (size_t)jl + g->bin_len == g->n;
  t_true("BIN chunk: type, length a multiple of 4, ends the file", ok);
  g->doc = cJSON_ParseWithLength((const char *)b + 20, jl);
  t_true("the JSON chunk parses (trailing spaces allowed)", g->doc != NULL);
  return ok && g->doc;
}
static void glb_free(glb *g) {
  cJSON_Delete(g->doc);
  free(g->bytes);
}

static const cJSON *at(const cJSON *o, const char *key, int i) {
  const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
  return i < 0 ? a : cJSON_GetArrayItem(a, i);
}
static double num(const cJSON *o, const char *key) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* Accessor a's bytes, after checking it lies inside BIN; NULL otherwise. */
static const uint8_t *acc_data(const glb *g, int a, int ctype, const char *type, uint32_t count, int target) {
  const cJSON *acc = at(g->doc, "accessors", a);
  const cJSON *view = at(g->doc, "bufferViews", (int)num(acc, "bufferView"));
  const cJSON *ty = at(acc, "type", -1);
  int comps = !strcmp(type, "VEC3") ? 3 : 1;
  double off = num(view, "byteOffset"), len = num(view, "byteLength");
  int ok = num(acc, "componentType") == ctype && cJSON_IsString(ty) && !strcmp(ty->valuestring, type) &&
           num(acc, "count") == count && num(view, "target") == target && num(view, "buffer") == 0 &&
           len == 4.0 * comps * count && fmod(off, 4) == 0 && off + len <= g->bin_len;
  return ok ? g->bin + (size_t)off : NULL;
}

/* --- checks of one mesh ------------------------------------------------------- */
static void check_mesh(const glb *g, int mi, const sessile_gltf_mesh *m, double mpu) {
  char what[160];
  const cJSON *prim = at(at(g->doc, "meshes", mi), "primitives", 0), *attr = at(prim, "attributes", -1);
  const uint8_t *pos = acc_data(g, (int)num(attr, "POSITION"), 5126, "VEC3", m->nv, 34962);
  const uint8_t *nrm = acc_data(g, (int)num(attr, "NORMAL"), 5126, "VEC3", m->nv, 34962);
  const uint8_t *idx = acc_data(g, (int)num(prim, "indices"), 5125, "SCALAR", 3 * m->nt, 34963);
  snprintf(what, sizeof what, "mesh %d: POSITION, NORMAL (float VEC3) and indices (uint SCALAR, elements)", mi);
  t_true(what, pos && nrm && idx);
  if (!pos || !nrm || !idx) return;
  double perr = 0, nerr = 0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t v = 0; v < m->nv; v++) {
    const double *p = m->pos + 3 * v;
    double want[3] = {mpu * p[0], mpu * p[2], -mpu * p[1]};
    for (int c = 0; c < 3; c++) {
      double got = f32(pos + 12 * v + 4 * c);
      perr = fmax(perr, fabs(got - (float)want[c]));
      lo[c] = fmin(lo[c], got), hi[c] = fmax(hi[c], got);
    }
    double n[3] = {f32(nrm + 12 * v), f32(nrm + 12 * v + 4), f32(nrm + 12 * v + 8)};
    nerr = fmax(nerr, fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1));
    if (m->normal) { /* the given normal, turned into glTF's frame */
      const double *q = m->normal + 3 * v;
      double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      nerr = fmax(nerr, fmax(fabs(n[0] - q[0] / l), fmax(fabs(n[1] - q[2] / l), fabs(n[2] + q[1] / l))));
    }
  }
  snprintf(what, sizeof what, "mesh %d: positions = metres_per_unit (x, z, -y)", mi);
  t_check(what, perr, 0);
  snprintf(what, sizeof what, "mesh %d: normals unit (and the given ones turned)", mi);
  t_check(what, nerr, 2e-7);
  const cJSON *pa = at(g->doc, "accessors", (int)num(attr, "POSITION"));
  double berr = 0;
  for (int c = 0; c < 3; c++)
    berr = fmax(berr, fmax(fabs(at(pa, "min", c)->valuedouble - lo[c]), fabs(at(pa, "max", c)->valuedouble - hi[c])));
  snprintf(what, sizeof what, "mesh %d: POSITION min/max are the data's exactly", mi);
  t_check(what, berr, 0);
  int same = 1;
  for (uint32_t i = 0; i < 3 * m->nt; i++) same = same && u32(idx + 4 * i) == m->tri[i];
  snprintf(what, sizeof what, "mesh %d: indices as given", mi);
  t_true(what, same);
  for (uint32_t q = 0; q < m->nscalars; q++) {
    const uint8_t *sv = acc_data(g, (int)num(attr, m->scalar_names[q]), 5126, "SCALAR", m->nv, 34962);
    double err = sv ? 0 : INFINITY;
    for (uint32_t v = 0; sv && v < m->nv; v++) err = fmax(err, fabs(f32(sv + 4 * v) - m->scalars[q][v]));
    snprintf(what, sizeof what, "mesh %d: attribute %s as given", mi, m->scalar_names[q]);
    t_check(what, err, 0);
  }
  snprintf(what, sizeof what, "mesh %d: material index", mi);
  t_true(what, num(prim, "material") == m->material);
}

/* out = a b (column-major 4x4) */
static void mul4(const double *a, const double *b, double *out) {
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      double s = 0;
      for (int k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
      out[4 * c + r] = s;
    }
}

static void check_nodes(const glb *g, const sessile_gltf_scene *s) {
  /* C: sessile -> glTF, (x, y, z) -> mpu (x, z, -y); its inverse */
  double C[16] = {0}, Ci[16] = {0}, mpu = s->metres_per_unit;
  C[0] = mpu, C[6] = -mpu, C[9] = mpu, C[15] = 1;
  Ci[0] = 1 / mpu, Ci[9] = -1 / mpu, Ci[6] = 1 / mpu, Ci[15] = 1;
  t_check("nodes: one per input node", fabs(cJSON_GetArraySize(at(g->doc, "nodes", -1)) - (double)s->nnodes), 0);
  t_check("the scene holds every node", fabs(cJSON_GetArraySize(at(at(g->doc, "scenes", 0), "nodes", -1)) - (double)s->nnodes), 0);
  for (uint32_t k = 0; k < s->nnodes; k++) {
    const cJSON *n = at(g->doc, "nodes", (int)k), *mat = at(n, "matrix", -1);
    double cm[16], want[16], err = 0;
    mul4(C, s->nodes[k].matrix, cm);
    mul4(cm, Ci, want);
    int ident = 1;
    for (int i = 0; i < 16; i++) ident = ident && fabs(want[i] - (i % 5 == 0)) < 1e-15;
    char what[128];
    snprintf(what, sizeof what, "node %u: mesh %u; matrix %s", k, s->nodes[k].mesh, ident ? "omitted" : "C M C^-1");
    /* node matrices are written at float precision (docs/io.md): each entry
     * within half a float ulp of C M C^-1, relative */
    for (int i = 0; !ident && i < 16; i++)
      err = fmax(err, mat ? fabs(at(n, "matrix", i)->valuedouble - want[i]) / fmax(1, fabs(want[i])) : 1);
    t_check(what, err + (ident && mat) + (num(n, "mesh") != s->nodes[k].mesh), 6e-8);
    /* and what it means: the node moves the glTF vertex where the sessile node
     * moves the sessile vertex */
    double perr = 0;
    for (uint32_t v = 0; mat && v < cube.nv; v++) {
      double p[4] = {cube_pos[3 * v], cube_pos[3 * v + 1], cube_pos[3 * v + 2], 1}, mp[4] = {0}, gp[4] = {0};
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) mp[r] += s->nodes[k].matrix[4 * c + r] * p[c];
      double pg[4] = {mpu * p[0], mpu * p[2], -mpu * p[1], 1};
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) gp[r] += at(n, "matrix", 4 * c + r)->valuedouble * pg[c];
      perr = fmax(perr, fmax(fabs(gp[0] - mpu * mp[0]), fmax(fabs(gp[1] - mpu * mp[2]), fabs(gp[2] + mpu * mp[1]))));
    }
    snprintf(what, sizeof what, "node %u: the glTF node places the vertices where sessile's does (m)", k);
    t_check(what, perr, 1e-7); /* float-precision matrices on a 0.3 m offset: ~2e-8 m */
  }
}

static void check_scene_file(const char *path, const sessile_gltf_scene *s) {
  glb g;
  if (!glb_read(path, &g)) {
    glb_free(&g);
    return;
  }
  const cJSON *asset = at(g.doc, "asset", -1);
  t_true("asset: version 2.0 and the generator",
         !strcmp(cJSON_GetStringValue(at(asset, "version", -1)), "2.0") &&
             !strcmp(cJSON_GetStringValue(at(asset, "generator", -1)), s->generator));
  t_true("one mesh per input mesh",
         cJSON_GetArraySize(at(g.doc, "meshes", -1)) == (int)s->nmeshes && num(g.doc, "scene") == 0);
  t_true("buffer 0 is the BIN chunk", num(at(g.doc, "buffers", 0), "byteLength") <= g.bin_len &&
                                          num(at(g.doc, "buffers", 0), "byteLength") + 3 >= g.bin_len);
  for (uint32_t k = 0; k < s->nmeshes; k++) check_mesh(&g, (int)k, &s->meshes[k], s->metres_per_unit);
  const cJSON *m1 = at(g.doc, "materials", 1), *pbr = at(m1, "pbrMetallicRoughness", -1);
  t_true("materials: as many, PBR factors as given, single-sided",
         cJSON_GetArraySize(at(g.doc, "materials", -1)) == (int)s->nmaterials &&
             at(pbr, "baseColorFactor", 0)->valuedouble == 0.3 && num(pbr, "metallicFactor") == 0.1 &&
             num(pbr, "roughnessFactor") == 1 && cJSON_IsFalse(at(m1, "doubleSided", -1)));
  if (s->nodes) check_nodes(&g, s);
  if (s->extras_json)
    t_true("the scene's extras", num(at(at(g.doc, "scenes", 0), "extras", -1), "seed") == 7);
  glb_free(&g);
}

/* --- refusals ------------------------------------------------------------------ */
static int entries(const char *d) {
  DIR *dir = opendir(d);
  int n = 0;
  for (struct dirent *e; dir && (e = readdir(dir));) n += e->d_name[0] != '.' || strlen(e->d_name) > 2;
  if (dir) closedir(dir);
  return n;
}

static void refuse(const char *what, const sessile_gltf_scene *s, const char *msg) {
  int before = entries(T);
  sessile_status st = sessile_gltf_write(P("bad.glb"), s);
  char line[256];
  snprintf(line, sizeof line, "refused (usage, nothing written): %s", what);
  t_true(line, st == SESSILE_ERR_USAGE && entries(T) == before && strstr(sessile_error_message(), msg));
  if (st == SESSILE_ERR_USAGE && !strstr(sessile_error_message(), msg)) printf("  message: %s\n", sessile_error_message());
}

static void test_refusals(const sessile_gltf_scene *good) {
  sessile_gltf_scene s = *good;
  sessile_gltf_mesh m = cube;
  sessile_gltf_node n[3];
  memcpy(n, nodes, sizeof n);
  double pos[24];
  uint32_t tri[36];
  memcpy(pos, cube_pos, sizeof pos), memcpy(tri, cube_tri, sizeof tri);
  s.meshes = &m, s.nodes = n, m.pos = pos, m.tri = tri;
  tri[7] = 8;
  refuse("an index out of range", &s, "names vertex 8 of 8");
  tri[7] = cube_tri[7], pos[4] = NAN;
  refuse("a NaN position", &s, "non-finite position");
  pos[4] = INFINITY;
  refuse("an infinite position", &s, "non-finite position");
  pos[4] = cube_pos[4];
  const char *bad_names[] = {"THICKNESS", "_thickness", "_", "_A B"};
  for (int k = 0; k < 4; k++) {
    m.scalar_names = &bad_names[k];
    refuse(bad_names[k], &s, "must be '_' then");
  }
  m.scalar_names = thick_name;
  float nanv[8] = {0};
  const float *nanp[] = {nanv};
  nanv[3] = NAN, m.scalars = nanp;
  refuse("a NaN attribute value", &s, "not finite at vertex 3");
  m.scalars = thick_vals, m.material = 2;
  refuse("a material out of range", &s, "material 2 of 2");
  m.material = 1, n[1].mesh = 1;
  refuse("a node's mesh out of range", &s, "mesh 1 of 1");
  n[1].mesh = 0, n[2].matrix[3] = 0.5;
  refuse("a projective matrix", &s, "not affine");
  n[2].matrix[3] = 0, n[2].matrix[13] = NAN;
  refuse("a NaN matrix", &s, "non-finite matrix");
  n[2].matrix[13] = 0, s.extras_json = "[1]";
  refuse("extras not an object", &s, "extras");
  s.extras_json = NULL, s.metres_per_unit = 0;
  refuse("metres_per_unit 0", &s, "metres_per_unit");
  s.metres_per_unit = 0.01, m.nt = 0;
  refuse("no triangles", &s, "no triangles");
  m.nt = 12, s.nmeshes = 0;
  refuse("no meshes", &s, "at least one mesh");
  s.nmeshes = 1, mats[0].rgba[1] = 1.5f;
  refuse("a colour above 1", &s, "in 0..1");
  mats[0].rgba[1] = 0.45f;
  t_ok("the repaired scene is written", sessile_gltf_write(P("repaired.glb"), &s));
}

/* A second mesh with normals given (not unit) and nodes NULL: one node each. */
static void test_two_meshes(sessile_gltf_scene *s) {
  static const double tp[12] = {0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 2};
  static const uint32_t tt[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  static const double tn[12] = {-1, -1, -1, 3, 0, 0, 0, 0.5, 0, 0, 0, 7};
  sessile_gltf_mesh ms[2] = {cube, {.name = "tet", .nv = 4, .nt = 4, .pos = tp, .tri = tt, .normal = tn}};
  sessile_gltf_scene two = *s;
  two.meshes = ms, two.nmeshes = 2, two.nodes = NULL, two.nnodes = 0, two.metres_per_unit = 0.5;
  t_ok("two meshes, one node each", sessile_gltf_write(P("two.glb"), &two));
  check_scene_file(P("two.glb"), &two);
  glb g;
  if (glb_read(P("two.glb"), &g))
    t_true("nodes NULL: node k shows mesh k, no matrix",
           cJSON_GetArraySize(at(g.doc, "nodes", -1)) == 2 && num(at(g.doc, "nodes", 1), "mesh") == 1 &&
               !at(at(g.doc, "nodes", 1), "matrix", -1));
  glb_free(&g);
}

/* A PLY with normals and two extra values, as a .glb. */
static void test_from_ply(void) {
  sessile_surface sf = {0};
  double c[3] = {0, 0, 5};
  t_must("icosphere", sessile_surface_icosphere(2, 3.0, c, &sf));
  double *n = malloc(3 * sizeof *n * sf.nv), *e0 = malloc(sizeof *e0 * sf.nv), *e1 = malloc(sizeof *e1 * sf.nv);
  sessile_surface_normals(&sf, n);
  for (uint32_t v = 0; v < sf.nv; v++) e0[v] = sf.pos[3 * v + 2], e1[v] = 0.125 * v;
  const char *names[] = {"c", "age2"};
  const double *ex[] = {e0, e1};
  t_ok("ply", sessile_write_ply(P("s.ply"), &sf, n, 2, names, ex));
  sessile_gltf_material mat = {"m", {1, 1, 1, 1}, 0, 0.5f};
  t_ok("ply -> glb", sessile_gltf_write_ply(P("s.glb"), P("s.ply"), &mat, 0.01, "sessile test"));
  float f0[sf.nv], f1[sf.nv];
  double nf[3 * sf.nv];
  for (uint32_t v = 0; v < sf.nv; v++) f0[v] = (float)e0[v], f1[v] = (float)e1[v];
  for (uint32_t i = 0; i < 3 * sf.nv; i++) nf[i] = (float)n[i];
  double pf[3 * sf.nv];
  for (uint32_t i = 0; i < 3 * sf.nv; i++) pf[i] = (float)sf.pos[i]; /* the PLY holds floats */
  const char *an[] = {"_C", "_AGE2"};
  const float *av[] = {f0, f1};
  sessile_gltf_mesh m = {.nv = sf.nv, .nt = sf.nf, .pos = pf, .tri = sf.tri, .normal = nf, .nscalars = 2,
                         .scalar_names = an, .scalars = av};
  glb g;
  if (glb_read(P("s.glb"), &g)) check_mesh(&g, 0, &m, 0.01);
  glb_free(&g);
  free(n), free(e0), free(e1);
  sessile_surface_free(&sf);
}

static int same_file(const char *a, const char *b) {
  glb x, y;
  int ok = glb_read(a, &x) && glb_read(b, &y) && x.n == y.n && !memcmp(x.bytes, y.bytes, x.n);
  glb_free(&x), glb_free(&y);
  return ok;
}

int main(int argc, char **argv) {
  sessile_gltf_scene s;
  make_scene(&s);
  if (argc == 3 && !strcmp(argv[1], "--samples")) { /* for test_gltf_readers.sh */
    snprintf(T, sizeof T, "%s", argv[2]);
    sessile_gltf_scene one = s;
    one.nodes = NULL, one.nnodes = 0;
    t_ok("instanced.glb", sessile_gltf_write(P("instanced.glb"), &s));
    t_ok("cube.glb", sessile_gltf_write(P("cube.glb"), &one));
    return t_finish(NULL);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: test_gltf [--samples DIR]\n");
    return 2;
  }
  snprintf(T, sizeof T, "%s/sessile_test_gltf.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(T)) {
    printf("FAIL cannot create a scratch folder: %s\n", strerror(errno));
    return 1;
  }
  t_ok("write the instanced scene", sessile_gltf_write(P("a.glb"), &s));
  check_scene_file(P("a.glb"), &s);
  t_ok("write it again", sessile_gltf_write(P("b.glb"), &s));
  t_true("the same scene gives the same bytes", same_file(P("a.glb"), P("b.glb")));
  test_two_meshes(&s);
  test_from_ply();
  test_refusals(&s);
  const char *left[] = {"a.glb", "b.glb", "two.glb", "s.ply", "s.glb", "repaired.glb"};
  for (int k = 0; k < 6; k++) unlink(P(left[k]));
  t_true("nothing else was left in the folder", entries(T) == 0);
  rmdir(T);
  return t_finish(NULL);
}
