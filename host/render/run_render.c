/* sessile render RUN_DIR — draws a plan (run_plan.c) into its folder:
 *   final_{oblique,side,top,front}.png   the final mesh from the standard views
 *   snap_<PREFIX>NNNN.png, snapshots.png  each snapshot small, and the contact sheet
 *   slice_iter_NNNN_PLANE_CHANNEL.png     each slice (c, or the first channel;
 *                                         every channel of the last snapshot)
 *   plot_<preset>.png                     plots of records.jsonl
 *   plot_step_times.png                   sds: FOLDER/steps.csv (ms per step and cells)
 * Into RUN/renders the names are added to the manifest's file list (under
 * the run folder's lock), so a later --force removes them with the run. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "run_internal.h"
#include "sessile/io/io.h"
#include "sessile/render/render2d.h"
#include "sessile/render/render_mesh.h"
#include "sessile/render/render_scene.h"

static const char *const views[4] = {"oblique", "side", "top", "front"};

/* out_dir/name (remembered for the manifest); the pictures before it are done */
static sessile_status out_path(sessile_render_plan *p, const char *name, char **path) {
  sessile_progress_count(p->progress, p->progress_user, "picture", p->nwritten, p->npictures, p->nwritten > 0);
  size_t n = strlen(p->out_dir) + strlen(name) + 2;
  *path = malloc(n);
  char *keep = strdup(name);
  char **w = realloc(p->written, (size_t)(p->nwritten + 1) * sizeof *w);
  if (w) p->written = w;
  if (!*path || !keep || !w) {
    free(*path), free(keep);
    *path = NULL;
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  snprintf(*path, n, "%s/%s", p->out_dir, name);
  p->written[p->nwritten++] = keep;
  return SESSILE_OK;
}

static void say(FILE *log, const sessile_render_plan *p, const char *name, const char *what) {
  if (log) fprintf(log, "wrote %s/%s: %s\n", p->out_dir, name, what);
}

static sessile_status draw_final(sessile_render_plan *p, sessile_gpu *g, FILE *log) {
  for (int v = 0; v < 4; v++) {
    sessile_render_options o;
    sessile_render_options_default(&o);
    o.width = p->width, o.height = p->height, o.view = views[v];
    char name[64], *path = NULL, what[160];
    snprintf(name, sizeof name, "final_%s.png", views[v]);
    SESSILE_CALL(out_path(p, name, &path));
    sessile_render_result res;
    sessile_status s = sessile_render_mesh_png(g, p->final_mesh, &o, path, &res);
    free(path);
    SESSILE_CALL(s);
    snprintf(what, sizeof what, "%s view of %s, %ux%u, grid %g cm", views[v],
             p->final_is_snapshot ? "the last snapshot (no final mesh yet)" : "the final mesh", o.width, o.height,
             res.grid_spacing_cm);
    say(log, p, name, what);
  }
  return SESSILE_OK;
}

/* The tiles of the contact sheet: n snapshots evenly spaced over them, the
 * first and the last included; tile k shows snapshot tile_snap(p, k, n). */
static int tile_count(const sessile_render_plan *p) { return p->nsnaps < RP_MAX_TILES ? p->nsnaps : RP_MAX_TILES; }
static int tile_snap(const sessile_render_plan *p, int k, int n) {
  return n == p->nsnaps ? k : (int)((long long)k * (p->nsnaps - 1) / (n - 1));
}

static sessile_status draw_snapshots(sessile_render_plan *p, sessile_gpu *g, FILE *log) {
  int n = tile_count(p);
  if (n == 0) return SESSILE_OK;
  char **tiles = calloc((size_t)n, sizeof *tiles);
  const char **caps = calloc((size_t)n, sizeof *caps);
  sessile_status s = tiles && caps ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (int k = 0; s == SESSILE_OK && k < n; k++) {
    int i = tile_snap(p, k, n);
    sessile_render_options o;
    sessile_render_options_default(&o);
    o.width = RP_TILE_W, o.height = RP_TILE_H;
    char name[64];
    snprintf(name, sizeof name, "snap_%s%04d.png", p->lay->snap_prefix, p->snaps[i].index);
    s = out_path(p, name, &tiles[k]);
    if (s == SESSILE_OK) s = sessile_render_mesh_png(g, p->snaps[i].mesh, &o, tiles[k], NULL);
    caps[k] = p->snaps[i].caption;
  }
  char *sheet = NULL;
  if (s == SESSILE_OK) s = out_path(p, "snapshots.png", &sheet);
  if (s == SESSILE_OK)
    s = sessile_render_contact_sheet((const char *const *)tiles, caps, n, n < RP_SHEET_COLS ? n : RP_SHEET_COLS, sheet);
  if (s == SESSILE_OK) {
    char what[160];
    snprintf(what, sizeof what, "contact sheet of %d of %d snapshots (%s %d to %d), tiles snap_*.png", n, p->nsnaps,
             p->lay->snap_word, p->snaps[0].index, p->snaps[p->nsnaps - 1].index);
    say(log, p, "snapshots.png", what);
  }
  for (int k = 0; tiles && k < n; k++) free(tiles[k]);
  free(tiles), free(caps), free(sheet);
  return s;
}

/* One slice's picture; with check, only reads it (check_inputs). */
static sessile_status draw_slice(sessile_render_plan *p, const rp_slice *sl, const char *channel, FILE *log,
                                 int check) {
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  if (check) {
    sessile_slice_layout lay;
    p->npictures++;
    return sessile_render_slice_layout(sl->exr, channel, &o, &lay);
  }
  o.outline_ply = sl->outline;
  char name[256], *path = NULL;
  snprintf(name, sizeof name, "slice_%s_%s.png", sl->base, channel);
  SESSILE_CALL(out_path(p, name, &path));
  sessile_status s = sessile_render_slice(sl->exr, channel, &o, path);
  free(path);
  SESSILE_CALL(s);
  char what[160];
  snprintf(what, sizeof what, "channel %s%s", channel, sl->outline ? ", outline from the snapshot's mesh" : "");
  say(log, p, name, what);
  return SESSILE_OK;
}

static sessile_status draw_slices(sessile_render_plan *p, FILE *log, int check) {
  for (int i = 0; i < p->nslices; i++) {
    const rp_slice *sl = &p->slices[i];
    char names[1024];
    SESSILE_CALL(sessile_render_slice_channels(sl->exr, names, sizeof names));
    /* c (the nutrient) when present, else the first; the last snapshot: all */
    int has_c = 0;
    for (char *t = names, *save = NULL; (t = strtok_r(t, ", ", &save)); t = NULL) has_c |= !strcmp(t, "c");
    SESSILE_CALL(sessile_render_slice_channels(sl->exr, names, sizeof names));
    if (!sl->all_channels) {
      if (has_c) SESSILE_CALL(draw_slice(p, sl, "c", log, check));
      else {
        names[strcspn(names, ",")] = 0;
        SESSILE_CALL(draw_slice(p, sl, names, log, check));
      }
      continue;
    }
    for (char *t = names, *save = NULL; (t = strtok_r(t, ", ", &save)); t = NULL)
      SESSILE_CALL(draw_slice(p, sl, t, log, check));
  }
  return SESSILE_OK;
}

static sessile_status draw_plots(sessile_render_plan *p, FILE *log) {
  for (int k = 0; k < 2 && p->lay->plots[k]; k++) {
    const char *what = p->lay->plots[k];
    if (!p->records) {
      if (log) fprintf(log, "no plot_%s.png: the run has no records.jsonl\n", what);
      continue;
    }
    char name[64], *path = NULL;
    snprintf(name, sizeof name, "plot_%s.png", what);
    SESSILE_CALL(out_path(p, name, &path));
    sessile_status s = sessile_render_plot_records(p->records, what, NULL, path);
    free(path);
    if (s == SESSILE_ERR_USAGE) { /* no record has the keys yet (a run stopped early) */
      p->nwritten--, free(p->written[p->nwritten]);
      if (log) fprintf(log, "no %s: %s\n", name, sessile_error_message());
      continue;
    }
    SESSILE_CALL(s);
    say(log, p, name, what);
  }
  return SESSILE_OK;
}

/* The per-step log's text, read through the run folder's descriptor (no
 * symlink followed, a regular file of at most RP_STEPS_MAX bytes): *text
 * NULL when it is gone. */
static sessile_status read_steps_log(const sessile_render_plan *p, char *shown, size_t n, char **text, size_t *len) {
  snprintf(shown, n, "'%.400s/%s/%s'", p->run_dir, p->lay->folder, p->lay->steps_log);
  *text = NULL, *len = 0;
  int fd = openat(p->dfd, p->lay->folder, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0 && errno == ENOENT) return SESSILE_OK;
  SESSILE_CHECK(fd >= 0, SESSILE_ERR_USAGE, "cannot open '%s/%s': %s", p->run_dir, p->lay->folder, strerror(errno));
  sessile_status s = sessile_read_small_file_at(fd, p->lay->steps_log, shown, RP_STEPS_MAX, text, len);
  close(fd);
  return s;
}

/* plot_step_times.png from the per-step log; a log with no steps yet (or
 * damaged) is skipped with a note, as a plot of records is. */
static sessile_status draw_step_times(sessile_render_plan *p, FILE *log) {
  if (!p->lay->steps_log) return SESSILE_OK;
  const char *name = "plot_step_times.png";
  char shown[600], *text = NULL, *path = NULL;
  size_t len = 0;
  if (p->has_steps_log) SESSILE_CALL(read_steps_log(p, shown, sizeof shown, &text, &len));
  if (!text) {
    if (log) fprintf(log, "no %s: the run has no %s/%s\n", name, p->lay->folder, p->lay->steps_log);
    return SESSILE_OK;
  }
  sessile_status s = out_path(p, name, &path);
  if (s == SESSILE_OK) s = rp_plot_sds_steps_text(text, len, shown, NULL, path);
  free(path), free(text);
  if (s == SESSILE_ERR_USAGE) {
    p->nwritten--, free(p->written[p->nwritten]);
    if (log) fprintf(log, "no %s: %s\n", name, sessile_error_message());
    return SESSILE_OK;
  }
  SESSILE_CALL(s);
  say(log, p, name, "ms per step and cells against simulated time");
  return SESSILE_OK;
}

/* Lists renders/NAME in the run's manifest (once each), under the lock. */
static sessile_status list_in_manifest(sessile_render_plan *p) {
  char *text = NULL;
  size_t len = 0;
  SESSILE_CALL(rp_read_at(p->dfd, p->run_dir, "manifest.json", (size_t)64 << 20, &text, &len));
  cJSON *m = text ? cJSON_ParseWithLength(text, len) : NULL;
  free(text);
  SESSILE_CHECK(m, SESSILE_ERR_USAGE, "'%s/manifest.json' went missing or is damaged", p->run_dir);
  cJSON *files = cJSON_GetObjectItemCaseSensitive(m, "files");
  if (!cJSON_IsArray(files)) files = cJSON_AddArrayToObject(m, "files");
  int added = 0;
  for (int i = 0; files && i < p->nwritten; i++) {
    char rel[300];
    snprintf(rel, sizeof rel, "renders/%s", p->written[i]);
    int have = 0;
    const cJSON *f;
    cJSON_ArrayForEach(f, files) have |= cJSON_IsString(f) && !strcmp(f->valuestring, rel);
    if (!have) cJSON_AddItemToArray(files, cJSON_CreateString(rel)), added++;
  }
  sessile_status s = SESSILE_OK;
  if (added) { /* printed as the run framework prints it, so a rerun changes nothing */
    char *out = cJSON_Print(m);
    if (!out) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else {
      size_t n = strlen(out);
      out[n] = '\n';
      char path[4200];
      snprintf(path, sizeof path, "%s/manifest.json", p->run_dir);
      s = sessile_write_file_atomic(path, out, n + 1);
      free(out);
    }
  }
  cJSON_Delete(m);
  return s;
}

static sessile_status check_mesh(const char *path) {
  sessile_render_mesh *m = NULL;
  sessile_render_scene *sc = NULL;
  sessile_status s = sessile_render_is_scene(path) ? sessile_render_scene_read(path, &sc) : sessile_render_mesh_read(path, &m);
  sessile_render_mesh_destroy(m);
  sessile_render_scene_destroy(sc);
  return s;
}

/* Every input read once before anything is written (docs/render.md "Runs"):
 * a truncated mesh or a damaged EXR refuses the render with nothing
 * written, not half a folder of pictures; the price is a second read. */
static sessile_status check_inputs(sessile_render_plan *p) {
  SESSILE_CALL(check_mesh(p->final_mesh));
  int n = tile_count(p);
  p->npictures = 4 + n + (n > 0) + (p->lay->steps_log != NULL);
  for (int k = 0; k < 2 && p->lay->plots[k]; k++) p->npictures++;
  for (int k = 0; k < n; k++) SESSILE_CALL(check_mesh(p->snaps[tile_snap(p, k, n)].mesh));
  for (int i = 0; i < p->nslices; i++)
    if (p->slices[i].outline) SESSILE_CALL(check_mesh(p->slices[i].outline));
  return draw_slices(p, NULL, 1);
}

sessile_status sessile_render_plan_run(sessile_render_plan *p, sessile_gpu *g, FILE *log) {
  if (p->quiet) log = NULL;
  SESSILE_CALL(check_inputs(p));
  if (log && p->running)
    fprintf(log, "note: a run is still writing '%s': drawing what it holds now\n", p->run_dir);
  if (p->listed) {
    if (mkdirat(p->dfd, "renders", 0777) != 0 && errno != EEXIST)
      return sessile_error_set(SESSILE_ERR_IO, "cannot create '%s': %s", p->out_dir, strerror(errno));
    struct stat st;
    SESSILE_CHECK(fstatat(p->dfd, "renders", &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode), SESSILE_ERR_USAGE,
                  "'%s' is not a folder (a symlink or file): refused", p->out_dir);
  } else {
    SESSILE_CALL(sessile_mkdirs(p->out_dir));
  }
  sessile_status s = draw_final(p, g, log);
  if (s == SESSILE_OK) s = draw_snapshots(p, g, log);
  if (s == SESSILE_OK) s = draw_slices(p, log, 0);
  if (s == SESSILE_OK) s = draw_plots(p, log);
  if (s == SESSILE_OK) s = draw_step_times(p, log);
  if (s == SESSILE_OK) sessile_progress_count(p->progress, p->progress_user, "picture", p->npictures, p->npictures, 1);
  /* what was written is listed even after a failure, so --force removes it */
  if (p->listed && p->nwritten) {
    sessile_status ls = list_in_manifest(p);
    if (s == SESSILE_OK) s = ls;
  }
  return s;
}
