/* Internal to host/growth: the run's state shared by the loop (grow.c) and
 * its outputs (grow_output.c, grow_manifest.c). */
#ifndef SESSILE_GROW_INTERNAL_H
#define SESSILE_GROW_INTERNAL_H

#include <cjson/cJSON.h>
#include "sessile/mesh/box.h"
#include "sessile/growth/grow.h"
#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/growth_ref.h"
#include "sessile/la/la.h"
#include "sessile/fem/nutrient_cut.h"
#include "sessile/mesh/surface.h"
#include "sessile/fem/advdiff.h"
#include "sessile/fem/fluid.h"
#include "sessile/mesh/tetmesh.h"

typedef struct grow_plane {
  int axis;     /* 0 x, 1 y, 2 z */
  double value; /* cm */
  char name[32];
} grow_plane;

/* A final-only snapshot (the last iteration, off the --every grid) solves
 * the flow only for its outputs; its solution must not become the next warm
 * start, or a resumed longer run would differ from one that never stopped.
 * keep copies the flow's warm starts before such a solve, putback restores
 * them after the snapshot is written (and frees the copies). */
typedef struct grow_flow_saved {
  int active, was_ready;
  double *up, *cup;
  sessile_tetmesh cmesh;
} grow_flow_saved;

typedef struct grow_run {
  const sessile_grow_params *p;
  const sessile_grow_options *o;
  sessile_gpu *gpu;
  sessile_la *la;
  sessile_box box;
  double center[3];
  sessile_surface surf;
  sessile_cut_nutrient *nutrient; /* the cut-cell nutrient and its box levels */
  sessile_growth_gpu *growth;
  sessile_buffer *solid;          /* the finest level's solid mask (the nutrient's) */
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
  int warned_degenerate;
  double t_start;
  sessile_grow_summary sum;
  /* The generator's (grow_gen.c): the options (r->o points here when the
   * command's setup made them), the kernels' parameters, the normals of the
   * current surface (snapshots and the final meshes write them), the growth
   * step's positions, a final-only snapshot's flow warm starts (put back
   * after it), the checkpoint's bytes, and a library caller's outputs. */
  sessile_grow_options opts;
  const sessile_gen_setup *su;
  sessile_growth_params gp;
  double *normals, *newpos;
  grow_flow_saved saved;
  void *ck_bytes[3];
  sessile_surface *final_out;
  sessile_grow_summary *summary_out;
} grow_run;

/* The state (grow.c): box, sponge, nutrient and kernels; freed whole. */
sessile_status grow_setup(grow_run *r);
void grow_teardown(grow_run *r);

/* One iteration (grow_iterate.c); snap: sessile_gen_snapshot_kind.  Its
 * stages: classify and the nutrient (grow_nutrient.c), the flow
 * (grow_flow.c), uptake, translocation and growth (grow_step.c), the
 * remesh (grow_remesh.c); r->normals are the new surface's at the end. */
sessile_status grow_iterate(grow_run *r, int it, cJSON *rec, int snap);
void grow_progress(grow_run *r, const char *stage, double part);
sessile_status grow_classify(grow_run *r);
sessile_status grow_nutrient_solve(grow_run *r, int it, cJSON *rec, const sessile_vec **probe_field);
sessile_status grow_flow_iteration(grow_run *r, int it, cJSON *rec, int snap);
sessile_status grow_growth_step(grow_run *r, int it, cJSON *rec, const sessile_vec *probe_field);
sessile_status grow_remesh(grow_run *r, int it, cJSON *rec);
sessile_status grow_normals(grow_run *r);

/* Parses o->slices into run->planes (SESSILE_ERR_USAGE on a bad spec). */
sessile_status grow_parse_planes(grow_run *r);
/* Writes sponge/iter_NNNN.ply, slices and fields for iteration it. */
sessile_status grow_write_snapshot(grow_run *r, int it);
/* Removes the snapshot of iteration it (files and series entry): a resumed
 * run that goes past its old last iteration drops that final-only snapshot. */
sessile_status grow_forget_snapshot(grow_run *r, int it);
/* Writes sponge/final.ply and final.obj. */
sessile_status grow_write_final(grow_run *r);

/* The flow of iteration it (records it under "fluid" in rec), with ufine
 * and pfine filled; the advected nutrient into r->c. */
sessile_status grow_flow_solve(grow_run *r, int it, cJSON *rec);
sessile_status grow_nutrient_advected(grow_run *r, sessile_solve_result *res);
void grow_flow_teardown(grow_run *r);
/* The flow's and the advected nutrient's state, created once (a resume
 * creates them to restore their warm starts). */
sessile_status grow_flow_setup(grow_run *r);
sessile_status grow_advected_setup(grow_run *r);
/* The run's fluid parameters (grow_flow.c). */
void grow_fluid_params(const grow_run *r, sessile_fluid_params *fp);
/* The conforming flow (grow_flow_conforming.c): TetGen's mesh of the box
 * minus the current surface, solved warm, interpolated to ufine/pfine by the
 * GPU locator.  *fell_back = 1 (reason under "fallback" in fl) when TetGen
 * rejected the surface; then nothing else changed. */
sessile_status grow_flow_conforming(grow_run *r, sessile_fluid_result *res, cJSON *fl, int *fell_back);

/* A warning to the caller's monitor (grow_monitor.c); warnings also go to
 * the iteration's record by the caller. */
void grow_warn(const grow_run *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The manifest's growth members (parameters, device, box, ...), and the
 * totals (set at checkpoints and the end; the run writes the manifest). */
sessile_status grow_manifest_begin(grow_run *r);
sessile_status grow_manifest_totals(grow_run *r);
void grow_manifest_surface_stats(cJSON *obj, const sessile_surface *s);

sessile_status grow_flow_keep(grow_run *r, grow_flow_saved *k);
void grow_flow_putback(grow_run *r, grow_flow_saved *k);
void grow_flow_saved_free(grow_flow_saved *k);

/* Contact inhibition (grow_guard.c, docs/intersection.md).  motion: newpos
 * (the growth step's positions; r->surf still at the old ones) guarded so
 * the surface does not cross itself; records "held_back_vertices" and more
 * under "growth".  check: after the remesh, the remesher's contact figures
 * under "remesh"; with check_every_iteration, "self_intersections", which
 * must be 0 (else SESSILE_ERR_INTERNAL). */
sessile_status grow_guard_motion(grow_run *r, int it, double *newpos, cJSON *rec);
sessile_status grow_guard_check(grow_run *r, int it, const sessile_remesh_stats *rs, cJSON *rec);

/* Checkpoint (grow_checkpoint.c): the state as sections (their bytes valid
 * until the next call), and back. */
sessile_status grow_checkpoint_sections(grow_run *r, sessile_ckpt_section *sec, int *n);
sessile_status grow_checkpoint_restore(grow_run *r, const sessile_ckpt *c);

#endif
