/* sessile — `sessile sds run MODEL.sds`: the SDS loop on the run framework
 * (docs/sds.md, "The loop"): per step the physics (GPU), inversions found
 * and handled (topology, host + TetGen), morphogens (GPU), rules (host),
 * growth and divisions; frames of the surface (PLY) and the complex (VTU,
 * PVD series); one record per frame interval with the paper's Figure 12
 * figures (cells, tets, ms per step, divisions, inversions). */
#ifndef SESSILE_SDS_RUN_H
#define SESSILE_SDS_RUN_H
#include <stdint.h>
#include "sessile/run/generator.h"
#include "sessile/gpu/gpu.h"
#include "sessile/run/param_table.h"
#include "sessile/run/run.h"
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The model's scalar physics and set-up parameters (docs/sds.md, "Parameters"):
 * the table gives each its default, range, unit and source; a model file's
 * `NAME = value` line overrides the default, --config and --set override
 * the model.  Vectors and files of the scene (box, rock, attractor,
 * surface) and the run's length (t_end, frames) stay the model text's. */
typedef struct sessile_sds_run_params {
  double sphere_radius;       /* u */
  int sphere_subdivisions;
  double start_jitter;
  int start_symmetry;         /* 0: the icosphere; n >= 2: the n-fold symmetric ball */
  int tips_below;             /* bool */
  double density;
  double edge_stiffness, volume_stiffness, surface_multiplier; /* u/s^2 (m u^2/s^2 when uniform) */
  int uniform_stiffness;      /* bool: the paper's same stiffness for every spring */
  double axial_stiffness;     /* a surface spring born along the axis morphogen's gradient: this x its stiffness */
  double axial_growth;        /* the share of a cell's growth its edges take along that axis (0: isotropic) */
  double convergent_extension; /* 1/s: edges between `extending` cells lengthen along the axis, shorten across */
  double damping;             /* the tets' damping on dV/dt */
  double viscosity;           /* 1/s */
  double gravity;             /* u/s^2 along -z */
  int self_collide;           /* bool */
  double obstacle_adhesion;   /* u/s^2: the rock's pull on a cell near it */
  double obstacle_friction;   /* 1/s: the rock's friction on a cell within its reach */
  double dt;                  /* s: the first step */
  double max_move, stable_safety;
  double mass_scaling_dt;     /* s: the step selective mass scaling lifts a stiff cell's bound to (0: none) */
  int device_loop;            /* bool: steps in batches on the device, rules included (the same bytes) */
  int device_rules;           /* sessile_sds_rules_kernel: the device's rules kernel (the same bytes either way) */
  int device_fuse;            /* sessile_sds_fuse: where the fused kernels run (the same bytes every way) */
} sessile_sds_run_params;

/* The rules kernel on the device (device_rules; docs/sds_rules.md,
 * "Generated kernel"): the rules written out as GLSL and compiled at model
 * load, or the bytecode interpreter. */
typedef enum sessile_sds_rules_kernel { SESSILE_SDS_RULES_GENERATED = 0, SESSILE_SDS_RULES_BYTECODE = 1 } sessile_sds_rules_kernel;

extern const sessile_param_table sessile_sds_run_param_table;

/* The table's defaults overridden by the model text's `NAME = value` lines
 * (text parsed as model `name`); a value outside its range, or not one
 * number, is SESSILE_ERR_USAGE naming name:line and the parameter. */
sessile_status sessile_sds_run_params_of_model(const char *text, const char *name, sessile_sds_run_params *p);

typedef struct sessile_sds_run_options {
  sessile_run *run;        /* required */
  sessile_gpu *gpu;        /* required */
  uint64_t seed;           /* division directions where the gradient vanishes */
  const char *model_text;  /* the model (docs/sds_rules.md) */
  const char *model_name;  /* names it in messages */
  /* the parameters (checked against the table); NULL: the model text's own */
  const sessile_sds_run_params *params;
  double t_end;            /* < 0: the model's t_end */
  int frames;              /* < 0: the model's frames */
  uint32_t max_cells;      /* a run that would pass this many cells stops with an error */
} sessile_sds_run_options;

typedef struct sessile_sds_run_stats {
  double time;             /* simulated time reached */
  uint64_t steps, divisions, inversions; /* inversions: transformed (case 1 or 2) */
  uint64_t resisted;       /* inversions without a transformation, resisted physically */
  uint64_t slivers;        /* tet-steps that began inverted (left to their volume springs) */
  uint64_t deferred;       /* divisions put off because the complex was not valid then */
  uint64_t repairs;        /* cavities around lasting inverted tets re-tetrahedralised */
  uint32_t cells, tets;
  int frames;              /* frames written */
  double wall_s;           /* wall time of the loop (this process's part) */
  uint64_t batches;        /* device_loop: batches submitted (this process's part) */
  uint64_t host_steps;     /* device_loop: steps whose rules the host completed (this process's part) */
  int resumed;             /* continued from the run's checkpoint */
  /* a blow-up (docs/sds.md, "Blow-ups"): the run ended with
   * SESSILE_ERR_NUMERIC and frames 0 .. frames - 1 are the good ones */
  int blowup;
  double blowup_time;      /* the start of the step that blew up */
  uint64_t blowup_step;    /* its number (1-based) */
  char blowup_cause[512];  /* what was found */
} sessile_sds_run_stats;

/* Checks a model without a device (its text, physics keys, sphere, run
 * length) with the parameters params (NULL: the model text's own):
 * SESSILE_ERR_USAGE with file:line:column where it can, and when reaching
 * t_end (< 0: the model's) would take more than max_steps steps at the
 * starting organism's stable step (the estimate in the message). */
sessile_status sessile_sds_model_check(const char *text, const char *name, const sessile_sds_run_params *params,
                                       double t_end, uint64_t max_steps);

/* Runs the model to t_end, writing sds/frame_NNNN.ply, sds/frame_NNNN.vtu,
 * sds/series.pvd, sds/final.ply and records, and a checkpoint after every
 * frame and when a stop is requested (then SESSILE_ERR_INTERRUPTED).  When
 * the run holds a checkpoint (a resume), the organism and the loop continue
 * from it, to the same bytes as a run that never stopped; a checkpoint of
 * another model, parameters or options (seed, t_end, frames, max_cells) is
 * SESSILE_ERR_USAGE.  On a failure mid-run (a blow-up: st->blowup set; a
 * topology change that cannot be made) the frames written so far stay and
 * the error names the time and the cause.  A model's `surface = "FILE.ply"`
 * is read relative to the folder of model_name. */
sessile_status sessile_sds_run(const sessile_sds_run_options *o, sessile_sds_run_stats *st);

/* `sds run MODEL` as a generator (sds_generator.c): one iteration per frame
 * interval, a snapshot every frame, its own arguments (MODEL, --t-end,
 * --frames, --max-cells, --max-steps) kept in the run's configuration, exit
 * code 3 on a blow-up.  Not in generators.def: `sds` also has `sds models`,
 * and its MODEL argument does not fit the generic contract test. */
extern const sessile_generator sessile_gen_sds;

#ifdef __cplusplus
}
#endif
#endif
