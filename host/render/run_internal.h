/* sessile render — a run directory's pictures: the plan (run_plan.c: what a
 * generator's run holds and what to draw) shared with run_render.c (drawing). */
#ifndef SESSILE_RUN_RENDER_INTERNAL_H
#define SESSILE_RUN_RENDER_INTERNAL_H
#include "sessile/render/render2d.h"
#include "sessile/render/render_run.h"

/* Where a generator writes its meshes (docs/render.md "Runs"). */
typedef struct rp_layout {
  const char *generator;   /* the manifest's "generator" */
  const char *folder;      /* meshes: FOLDER/final.ply and FOLDER/PREFIXNNNN.ply */
  const char *snap_prefix; /* "iter_", "frame_", or NULL: no snapshots */
  const char *snap_word;   /* caption: "iteration 10", "frame 3" */
  int slices;              /* slices/iter_NNNN_PLANE.exr with FOLDER/iter_NNNN.ply as outline */
  const char *plots[2];    /* records.jsonl presets (render2d.h) */
  const char *steps_log;   /* FOLDER/steps.csv, the per-step log drawn as plot_step_times.png, or NULL */
  const char *final_name;  /* the final mesh or scene in FOLDER; NULL: final.ply */
} rp_layout;

typedef struct rp_snap {
  int index;         /* NNNN */
  char *mesh;        /* path */
  char caption[96];
} rp_snap;

typedef struct rp_slice {
  int index;
  char *exr, *outline; /* outline: the snapshot's mesh, or NULL */
  char base[160];      /* "iter_0002_y" */
  int all_channels;    /* the last snapshot's slices: every channel */
} rp_slice;

/* At most this many snapshots go on the contact sheet (evenly spaced, the
 * first and the last included): 12 rows of 4 tiles of 320 x 240 fit the
 * sheet's 16384-pixel limit with room to spare. */
#define RP_MAX_TILES 48
#define RP_TILE_W 320
#define RP_TILE_H 240
#define RP_SHEET_COLS 4

struct sessile_render_plan {
  char *run_dir, *out_dir;
  int listed;   /* out_dir is RUN/renders: its files go into the manifest */
  int dfd;      /* the run folder (flocked when listed) */
  int running;  /* a run held the lock when planned (read-only plans only) */
  const rp_layout *lay;
  char *final_mesh; /* FOLDER/final.ply (a reef's scene.json), or the last snapshot when the run has none yet */
  int final_is_snapshot;
  rp_snap *snaps;
  int nsnaps;
  rp_slice *slices;
  int nslices;
  char *records; /* records.jsonl, or NULL */
  int has_steps_log; /* FOLDER/steps.csv is there (a regular file) */
  uint32_t width, height;
  int quiet;
  sessile_progress_fn progress;
  void *progress_user;
  int npictures; /* planned, for progress (the slices' counted by check_inputs) */
  char **written; /* names written into out_dir */
  int nwritten;
};

/* Reads a small regular file name in the folder dfd without following a
 * symlink: *text NULL when absent. */
sessile_status rp_read_at(int dfd, const char *dir, const char *name, size_t max, char **text, size_t *len);

/* The per-step log is read whole: ~55 000 rows of ~100 bytes for a long run. */
#define RP_STEPS_MAX ((size_t)256 << 20)
/* sessile_render_plot_sds_steps of the log's text (text[len] = 0), which
 * the run renderer reads through the run folder's descriptor; shown names
 * the file in messages (quoted). */
sessile_status rp_plot_sds_steps_text(const char *text, size_t len, const char *shown, const sessile_render2d_opts *o,
                                      const char *png_out);
#endif
