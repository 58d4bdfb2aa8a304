/* sessile — reef scenes (Liapis et al., Coralize, §4; docs/reef.md): a
 * seabed, a pool of organisms from other generators, brush strokes that place
 * them, reef growth (§4.2) and water currents (§4.3).  The reef layer knows
 * no other generator: it places (entry, seed) pairs; the CLI turns them into
 * meshes through sessile_reef_organism_fn.
 *
 * Units: metres, z up, in the scene; organisms' meshes are centimetres. */
#ifndef SESSILE_REEF_H
#define SESSILE_REEF_H

#include <stddef.h>
#include <stdint.h>
#include <cjson/cJSON.h>
#include "sessile/gpu/gpu.h"
#include "sessile/io/gltf.h"
#include "sessile/mesh/surface.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* More placements than this are refused before any work (brush candidates
 * plus what growth could add). */
#define SESSILE_REEF_MAX_ORGANISMS 1000000

/* The seabed: a heightfield over [0, extent[0]] x [0, extent[1]], sample
 * (i, j) at (i dx, j dy), z = h[j nx + i] (metres). */
typedef struct sessile_reef_seabed {
  uint32_t nx, ny;
  double extent[2];
  double *h;
} sessile_reef_seabed;

typedef struct sessile_reef_entry {
  char *name;       /* the entry's name (material, placements.json) */
  char *generator;  /* a registered generator ("coral venation") */
  char **settings;  /* "name=value" as --set */
  int nsettings;
  char **arguments; /* the generator's own arguments, as on its command line ("limb", "--t-end", "2") */
  int narguments;
  float rgba[4], roughness;
  double bias;         /* random bias, % (relative weight) */
  double size[2];      /* footprint radius range, m */
  int follow_terrain;  /* up axis = terrain normal, else +z */
  int rotate[3];       /* random rotation about x, y, z (the organism's own axes) */
  double depth[2];     /* band below sea level, m */
} sessile_reef_entry;

typedef enum { SESSILE_REEF_STANDARD = 0, SESSILE_REEF_AUTOMATIC = 1 } sessile_reef_brush_kind;

typedef struct sessile_reef_stroke {
  double *pts;     /* 2 npts: x, y (m) */
  int npts;
  double size;     /* brush radius, m */
  double density;  /* candidates per dab, or per m^2 of the dab */
  int per_m2;
  sessile_reef_brush_kind kind;
} sessile_reef_stroke;

typedef struct sessile_reef_current {
  double origin[3], dir[3]; /* dir unit after parsing */
  double strength;          /* hemisphere radius, m */
  double range;             /* nutrition range, m */
} sessile_reef_current;

typedef struct sessile_reef_scene {
  /* seabed: a user's mesh sampled to res heights (owned; NULL: noise) */
  double *heights;
  /* seabed: noise (octaves of seeded value noise) */
  uint32_t res[2];
  double extent[2], height_scale, base, wavelength;
  int octaves;
  uint64_t seabed_seed;
  double sea_level;
  sessile_reef_entry *entries;
  int nentries;
  sessile_reef_stroke *strokes;
  int nstrokes;
  sessile_reef_current *currents;
  int ncurrents;
  int growth_steps;
  double spacing;
} sessile_reef_scene;

/* Parses and checks a scene (strict: unknown keys, duplicates, wrong kinds
 * and values out of range are SESSILE_ERR_USAGE with one line naming the
 * JSON path, e.g. "pool[1].size: ...").  where names the file. */
sessile_status sessile_reef_scene_parse(const char *text, size_t len, const char *where, sessile_reef_scene *out);
void sessile_reef_scene_free(sessile_reef_scene *s); /* NULL-safe, leaves it zeroed */

/* The seabed of the scene (seeded noise). */
sessile_status sessile_reef_seabed_make(const sessile_reef_scene *s, sessile_reef_seabed *out);
void sessile_reef_seabed_free(sessile_reef_seabed *b);
/* Bilinear height at (x, y) and the unit normal of that bilinear patch;
 * 0 outside the extent. */
int sessile_reef_seabed_at(const sessile_reef_seabed *b, double x, double y, double *z, double n[3]);

typedef struct sessile_reef_placement {
  uint32_t entry;
  uint32_t stroke;    /* the brush stroke, or UINT32_MAX for a grown one */
  uint32_t automatic; /* 1: a distinct organism per placement (else one per entry) */
  uint32_t pad;       /* 0: no padding bytes, so a checkpoint's bytes are the same */
  uint64_t seed;      /* the organism's seed */
  double pos[3];      /* base on the seabed, m */
  double up[3];       /* unit up axis (terrain normal or +z) */
  double angle[3];    /* random rotations about x, y, z, radians (0: axis not random) */
  double size;        /* footprint radius, m */
  double depth;       /* sea level - z, m */
  double exposure;    /* sum over currents (§4.3) */
} sessile_reef_placement;

typedef struct sessile_reef_placements {
  sessile_reef_placement *p;
  uint32_t n, cap;
} sessile_reef_placements;
void sessile_reef_placements_free(sessile_reef_placements *p);

/* Upper bound of the placements the scene can make; SESSILE_ERR_USAGE
 * naming the JSON path when over SESSILE_REEF_MAX_ORGANISMS, or when a
 * stroke leaves the seabed. */
sessile_status sessile_reef_check(const sessile_reef_scene *s, double *estimate);
/* The brushes (§4.1), in stroke, dab, candidate order from one stream of
 * seed. */
sessile_status sessile_reef_place(const sessile_reef_scene *s, const sessile_reef_seabed *b, uint64_t seed,
                                  sessile_reef_placements *out);
/* One growth step (§4.2; the rule in docs/reef.md): appends the new
 * organisms; *added their count. */
sessile_status sessile_reef_grow_step(const sessile_reef_scene *s, const sessile_reef_seabed *b, int step,
                                      sessile_reef_placements *pl, uint32_t *added);

/* Exposure to currents (§4.3): the host reference, and the GPU kernel
 * (one invocation per organism); both set pl->p[k].exposure for k >= first. */
double sessile_reef_exposure_one(const sessile_reef_current *c, const sessile_reef_seabed *b, const double p[3]);
void sessile_reef_exposure_ref(const sessile_reef_scene *s, const sessile_reef_seabed *b,
                               sessile_reef_placements *pl, uint32_t first);
sessile_status sessile_reef_exposure_gpu(sessile_gpu *gpu, const sessile_reef_scene *s, const sessile_reef_seabed *b,
                                         sessile_reef_placements *pl, uint32_t first);

/* An organism's per-vertex scalars (its PLY's vertex properties): n names
 * and n arrays of nv floats, all malloc'd; n = 0 when it has none. */
typedef struct sessile_reef_scalars {
  uint32_t n;
  char **names;
  float **values;
} sessile_reef_scalars;
void sessile_reef_scalars_free(sessile_reef_scalars *s);

/* The organism's mesh (cm, z up, base near the origin) for generator with
 * settings, seed and exposure (the callee maps exposure to the generator's
 * thickness parameter), and its per-vertex scalars (scalars arrives zeroed;
 * the callee may leave it so).  The CLI implements it. */
typedef sessile_status (*sessile_reef_organism_fn)(void *ctx, const sessile_reef_entry *e, uint64_t seed,
                                                   double exposure, sessile_surface *out,
                                                   sessile_reef_scalars *scalars);

/* A reef's glTF scene: its meshes (the seabed as mesh 0, then one per
 * distinct organism), materials (the seabed's, then one per entry), nodes
 * (the seabed, then one per placement), in centimetres. */
typedef struct sessile_reef_gltf {
  sessile_gltf_scene scene;
  sessile_gltf_mesh *meshes;
  sessile_gltf_material *materials;
  sessile_gltf_node *nodes;
  sessile_surface *surfaces; /* nmeshes, the seabed's first */
  sessile_reef_scalars *scalars; /* per mesh: its scalars, named as glTF attributes ("_THICKNESS_INDEX") */
  uint32_t *node_mesh;       /* per placement: its mesh */
  double *radius_cm;         /* per mesh: its footprint radius */
  char (*names)[64];         /* the meshes' names, then the nodes' */
} sessile_reef_gltf;
sessile_status sessile_reef_gltf_make(const sessile_reef_scene *s, const sessile_reef_seabed *b,
                                      const sessile_reef_placements *pl, sessile_reef_organism_fn fn, void *ctx,
                                      sessile_reef_gltf *out);
void sessile_reef_gltf_free(sessile_reef_gltf *g);

/* placements.json (docs/reef.md, "Output"): per placement its entry,
 * generator, parameters, seed, transform (g's node matrix in metres; none
 * when g is NULL), exposure and depth.  NULL when out of memory. */
cJSON *sessile_reef_placements_json(const sessile_reef_scene *s, const sessile_reef_placements *pl,
                                    const sessile_reef_gltf *g);

#ifdef __cplusplus
}
#endif
#endif
