/* The SDS loop's state and its parts, shared by the files of the loop
 * (sessile/sds/sds_run.h; docs/sds.md "The loop"): sds_setup.c (the model, the
 * starting organism), sds_rules_step.c (neighbours, morphogens, rules),
 * sds_divide.c (division through the complex), sds_inversions.c (§3.1.2
 * and the repairs), sds_frames.c (frames and records), sds_steplog.c
 * (sds/steps.csv, sds/divisions.csv) and sds_loop.c (one step, the loop, checkpoints). */
#ifndef SESSILE_SDS_SIM_H
#define SESSILE_SDS_SIM_H
#include <stdint.h>
#include "sessile/run/generator.h"
#include "sessile/run/run.h"
#include "sds/sds_checkpoint.h"
#include "sessile/sds/sds.h"
#include "sessile/sds/sds_process.h"
#include "sessile/sds/sds_run.h"
#include "sessile/sds/sds_topo.h"

/* the state the loop reads for convergent extension (the rules set it) */
#define SDS_STATE_EXTENDING "extending"

typedef struct sds_sim {
  const char *text;           /* the model */
  sessile_sds_model *model;
  sessile_sds o;
  sessile_sds_params p;
  sessile_sds_run_params prm; /* the parameter table's values (sds_params.c) */
  sessile_sds_gpu *pg;
  sessile_morph_gpu *mg;
  sessile_surface rock;       /* the obstacle, when the model has one */
  double attractor[3];
  double density;
  uint32_t *nbr_off, *nbr;    /* cell neighbours (from the edges) */
  double *xprev;              /* positions before the step (rewind) */
  double time, dt;
  int stalled;                /* steps in a row that were rewound to their start */
  double *retry_at;           /* per cell: a deferred division is not tried again before this time */
  uint32_t retry_cap;
  uint64_t *sliver;           /* the repairs' backoff: per failed inverted tet (FNV-1a of its cells),
                                 failures in a row, the step before which it is not tried again */
  uint32_t nsliver, sliver_cap;
  uint64_t sl_hash[64];       /* sds_sliver_table's cache: entry e's name and tet when it was found */
  uint32_t sl_tet[64];
  int topo_changed;           /* the complex changed since the last upload (refresh uploads it whole) */
  int sm_changed;             /* the edges' rest multipliers changed since (axial_growth) */
  int morph_lists_set;        /* the morphogen kernel has the current neighbour lists (neighbours() clears) */
  uint64_t rng;
  int tip_state;              /* state index of `tip`, -1 none */
  int birth_state;            /* state index of `birth_radius` (the loop keeps it), -1 none */
  sessile_sds_run_stats *st;
  uint64_t div_interval, inv_interval; /* counts since the last record */
  uint64_t key;               /* sds_ckpt_key of the model and options */
  uint64_t seed;              /* the run's seed (division directions, the start's jitter) */
  double c0[3], size0;        /* the starting organism's centroid and size */
  int frame;                  /* the next frame to write */
  uint64_t steps_frame;       /* steps since the last frame */
  int resumed;                /* restored from a checkpoint */
  double step_t0;             /* the time at the start of the step being made */
  double t_end;               /* resolved: the option or the model's */
  int frames;
  double *frame_time;         /* the simulated time of each frame written (frames + 1 entries) */
  char *steplog;              /* sds/steps.csv rows not yet appended (flushed before each checkpoint) */
  size_t steplog_len, steplog_cap;
  char *divlog;               /* sds/divisions.csv rows not yet appended (flushed with the step log's) */
  size_t divlog_len, divlog_cap;
  /* the loop on the device (device_loop; sds_loop_device.c) */
  struct sds_gpu_rules *rules_dev; /* the rules' kernels and the cells' amounts and states */
  int rules_sync;             /* the device holds the host's cells, amounts and states */
  uint32_t batch_steps;       /* steps the next batch asks for */
  double *blog;               /* a batch's log: dt and end time per step */
} sds_sim;

/* The model line NAME's first number, or def (t_end, frames). */
double sds_param1(const sessile_sds_model *m, const char *name, double def);

/* sds_setup.c: the model without a device (text, parameters, physics,
 * sphere, run length); the starting organism; its tips; a cell below each
 * tip (§3.6); the start's centroid and size (the blow-up test's yardstick). */
sessile_status sds_check_model(sds_sim *s, const char *where, const sessile_sds_run_params *params, int *level,
                               double *radius);
sessile_status sds_import_organism(sds_sim *s, const char *where, int level, double radius);
sessile_status sds_mark_tips(sds_sim *s, const char *where);
sessile_status sds_cells_below_tips(sds_sim *s);
void sds_measure_start(sds_sim *s);

/* sds_rules_step.c: the cell neighbour lists (from the edges), the cells as
 * the morphogens and rules see them, the device's copy after a change, and
 * one step of morphogens and rules (growth, divisions). */
sessile_status sds_neighbours(sds_sim *s);
sessile_morph_cells sds_cells_of(const sds_sim *s);
sessile_status sds_refresh(sds_sim *s);
/* sds_axial.c: a spring's stiffness multiplier on the surface at birth,
 * 1 + (q - 1) cos^2 of the angle between d and g (1 where either is 0); the
 * springs of o born since the last call (edge_k 0) given theirs, g the sum
 * of morphogen k's gradients at their two cells; and that for the loop (the
 * model's axis morphogen and axial_stiffness, the neighbour lists current). */
double sds_axial_k(double q, const double *d, const double *g);
void sds_axial_springs(sessile_sds *o, const sessile_morph_cells *cells, int k, double q);
sessile_status sds_axial_assign(sds_sim *s);
/* The oriented growth (axial_growth A): the cells' radii have gone from r0
 * to o->r; each edge whose cells grew takes w = 1 + A (3 cos^2 - 1) times
 * that growth of its rest length, the angle now between it and the sum of
 * morphogen k's gradients at its cells (w = 1 where there is none), through
 * its s_m; *changed = 1 when any s_m moved. */
sessile_status sds_axial_grow_edges(sessile_sds *o, const sessile_morph_cells *cells, int k, double A,
                                    const double *r0, int *changed);
/* Convergent extension (convergent_extension C): each edge between two cells
 * whose state j is set multiplies its s_m by 1 + C dt (3 cos^2 - 1), the
 * angle between it and the sum of morphogen k's gradients at its cells (no
 * change where there is none); *changed = 1 when any moved. */
sessile_status sds_axial_extend_edges(sessile_sds *o, const sessile_morph_cells *cells, int k, double C, double dt,
                                      int j, int *changed);
/* The loop's step of both (the model's axis morphogen, axial_growth with r0
 * the radii before the rules' growth or NULL for none, convergent_extension
 * over dt, sm_changed): the growth's pass, then the extension's, on one
 * gradient per cell. */
sessile_status sds_axial_edges_step(sds_sim *s, const double *r0, double dt);
sessile_status sds_rules(sds_sim *s, double dt);
sessile_status sds_divisions(sds_sim *s, const sessile_sds_divide *req, size_t n);

/* sds_divide.c: the organism as a growable complex and back; one division. */
sessile_status sds_complex_of(const sessile_sds *o, sessile_sds_topo_complex *cx);
sessile_status sds_take_complex(sds_sim *s, const sessile_sds_topo_complex *cx, const uint32_t *tet_from);
sessile_status sds_divide(sds_sim *s, uint32_t c, const double dir[3]);

/* sds_inversions.c: the tets the last step inverted (§3.1.2), and repairs
 * of lasting ones. */
sessile_status sds_inversions(sds_sim *s, int *handled, double *frac);
/* The backoff table as a batch on the device takes it (sessile_sds_batch's
 * slivers: pairs of a tet and the steps until its repair is due, for up to
 * SESSILE_SDS_SLIVERS_MAX entries); returns the entries, or UINT32_MAX when
 * the table cannot be given (too long, or an entry whose tet is gone: the
 * next inverted tet must go to the host, which prunes it). */
uint32_t sds_sliver_table(sds_sim *s, uint32_t *pairs);

/* sds_frames.c: a frame's surface (PLY) and complex (VTU), the PVD series,
 * one record per frame interval. */
sessile_status sds_write_frame(sds_sim *s, sessile_run *run, int frame, const char *ply_rel);
sessile_status sds_write_pvd(sessile_run *run, int nframes, const double *times);
sessile_status sds_record(sds_sim *s, sessile_run *run, int frame, double ms_per_step, uint64_t steps);
sessile_status sds_record_fill(sds_sim *s, cJSON *r, int frame, double ms_per_step, uint64_t steps);

/* sds_steplog.c: sds/steps.csv, the paper's Figure 12 per step: its header
 * (a new run), one row per step (appended once a MiB has gathered), and
 * the rows kept so far appended. */
sessile_status sds_steplog_start(sessile_run *run);
sessile_status sds_steplog_row(sds_sim *s, sessile_run *run, double dt, double ms, uint64_t divisions,
                               uint64_t inversions);
sessile_status sds_steplog_flush(sds_sim *s, sessile_run *run);
/* sds/divisions.csv, one row per division (time, the dividing cell, its
 * daughter, the cell's place and radius before it divided): which limb
 * divided when (Figure 12's simultaneous limbs; tools/sds/figures.py). */
sessile_status sds_divlog_row(sds_sim *s, uint32_t cell, uint32_t daughter, const double x[3], double r);

/* sds_loop.c: a blow-up (docs/sds.md, "Blow-ups"): the message, and the
 * run's stats say what happened when. */
sessile_status sds_blowup(sds_sim *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* sds_loop.c: what follows a step's physics (the state downloaded, the
 * physics' verdict a blow-up when st is SESSILE_ERR_NUMERIC): the motion
 * checked, inversions, the rules, the counts; the cells checked after the
 * rules; frame k's time. */
sessile_status sds_physics_failed(sds_sim *s, sessile_status st);
sessile_status sds_finish_step(sds_sim *s, double elapsed);
sessile_status sds_check_motion(sds_sim *s);
sessile_status sds_check_cells(sds_sim *s);
double sds_frame_time(const sds_sim *s, int k);
/* sds_loop_device.c (device_loop): the loop on the device's set-up and
 * teardown, and one batch of steps ending at the first step at or past
 * t_stop at the latest, what the host does after it included. */
sessile_status sds_device_batch(sds_sim *s, sessile_run *run, double t_stop);
sessile_status sds_device_loop_create(sds_sim *s, sessile_gpu *gpu);
void sds_device_loop_destroy(sds_sim *s);

/* `sds run` on the generator framework (sds_generator.c): the command's own
 * arguments (the generator's extra), stored in the run's configuration. */
typedef struct sds_gen_args {
  const char *model;       /* MODEL as given, NULL: none */
  char *name, *text;       /* the run's model: its name and text (owned unless borrowed) */
  int borrowed;            /* name and text belong to the caller (sessile_sds_run) */
  double t_end;            /* < 0: the model's */
  int frames;              /* <= 0: the model's */
  int have_t_end;
  unsigned max_cells, max_steps; /* 0: the defaults */
  sessile_sds_run_stats stats;   /* the run's, after end() */
  unsigned given;                /* bit per option seen: a repeated one is refused */
} sds_gen_args;

/* The generator's state: the simulation, its stats and the run around it. */
typedef struct sds_gen_state {
  sds_sim s;
  sessile_sds_run_stats st;
  const sessile_gen_setup *su;
  double t0, tf;           /* wall seconds at the start and at the last frame */
  sds_ckpt_loop loop;      /* the checkpoint's loop section and counts (sds_sections) */
  uint64_t counts[6];
} sds_gen_state;

/* sds_setup.c: the run's length, the option's or the model's. */
sessile_status sds_run_length(const sessile_sds_model *m, double t_end_in, int frames_in, double *t_end, int *frames);
/* sds_loop.c: the pieces of the generator's callbacks. */
sessile_status sds_gen_setup(sds_gen_state *g, const sessile_sds_run_params *params);
sessile_status sds_gen_restore(sds_gen_state *g, const sessile_ckpt *ck);
sessile_status sds_gpu_create(sds_gen_state *g);
sessile_status sds_frame_steps(sds_gen_state *g);
sessile_status sds_sections(sds_gen_state *g, sessile_ckpt_section *sec, int *n);
void sds_teardown(sds_sim *s);
#endif
