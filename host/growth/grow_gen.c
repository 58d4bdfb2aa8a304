/* `sessile grow` as a generator (sessile/run/generator.h): the run loop drives
 * the growth state (grow.c) through grow_iterate.c, the snapshots and final
 * meshes (grow_output.c), the checkpoint (grow_checkpoint.c) and the
 * manifest's members (grow_manifest.c).  sessile_grow_run is the same loop
 * for library callers (benchmarks, tests) with options of their own. */
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"

/* What sessile_grow_run hands the generator through su->caller. */
typedef struct grow_call {
  const sessile_grow_options *o;
  sessile_surface *final;
  sessile_grow_summary *summary;
} grow_call;

static const sessile_gen_option options[] = {
    {"--slices", "slices", "SPEC", "x,y,z",
     "EXR slice planes: 'x,y,z' through the sponge centre,\n"
     "                  'z=3.5,y=19.2' at given heights in cm, or '' for none"},
};
static const sessile_gen_flag flags[] = {{"--no-fields", "no_fields", "no VTU volume fields"}};

/* The library's options from the command's setup. */
static void options_from(const sessile_gen_setup *su, sessile_grow_options *o) {
  sessile_grow_options_default(o);
  o->run = su->run, o->preset = su->preset, o->seed = su->seed;
  o->iterations = su->iterations, o->every = su->every;
  o->slices = su->values[0] ? su->values[0] : "";
  o->fields = !(su->flags & 1u);
  o->monitor = su->say, o->monitor_user = su->say_user;
}

static int needs_device(const void *params) {
  (void)params;
  return 1; /* every solve runs on the device */
}

static sessile_status check(const void *params, const sessile_gen_setup *su) {
  sessile_grow_options o;
  options_from(su, &o);
  SESSILE_CALL(sessile_grow_check_options(params, &o));
  return su->gpu ? sessile_grow_check_device(su->gpu, params) : SESSILE_OK;
}

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  grow_run *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  *state = r;
  const grow_call *call = su->caller;
  if (call) r->opts = *call->o, r->final_out = call->final, r->summary_out = call->summary;
  else options_from(su, &r->opts);
  r->o = &r->opts, r->p = params, r->gpu = su->gpu, r->su = su;
  r->t_start = sessile_wall_seconds();
  sessile_growth_params_from(r->p, &r->gp);
  SESSILE_CALL(grow_setup(r));
  SESSILE_CALL(grow_parse_planes(r));
  return r->o->run ? grow_manifest_begin(r) : SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  grow_run *r = state;
  return grow_checkpoint_restore(r, ck);
}

static sessile_status step(void *state, int it, cJSON *rec) {
  grow_run *r = state;
  return grow_iterate(r, it, rec, sessile_gen_snapshot_kind(r->su, it));
}

/* Every file of the snapshot (rel, the mesh, is one of them); then a
 * final-only snapshot's flow warm starts are put back (docs/run.md). */
static sessile_status snapshot(void *state, const char *rel) {
  grow_run *r = state;
  (void)rel;
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(grow_write_snapshot(r, r->sum.iterations));
  grow_flow_putback(r, &r->saved);
  r->sum.stage_seconds[SESSILE_STAGE_output] += sessile_wall_seconds() - t0;
  return SESSILE_OK;
}

static sessile_status unsnapshot(void *state, int k) { return grow_forget_snapshot(state, k); }

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  return grow_checkpoint_sections(state, sec, n);
}

static sessile_status finish(void *state) {
  grow_run *r = state;
  SESSILE_CALL(grow_normals(r));
  if (r->o->run) SESSILE_CALL(grow_write_final(r));
  return r->final_out ? sessile_surface_copy(&r->surf, r->final_out) : SESSILE_OK;
}

static void destroy(void *state) {
  grow_run *r = state;
  if (!r) return;
  r->sum.total_seconds = sessile_wall_seconds() - r->t_start;
  r->sum.final_vertices = r->surf.nv;
  r->sum.final_triangles = r->surf.nf;
  /* the totals so far, also of a failed run (its close writes the manifest) */
  if (r->o->run) (void)grow_manifest_totals(r);
  if (r->summary_out) *r->summary_out = r->sum;
  grow_teardown(r);
  free(r);
}

static sessile_status preset(const char *name, void *params) { return sessile_params_preset(params, name); }

static const sessile_gen_presets presets = {
    "radiate",
    "                  radiate: Table 1 as is (radiate accretive growth);\n"
    "                  crella: Halichondrid normals + randomised x/y position (§4.7)",
    preset};

const sessile_generator sessile_gen_grow = {
    .name = "grow",
    .summary = "grow a sponge (O'Hagan et al.'s accretive model)",
    .about =
        "Grows a sponge by O'Hagan et al.'s accretive model: per iteration the nutrient\n"
        "field is solved (diffusion limited: a Laplace problem, c = 0 on the sponge's\n"
        "surface by cut cells, c = 1 in the far field; multigrid on the GPU), each vertex\n"
        "takes up the nutrient's flux into it (probe=flux; probe=paper: eq 6), which is\n"
        "translocated over the surface (eqs 7-8), and each vertex grows by the Chindapol\n"
        "function (eq 10) unless that would make the surface cross itself; then the\n"
        "surface is remeshed.  Lengths are in cm; docs/model.md has every equation and\n"
        "parameter, docs/science.md what converges and what the model shows.\n"
        "The ocean current (stationary Navier-Stokes, docs/fluid.md) is solved at each\n"
        "snapshot for the velocity and pressure outputs (fluid_at_snapshots); with\n"
        "--set diffusion_limited=false it is solved every iteration and advects the\n"
        "nutrient (--set domain=conforming meshes the water around the sponge with\n"
        "TetGen; fluid_resolution=2 doubles the flow's resolution at ~10x the time).\n"
        "\n"
        "The run directory (docs/run.md) holds manifest.json, records.jsonl (one line per\n"
        "iteration: stage timings, solver iterations and true residuals, mesh\n"
        "statistics), checkpoint.bin, sponge/final.ply and final.obj, and at each\n"
        "snapshot sponge/iter_NNNN.ply, slices/iter_NNNN_P.exr and fields/iter_NNNN.vtu\n"
        "(fields/series.pvd opens the VTU series in ParaView).  --resume gives the bytes\n"
        "of a run that never stopped; the same seed on the same device gives the same\n"
        "bytes.  --out defaults to runs/<preset>.",
    .seed_help = "every random choice",
    .out_default = "runs/%s",
    .snapshot_name = "sponge/iter_%04d.ply",
    .preview = "sponge/final.ply",
    .table = &sessile_grow_param_table,
    .iterations = 50,
    .every = 10,
    .flags = flags,
    .nflags = 1,
    .needs_device = needs_device,
    .check = check,
    SESSILE_GEN_CALLBACKS,
    .options = options,
    .noptions = 1,
    .presets = &presets,
    .unsnapshot = unsnapshot,
};

sessile_status sessile_grow_run(sessile_gpu *g, const sessile_grow_params *p, const sessile_grow_options *o,
                                sessile_surface *final, sessile_grow_summary *summary) {
  if (summary) memset(summary, 0, sizeof *summary);
  SESSILE_CALL(sessile_params_validate(p));
  SESSILE_CHECK(o->iterations >= 0, SESSILE_ERR_USAGE, "iterations must be >= 0");
  SESSILE_CALL(sessile_grow_check_device(g, p));
  grow_call call = {o, final, summary};
  sessile_gen_setup su = {.run = o->run, .gpu = g, .seed = o->seed, .iterations = o->iterations,
                          .every = o->every, .caller = &call};
  int done = 0;
  return sessile_run_loop(&sessile_gen_grow, p, &su, NULL, NULL, &done);
}
