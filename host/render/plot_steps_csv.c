/* sessile render — Fig. 12 of Porter & McCormack's SDS paper from the
 * per-step log sds/steps.csv of `sessile sds run` (render2d.h): ms per step
 * (left axis) and the number of cells (right axis) against simulated time.
 * The CSV is read whole (it is a few MB for a long run) and parsed here:
 * columns by the header's names, every field of every row a finite number. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "run_internal.h"
#include "sessile/io/io.h"

#define MAX_LINE 4096 /* a row of 8 numbers is ~150 bytes */
#define MAX_FIELDS 64

enum { C_TIME, C_MS, C_CELLS, NCOLS };
static const char *const col_names[NCOLS] = {"time", "ms", "cells"};

typedef struct steps {
  double *v[NCOLS]; /* time, ms (NaN where no measurement), cells */
  size_t n, cap;
} steps;

static void steps_free(steps *s) {
  for (int k = 0; k < NCOLS; k++) free(s->v[k]);
}

/* Splits line (modified) at commas into at most MAX_FIELDS fields, each
 * trimmed of spaces; the number of fields, or -1 when there are more. */
static int split(char *line, char **field) {
  int n = 0;
  for (char *f = line;; n++) {
    if (n == MAX_FIELDS) return -1;
    char *end = f + strcspn(f, ",");
    int last = !*end;
    *end = 0;
    while (*f == ' ' || *f == '\t') f++;
    for (char *e = end; e > f && (e[-1] == ' ' || e[-1] == '\t');) *--e = 0;
    field[n] = f;
    if (last) return n + 1;
    f = end + 1;
  }
}

/* The header: where time, ms and cells are (a missing one is an error). */
static sessile_status header(char *line, const char *shown, long lineno, int col[NCOLS], int *nfields) {
  char copy[200];
  snprintf(copy, sizeof copy, "%s", line);
  char *field[MAX_FIELDS];
  int n = split(line, field);
  SESSILE_CHECK(n > 0, SESSILE_ERR_USAGE, "%s line %ld: a header of more than %d columns", shown, lineno, MAX_FIELDS);
  for (int c = 0; c < NCOLS; c++) {
    col[c] = -1;
    for (int k = 0; k < n && col[c] < 0; k++)
      if (!strcmp(field[k], col_names[c])) col[c] = k;
    SESSILE_CHECK(col[c] >= 0, SESSILE_ERR_USAGE,
                  "%s has no column '%s' (its header, line %ld: \"%s\"; needs time, ms and cells; not a steps.csv?)",
                  shown, col_names[c], lineno, copy);
  }
  *nfields = n;
  return SESSILE_OK;
}

/* One row: as many fields as the header, each a finite number. */
static sessile_status row(char *line, const char *shown, long lineno, const int col[NCOLS], int nfields, steps *s) {
  char *field[MAX_FIELDS];
  int n = split(line, field);
  SESSILE_CHECK(n == nfields, SESSILE_ERR_USAGE, "%s line %ld: %s%d fields where the header has %d", shown, lineno,
                n < 0 ? "more than " : "", n < 0 ? MAX_FIELDS : n, nfields);
  double v[MAX_FIELDS];
  for (int k = 0; k < n; k++) {
    char *end = NULL;
    v[k] = strtod(field[k], &end);
    SESSILE_CHECK(field[k][0] && !*end && isfinite(v[k]), SESSILE_ERR_USAGE,
                  "%s line %ld: field %d ('%.40s') is not a finite number", shown, lineno, k + 1, field[k]);
  }
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 1024;
    for (int c = 0; c < NCOLS; c++) {
      double *q = realloc(s->v[c], cap * sizeof *q);
      SESSILE_CHECK(q, SESSILE_ERR_NO_MEMORY, "out of host memory reading %s", shown);
      s->v[c] = q;
    }
    s->cap = cap;
  }
  s->v[C_TIME][s->n] = v[col[C_TIME]];
  /* 0 ms is no measurement (a step not timed), so no point */
  s->v[C_MS][s->n] = v[col[C_MS]] > 0 ? v[col[C_MS]] : NAN;
  s->v[C_CELLS][s->n] = v[col[C_CELLS]];
  s->n++;
  return SESSILE_OK;
}

/* Every row of the text; blank lines skipped, the first other line the header.
 * A last row without its newline is a row still being appended by a running
 * run (the log grows by whole lines, but a reader may see part of a write):
 * it is left out, not an error. */
static sessile_status parse(const char *text, size_t len, const char *shown, steps *s) {
  int col[NCOLS], nfields = 0, have_header = 0;
  long lineno = 0;
  char line[MAX_LINE];
  for (const char *p = text, *end = text + len; p < end;) {
    const char *nl = memchr(p, '\n', (size_t)(end - p)), *eol = nl ? nl : end;
    size_t n = (size_t)(eol - p);
    lineno++;
    SESSILE_CHECK(n < sizeof line, SESSILE_ERR_USAGE, "%s line %ld: longer than %d bytes", shown, lineno, MAX_LINE - 1);
    memcpy(line, p, n);
    line[n] = 0;
    p = eol + 1;
    if (!nl && have_header) break;
    SESSILE_CHECK(strlen(line) == n, SESSILE_ERR_USAGE, "%s line %ld: a NUL byte (not a text file?)", shown, lineno);
    if (n && line[n - 1] == '\r') line[--n] = 0;
    if (strspn(line, " \t") == n) continue;
    if (have_header) {
      SESSILE_CALL(row(line, shown, lineno, col, nfields, s));
    } else {
      SESSILE_CALL(header(line, shown, lineno, col, &nfields));
      have_header = 1;
    }
  }
  SESSILE_CHECK(have_header, SESSILE_ERR_USAGE, "%s is empty (no header)", shown);
  SESSILE_CHECK(s->n > 0, SESSILE_ERR_USAGE, "%s has a header but no steps yet", shown);
  return SESSILE_OK;
}

sessile_status rp_plot_sds_steps_text(const char *text, size_t len, const char *shown, const sessile_render2d_opts *o,
                                      const char *png_out) {
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  steps s = {0};
  sessile_status st = parse(text, len, shown, &s);
  if (st == SESSILE_OK) {
    sessile_plot p = {
        .title = "Time per step and cells against simulated time (cf. Porter & McCormack, Fig. 12)",
        .xlabel = "simulated time (s)",
        .ylabel = "time per step (ms)",
        .y2label = "cells",
        .nseries = 2,
        .series = {{.label = "ms per step", .x = s.v[C_TIME], .y = s.v[C_MS], .n = s.n},
                   {.label = "cells", .x = s.v[C_TIME], .y = s.v[C_CELLS], .n = s.n, .axis2 = 1}},
    };
    st = sessile_render_plot(&p, o, png_out);
  }
  steps_free(&s);
  return st;
}

sessile_status sessile_render_plot_sds_steps(const char *steps_csv, const sessile_render2d_opts *o,
                                             const char *png_out) {
  SESSILE_CHECK(steps_csv && steps_csv[0], SESSILE_ERR_USAGE, "no steps.csv given");
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  char *text = NULL, shown[600];
  size_t len = 0;
  SESSILE_CALL(sessile_read_small_file(steps_csv, RP_STEPS_MAX, "steps log", &text, &len));
  snprintf(shown, sizeof shown, "'%.580s'", steps_csv);
  sessile_status st = rp_plot_sds_steps_text(text, len, shown, o, png_out);
  free(text);
  return st;
}
