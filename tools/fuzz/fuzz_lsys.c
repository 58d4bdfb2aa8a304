/* Fuzz target of the L-system grammar parser and derivation
 * (sessile/coral/lsystem.h): the input is a grammar.  A refused grammar must give
 * SESSILE_ERR_USAGE with one line "fuzz.lsys:LINE:COLUMN: ..." (LINE within
 * the input's lines); an accepted one is derived up to 6 steps within
 * 20000 modules (only the size limit, a non-finite parameter or memory may
 * stop it), its homomorphism applied, and the string must be consistent
 * (offsets, parameter counts, format), then drawn by the turtle into finite
 * segments with positive radii.  Anything else aborts.  Built with libFuzzer by run_lsys.sh, or
 * with driver.c (-DFUZZ_WORDS) by CMake's fuzz_lsys_short. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/coral/lsystem.h"
#include "sessile/mesh/skeleton.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fail(const char *what) {
  fprintf(stderr, "fuzz_lsys: %s (last message: %s)\n", what, sessile_error_message());
  abort();
}

static void check_refusal(const uint8_t *data, size_t size) {
  const char *m = sessile_error_message();
  if (strncmp(m, "fuzz.lsys:", 10)) fail("a refusal without 'fuzz.lsys:'");
  if (strchr(m, '\n')) fail("a refusal of more than one line");
  long line = 0, col = 0;
  char tail = 0;
  if (sscanf(m + 10, "%ld:%ld%c", &line, &col, &tail) == 3) {
    long lines = 1;
    for (size_t i = 0; i < size; i++) lines += data[i] == '\n';
    if (line < 1 || line > lines || col < 1 || tail != ':') fail("a refusal's line or column outside the input");
  } else if (!strstr(m, "larger than")) {
    fail("a refusal without line and column");
  }
}

static void check_string(const sessile_lsys_string *s) {
  size_t np = 0;
  for (uint32_t i = 0; i < s->n; i++) {
    if (s->off[i] != np || s->np[i] > SESSILE_LSYS_MAX_PARAMS) fail("string offsets inconsistent");
    for (uint8_t a = 0; a < s->np[i]; a++)
      if (!isfinite(s->par[np + a])) fail("a non-finite parameter in the string");
    np += s->np[i];
  }
  if (np != s->npar) fail("string parameter count inconsistent");
  char *t = NULL;
  if (sessile_lsys_string_format(s, &t) == SESSILE_OK && strlen(t) < s->n) fail("formatted string too short");
  free(t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  sessile_lsys *g = NULL;
  sessile_status s = sessile_lsys_parse((const char *)data, size, "fuzz.lsys", 0, NULL, NULL, &g);
  if (s != SESSILE_OK) {
    if (g) fail("a refused grammar returned a handle");
    if (s == SESSILE_ERR_USAGE) check_refusal(data, size);
    else if (s != SESSILE_ERR_NO_MEMORY) fail("an unexpected status from the parser");
    return 0;
  }
  int it = sessile_lsys_iterations(g);
  if (it < 0 || it > 1000) fail("iterations out of range");
  sessile_lsys_string str = {0};
  uint64_t rng = 1;
  s = sessile_lsys_derive(g, it < 6 ? it : 6, &rng, 20000, &str);
  if (s == SESSILE_OK && sessile_lsys_has_homomorphism(g)) {
    check_string(&str);
    sessile_lsys_string h = {0};
    s = sessile_lsys_homomorphism(g, &str, &rng, 20000, &h);
    sessile_lsys_string_free(&str);
    str = h;
  }
  if (s == SESSILE_OK) {
    if (str.n > 20000) fail("the string exceeds max_modules");
    check_string(&str);
    sessile_turtle_params tp = {.step = 1, .angle = sessile_lsys_angle(g), .thickness = 0.1,
                                .thickness_variance = 0.2, .width_factor = sessile_lsys_width_factor(g),
                                .tropism = {0, 0, 1}, .tropism_strength = 0.1, .min_radius = 1e-3};
    sessile_skeleton sk = {0};
    uint64_t trng = 2;
    s = sessile_turtle_interpret(&str, &tp, &trng, &sk, NULL);
    /* huge parameters may overflow positions: the skeleton refuses those */
    if (s != SESSILE_OK && s != SESSILE_ERR_USAGE && s != SESSILE_ERR_NO_MEMORY) fail("turtle failed");
    for (uint32_t i = 0; s == SESSILE_OK && i < sk.n; i++)
      if (!(sk.ra[i] > 0 && sk.rb[i] > 0 && isfinite(sk.a[3 * i] + sk.b[3 * i + 2]))) fail("a bad segment");
    sessile_skeleton_free(&sk);
  } else if (s != SESSILE_ERR_TOO_LARGE && s != SESSILE_ERR_NUMERIC && s != SESSILE_ERR_NO_MEMORY &&
             s != SESSILE_ERR_USAGE) { /* a rule whose parameters come out NaN or infinite: the grammar's fault, file:line */
    fail("an unexpected status from the derivation");
  }
  sessile_lsys_string_free(&str);
  sessile_lsys_destroy(g);
  return 0;
}
