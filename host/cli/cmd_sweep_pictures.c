/* `sweep gather`'s pictures (docs/sweep.md "Gather"): each metric against
 * each axis (gather/plots/METRIC-vs-AXIS.png: the mean over a combination's
 * completed seeds with its 95 % interval) and a contact sheet of the points'
 * previews (gather/sheet.png), drawn by render's 2-D API (Cairo, no device). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cmd_sweep.h"
#include "sessile/io/io.h"
#include "sessile/render/render2d.h"

#define CMD "sweep gather"

/* A name as part of a file name: letters, digits, '.', '_', '-'; else '_'. */
static void file_part(char *out, size_t n, const char *s) {
  size_t k = 0;
  for (; s[k] && k + 1 < n; k++) {
    char c = s[k];
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    out[k] = ok ? c : '_';
  }
  out[k] = 0;
}

/* A picture gather no longer draws goes, so that gather/ holds this plan's only. */
static void drop_stale(const char *path) {
  if (unlink(path) != 0 && errno != ENOENT) fprintf(stderr, "sessile " CMD ": warning: cannot remove '%s': %s\n", path, strerror(errno));
}

/* An axis value as the plot's x: the number --set reads (true/false: 1/0). */
static int numeric(const char *v, double *x) {
  char *end;
  if (!strcmp(v, "true") || !strcmp(v, "false")) return *x = v[0] == 't', 1;
  *x = strtod(v, &end);
  return end != v && !*end;
}

static const char *param(const cJSON *pt, const char *name) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(pt, "parameters"), name);
  return cJSON_IsString(v) ? v->valuestring : "";
}

enum { LEFT_OUT = 1 << 30 }; /* a combination in no drawn series */

typedef struct pos {
  int series, comb;
  double x;
} pos;

static int by_series_then_x(const void *a, const void *b) {
  const pos *p = a, *q = b;
  if (p->series != q->series) return p->series < q->series ? -1 : 1;
  return p->x < q->x ? -1 : p->x > q->x ? 1 : p->comb - q->comb;
}

/* The layout of the plots of one axis: each combination's x, and its series
 * (a combination of the other axes' values; one series when the axes are
 * zipped); combinations past the 8th series are left out (pos.series -1). */
typedef struct axis_plot {
  pos *p; /* ncomb, sorted by series then x */
  char label[8][160], xlabel[400];
  int nseries, dropped;
} axis_plot;

static void other_axes(char *key, size_t n, const cJSON *axes, const char *axis, const cJSON *pt) {
  size_t k = 0;
  key[0] = 0;
  for (const cJSON *a = axes->child; a && k < n; a = a->next)
    if (strcmp(a->valuestring, axis))
      k += (size_t)snprintf(key + k, n - k, "%s%s=%s", k ? ", " : "", a->valuestring, param(pt, a->valuestring));
}

/* first[c]: combination c's first point (its parameters are the combination's). */
static int axis_layout(const cJSON *plan, const cJSON *const *first, const char *axis, axis_plot *ap) {
  const cJSON *axes = cJSON_GetObjectItemCaseSensitive(plan, "axes");
  const cJSON *comb = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(plan, "sweep"), "combine");
  int ncomb = cJSON_GetObjectItemCaseSensitive(plan, "combinations")->valueint, zip = cJSON_IsString(comb) && !strcmp(comb->valuestring, "zip");
  const char *cat[64];
  int ncat = 0, all_numeric = 1;
  double x;
  for (int c = 0; c < ncomb; c++) all_numeric &= numeric(param(first[c], axis), &x);
  snprintf(ap->xlabel, sizeof ap->xlabel, "%s", axis);
  char key[sizeof ap->label[0]];
  for (int c = 0; c < ncomb; c++) {
    const cJSON *pt = first[c];
    const char *v = param(pt, axis);
    pos *q = &ap->p[c];
    q->comb = c;
    if (all_numeric) numeric(v, &q->x);
    else { /* an enum: its place among the axis's values, named in the label */
      int k = 0;
      while (k < ncat && strcmp(cat[k], v)) k++;
      if (k == ncat && ncat < 64) {
        cat[ncat++] = v;
        size_t l = strlen(ap->xlabel);
        snprintf(ap->xlabel + l, sizeof ap->xlabel - l, "%s%d = %s", k ? ", " : " (", k, v);
      }
      q->x = k;
    }
    other_axes(key, sizeof key, axes, axis, pt);
    int s = 0;
    if (!zip) {
      while (s < ap->nseries && strcmp(ap->label[s], key)) s++;
      if (s == ap->nseries && s < SESSILE_PLOT_MAX_SERIES) snprintf(ap->label[ap->nseries++], sizeof key, "%s", key);
    } else ap->nseries = 1;
    q->series = s < ap->nseries ? s : LEFT_OUT;
    ap->dropped += q->series == LEFT_OUT;
  }
  if (ncat) {
    size_t l = strlen(ap->xlabel);
    snprintf(ap->xlabel + l, sizeof ap->xlabel - l, ")");
  }
  if (ap->nseries == 1) snprintf(ap->label[0], sizeof ap->label[0], "mean over the seeds, 95 %% interval");
  qsort(ap->p, (size_t)ncomb, sizeof *ap->p, by_series_then_x);
  return ncomb - ap->dropped;
}

/* One metric against one axis; 0 when it has no finite mean (no plot). */
static int plot_one(const char *dir, const axis_plot *ap, const char *axis, int n, const double *stat, int nm, int m,
                    const char *metric, double *buf, sessile_status *st) {
  double *x = buf, *y = buf + n, *lo = buf + 2 * n, *hi = buf + 3 * n;
  sessile_plot p = {metric, ap->xlabel, metric, ap->nseries, {{0}}, NULL};
  int any = 0;
  for (int k = 0; k < n; k++) {
    const double *s = stat + ((size_t)ap->p[k].comb * nm + m) * 5;
    x[k] = ap->p[k].x, y[k] = s[1], lo[k] = s[3], hi[k] = s[4];
    any |= isfinite(y[k]);
  }
  for (int s = 0, k = 0; s < ap->nseries; s++) {
    int k0 = k;
    while (k < n && ap->p[k].series == s) k++;
    p.series[s] = (sessile_plot_series){ap->label[s], x + k0, y + k0, (size_t)(k - k0), 0, lo + k0, hi + k0};
  }
  char a[200], b[200], path[4096], title[400];
  file_part(a, sizeof a, metric), file_part(b, sizeof b, axis);
  snprintf(path, sizeof path, "%s/gather/plots/%s-vs-%s.png", dir, a, b);
  if (!any) return drop_stale(path), 0;
  if (ap->dropped) {
    snprintf(title, sizeof title, "%s (%d combinations of the other axes past the first 8 not drawn)", metric, ap->dropped);
    p.title = title;
  }
  *st = sessile_render_plot(&p, NULL, path);
  return 1;
}

static int plots(const char *dir, const cJSON *plan, const double *stat) {
  const cJSON *axes = cJSON_GetObjectItemCaseSensitive(plan, "axes"), *metrics = cJSON_GetObjectItemCaseSensitive(plan, "metrics");
  int ncomb = cJSON_GetObjectItemCaseSensitive(plan, "combinations")->valueint;
  int nm = cJSON_GetArraySize(metrics), npts = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(plan, "points"));
  if (!axes->child || !nm) return EXIT_OK;
  char path[4096];
  snprintf(path, sizeof path, "%s/gather/plots", dir);
  sessile_status st = sessile_mkdirs(path);
  if (st != SESSILE_OK) return cli_fail_in(CMD, st);
  axis_plot ap;
  double *buf = malloc(sizeof *buf * 4 * (size_t)ncomb);
  const cJSON **first = malloc(sizeof *first * (size_t)ncomb);
  ap.p = malloc(sizeof *ap.p * (size_t)ncomb);
  int drawn = 0, skipped = 0, rc = buf && first && ap.p ? EXIT_OK : sweep_oom(CMD), nseeds = npts / ncomb, i = 0;
  /* the points are combination-major: combination c starts at point c * nseeds */
  for (const cJSON *pt = cJSON_GetObjectItemCaseSensitive(plan, "points")->child; !rc && pt; pt = pt->next, i++)
    if (i % nseeds == 0) first[i / nseeds] = pt;
  for (const cJSON *a = axes->child; !rc && a; a = a->next) {
    ap.nseries = ap.dropped = 0;
    int n = axis_layout(plan, first, a->valuestring, &ap), m = 0;
    for (const cJSON *me = metrics->child; !rc && me; me = me->next, m++) {
      st = SESSILE_OK;
      int did = plot_one(dir, &ap, a->valuestring, n, stat, nm, m, me->valuestring, buf, &st);
      drawn += did, skipped += !did;
      if (st != SESSILE_OK) rc = cli_fail_in(CMD, st);
    }
  }
  if (!rc)
    printf("sweep: %d plots in %s/gather/plots/%s\n", drawn, dir,
           skipped ? " (metrics with no completed number not plotted)" : "");
  free(buf), free(first), free(ap.p);
  return rc;
}

/* A PNG's size from its header (IHDR); 0 when it is no PNG. */
static int png_size(const char *path, int *w, int *h) {
  static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char b[24];
  FILE *f = fopen(path, "rb");
  size_t got = f ? fread(b, 1, sizeof b, f) : 0;
  if (f) fclose(f);
  if (got != sizeof b || memcmp(b, magic, 8) || memcmp(b + 12, "IHDR", 4)) return 0;
  *w = (int)((unsigned)b[16] << 24 | (unsigned)b[17] << 16 | (unsigned)b[18] << 8 | b[19]);
  *h = (int)((unsigned)b[20] << 24 | (unsigned)b[21] << 16 | (unsigned)b[22] << 8 | b[23]);
  return *w > 0 && *h > 0;
}

/* The completed points' previews, in point order, one row per combination
 * when the seeds are several (a column per seed); a point without
 * preview.png (--no-preview, a device that could not draw) is left out and
 * counted.  One seed: a row of up to 4, else a square-ish grid.  A sheet is at most SESSILE_RENDER2D_MAX_SIZE a side: past that,
 * the first previews that fit. */
static int sheet(const char *dir, const cJSON *plan, const unsigned char *completed) {
  const cJSON *pts = cJSON_GetObjectItemCaseSensitive(plan, "points"), *axes = cJSON_GetObjectItemCaseSensitive(plan, "axes");
  int npts = cJSON_GetArraySize(pts), width = cJSON_GetObjectItemCaseSensitive(plan, "width")->valueint;
  int nseeds = npts / cJSON_GetObjectItemCaseSensitive(plan, "combinations")->valueint;
  char out[4096];
  snprintf(out, sizeof out, "%s/gather/sheet.png", dir);
  char **path = calloc((size_t)npts, sizeof *path), **cap = calloc((size_t)npts, sizeof *cap);
  int n = 0, missing = 0, cw = 0, th = 0, rc = path && cap ? EXIT_OK : sweep_oom(CMD), i = 0;
  for (const cJSON *pt = pts->child; !rc && pt; pt = pt->next, i++) {
    if (!completed[i]) continue;
    char p[4096], c[512];
    int w, h;
    snprintf(p, sizeof p, "%s/runs/%0*d/preview.png", dir, width, i);
    if (!png_size(p, &w, &h)) {
      missing++;
      continue;
    }
    size_t k = (size_t)snprintf(c, sizeof c, "%0*d seed %.0f", width, i, cJSON_GetObjectItemCaseSensitive(pt, "seed")->valuedouble);
    for (const cJSON *a = axes->child; a && k < sizeof c; a = a->next)
      k += (size_t)snprintf(c + k, sizeof c - k, " %s=%s", a->valuestring, param(pt, a->valuestring));
    path[n] = strdup(p), cap[n] = strdup(c);
    if (!path[n] || !cap[n]) rc = sweep_oom(CMD);
    n++;
    cw = w > cw ? w : cw, th = h > th ? h : th;
  }
  if (!rc && !n) {
    drop_stale(out);
    printf("sweep: no completed point has a preview.png: no contact sheet\n");
  } else if (!rc) {
    enum { PAD = SESSILE_SHEET_PAD, MAX = SESSILE_RENDER2D_MAX_SIZE };
    int cols = nseeds > 1 ? nseeds : n <= 4 ? n : (int)ceil(sqrt(n)), maxcols = (MAX - PAD) / (cw + PAD);
    int maxrows = (MAX - PAD) / (th + SESSILE_SHEET_CAPTION_H + PAD);
    if (cols > maxcols) cols = maxcols > 0 ? maxcols : 1;
    int fit = cols * maxrows < n ? cols * maxrows : n;
    sessile_status st = fit > 0 ? sessile_render_contact_sheet((const char *const *)path, (const char *const *)cap, fit, cols, out)
                                : sessile_error_set(SESSILE_ERR_USAGE, "previews of %d x %d pixels do not fit on a sheet", cw, th);
    if (st != SESSILE_OK) rc = cli_fail_in(CMD, st);
    else {
      printf("sweep: a contact sheet of %d previews in %s", fit, out);
      if (missing) printf(" (%d completed points without preview.png left out)", missing);
      if (fit < n) printf(" (the first %d of %d: a sheet is at most %d pixels a side)", fit, n, MAX);
      printf("\n");
    }
  }
  for (int k = 0; k < npts && path && cap; k++) free(path[k]), free(cap[k]);
  free(path), free(cap);
  return rc;
}

int sweep_gather_pictures(const char *dir, const cJSON *plan, const double *stat, const unsigned char *completed) {
  int rc = plots(dir, plan, stat);
  return rc ? rc : sheet(dir, plan, completed);
}
