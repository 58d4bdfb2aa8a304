/* Internal to host/growth: the run's state shared by the loop (grow.c) and
 * its outputs (grow_output.c, grow_manifest.c). */
#ifndef SESSILE_GROW_INTERNAL_H
#define SESSILE_GROW_INTERNAL_H

#include <cjson/cJSON.h>
#include "sessile/box.h"
#include "sessile/grow.h"
#include "sessile/growth_gpu.h"
#include "sessile/la.h"
#include "sessile/nutrient.h"
#include "sessile/surface.h"
#include "sessile/advdiff.h"
#include "sessile/fluid.h"
#include "sessile/tetmesh.h"

typedef struct grow_plane {
  int axis;     /* 0 x, 1 y, 2 z */
  double value; /* cm */
  char name[32];
} grow_plane;

typedef struct grow_run {
  const sessile_params *p;
  const sessile_grow_options *o;
  sessile_gpu *gpu;
  sessile_la *la;
  sessile_box box;
  double center[3];
  sessile_surface surf;
  sessile_nutrient *nutrient;
  sessile_growth_gpu *growth;
  sessile_buffer *solid;
  sessile_vec *c;
  int nplanes;
  grow_plane planes[16];
  /* snapshots written so far (for series.pvd) */
  int nvtu;
  int *vtu_steps;
  char **vtu_files;
  /* The flow (grow_flow.c).  Immersed: on fbox (box level fluid_resolution)
   * with its own solid mask; conforming: on TetGen's mesh of the latest
   * surface.  ufine/pfine: the flow at the nutrient box's nodes. */
  int flow_ready, flow_valid;
  sessile_box fbox;
  sessile_tetmesh fmesh, cmesh;
  sessile_fluid *fluid;
  sessile_buffer *fsolid;
  double *up, *cup;       /* warm starts: immersed (4/fbox node), conforming (4/cmesh node) */
  double *ufine, *pfine;  /* 3 and 1 per nutrient box node */
  const char *flow_domain; /* "immersed" or "conforming" for the current flow */
  /* The advected nutrient on the nutrient box (grow_flow.c). */
  sessile_tetmesh nmesh;
  sessile_advdiff *ad;
  uint8_t *nmask, *nsolid;
  double *nval, *nc;
  cJSON *manifest, *iters;
  double t_start;
  sessile_grow_summary sum;
} grow_run;

/* 64-bit mixing generator (splitmix64): host-side random choices. */
uint64_t grow_splitmix64(uint64_t *state);

/* Parses o->slices into run->planes (SESSILE_ERR_USAGE on a bad spec). */
sessile_status grow_parse_planes(grow_run *r);
/* Creates the run folders (sponge/, slices/, fields/); SESSILE_ERR_USAGE when
 * the folder cannot be created or written. */
sessile_status grow_prepare_outdir(grow_run *r);
/* Writes sponge/iter_NNNN.ply, slices and fields for iteration it. */
sessile_status grow_write_snapshot(grow_run *r, int it, const double *normals);
/* Writes sponge/final.ply and final.obj. */
sessile_status grow_write_final(grow_run *r, const double *normals);

/* The flow of iteration it (records it under "fluid" in rec), with ufine
 * and pfine filled; the advected nutrient into r->c. */
sessile_status grow_flow_solve(grow_run *r, int it, cJSON *rec);
sessile_status grow_nutrient_advected(grow_run *r, sessile_solve_result *res);
void grow_flow_teardown(grow_run *r);
/* The run's fluid parameters (grow_flow.c). */
void grow_fluid_params(const grow_run *r, sessile_fluid_params *fp);
/* The conforming flow (grow_flow_conforming.c): TetGen's mesh of the box
 * minus the current surface, solved warm, interpolated to ufine/pfine by the
 * GPU locator.  *fell_back = 1 (reason under "fallback" in fl) when TetGen
 * rejected the surface; then nothing else changed. */
sessile_status grow_flow_conforming(grow_run *r, sessile_fluid_result *res, cJSON *fl, int *fell_back);

/* Manifest: created at start, one record per iteration, rewritten (atomically)
 * after every iteration so an interrupted run still says what it did. */
sessile_status grow_manifest_begin(grow_run *r);
cJSON *grow_manifest_iteration(grow_run *r, int it);
sessile_status grow_manifest_write(grow_run *r, const char *state);
void grow_manifest_surface_stats(cJSON *obj, const sessile_surface *s);

#endif
