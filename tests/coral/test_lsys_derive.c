/* L-system derivation (host/coral/lsys_*.c) against hand-computed strings:
 * parallel rewriting, parametric arithmetic, conditions, branches, left and
 * right context skipping branches and ignored symbols (ABOP ch. 1.8), the
 * % cut, defines and their overrides; stochastic productions by chi-square;
 * the size limit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/coral/lsystem.h"
#include "testutil.h"

/* text derived n times with seed; the result as text (caller frees) or NULL */
static char *derive(const char *text, int n, uint64_t seed, int nov, const char *const *on, const double *ov) {
  sessile_lsys *g = NULL;
  if (sessile_lsys_parse(text, strlen(text), "t.lsys", nov, on, ov, &g) != SESSILE_OK) {
    printf("  parse failed: %s\n", sessile_error_message());
    return NULL;
  }
  sessile_lsys_string s = {0};
  char *out = NULL;
  uint64_t rng = seed;
  if (sessile_lsys_derive(g, n, &rng, 1000000, &s) == SESSILE_OK) sessile_lsys_string_format(&s, &out);
  else printf("  derive failed: %s\n", sessile_error_message());
  sessile_lsys_string_free(&s);
  sessile_lsys_destroy(g);
  return out;
}

static void expect(const char *what, const char *text, int n, const char *want) {
  char *got = derive(text, n, 1, 0, NULL, NULL);
  int ok = got && !strcmp(got, want);
  if (!ok) printf("  %s: got '%s', want '%s'\n", what, got ? got : "(null)", want);
  t_true(what, ok);
  free(got);
}

static void chi_square(void) {
  /* 2^14 A's, each rewritten once by weights 0.2 : 0.5 : 0.3 */
  const char *g = "axiom: D(14)\n"
                  "D(n) : n > 0 -> D(n - 1) D(n - 1)\n"
                  "D(n) : n == 0 -> A\n"
                  "A -(0.2)-> X\nA -(0.5)-> Y\nA -(0.3)-> Z\n";
  char *s = derive(g, 16, 7, 0, NULL, NULL);
  t_true("chi-square grammar derived", s != NULL);
  if (!s) return;
  double c[3] = {0, 0, 0}, p[3] = {0.2, 0.5, 0.3};
  size_t n = strlen(s), other = 0;
  for (size_t i = 0; i < n; i++) {
    if (s[i] == 'X') c[0]++;
    else if (s[i] == 'Y') c[1]++;
    else if (s[i] == 'Z') c[2]++;
    else other++;
  }
  double N = c[0] + c[1] + c[2], chi = 0;
  for (int k = 0; k < 3; k++) chi += (c[k] - N * p[k]) * (c[k] - N * p[k]) / (N * p[k]);
  printf("  weights 0.2/0.5/0.3: counts %g %g %g of %g, chi2 = %.3f (2 dof; critical 13.816 at 0.001)\n", c[0],
         c[1], c[2], N, chi);
  t_true("16384 modules, nothing else", N == 16384 && other == 0);
  t_check("chi-square of stochastic choice below the 0.001 critical value 13.816", chi, 13.816);
  free(s);
  /* weights normalised among the productions whose conditions hold: the
   * first (x > 5) never holds, so Y : Z = 1 : 2 */
  const char *g2 = "axiom: D(13)\n"
                   "D(n) : n > 0 -> D(n - 1) D(n - 1)\n"
                   "D(n) : n == 0 -> B(1)\n"
                   "B(x) : x > 5 -(5)-> X\nB(x) -(1)-> Y\nB(x) -(2)-> Z\n";
  s = derive(g2, 15, 9, 0, NULL, NULL);
  if (!s) return;
  double y = 0, z = 0, x = 0;
  for (size_t i = 0; s[i]; i++) x += s[i] == 'X', y += s[i] == 'Y', z += s[i] == 'Z';
  N = y + z;
  chi = (y - N / 3) * (y - N / 3) / (N / 3) + (z - 2 * N / 3) * (z - 2 * N / 3) / (2 * N / 3);
  printf("  conditional weights: X %g, Y %g, Z %g, chi2 = %.3f (1 dof; critical 10.828 at 0.001)\n", x, y, z, chi);
  t_true("a weighted production whose condition fails is never chosen", x == 0 && N == 8192);
  t_check("chi-square among the productions whose conditions hold below 10.828", chi, 10.828);
  free(s);
}

int main(void) {
  expect("algae (ABOP 1.2): 5 steps", "axiom: A\nA -> AB\nB -> A\n", 5, "ABAABABAABAAB");
  expect("branches", "axiom: A\nA -> F[+A][-A]\n", 2, "F[+F[+A][-A]][-F[+A][-A]]");
  expect("parametric arithmetic", "axiom: A(1, 2)\nA(x, y) -> A(x + y, x * y) B(x / 2)\n", 2, "A(5,6)B(1.5)B(0.5)");
  expect("functions and ternary", "axiom: A(4)\nA(x) -> A(sqrt(x), x > 3 ? 1 : 0, min(x, 2))\n", 1, "A(2,1,2)");
  expect("conditions", "axiom: A(0)\nA(x) : x < 3 -> A(x + 1) F\nA(x) : x >= 3 -> B\n", 5, "BFFF");
  expect("first matching production wins", "axiom: A(5)\nA(x) : x > 1 -> B\nA(x) -> C\n", 1, "B");
  expect("parameter count must match", "axiom: A(1)A\nA(x) -> B\nA -> C\n", 1, "BC");
  expect("deleting successor", "axiom: AXA\nX ->\n", 1, "AA");
  expect("signal propagation uses the old string (parallel)", "axiom: BAAAA\nB < A -> B\nB -> A\n", 2, "AABAA");
  expect("right context skips a bracketed branch", "axiom: A[C]B\nA > B -> X\n", 1, "X[C]B");
  expect("right context stops at the branch's end", "axiom: [A]B\nA > B -> X\n", 1, "[A]B");
  expect("left context skips a completed branch", "axiom: B[A]C\nB < C -> X\n", 1, "B[A]X");
  expect("left context does not see into a completed branch", "axiom: B[A]C\nA < C -> X\n", 1, "B[A]C");
  expect("left context climbs to the parent", "axiom: B[C]\nB < C -> X\n", 1, "B[X]");
  expect("left context from a later sibling branch reaches the parent", "axiom: A[B][C]\nA < C -> X\n", 1, "A[B][X]");
  expect("multi-module left context over completed branches", "axiom: A[X]B[Y]C\nA B < C -> Z\n", 1, "A[X]B[Y]Z");
  expect("multi-module right context over a branch", "axiom: AB[X]C\nA > B C -> Z\n", 1, "ZB[X]C");
  expect("bracketed right context enters a branch", "axiom: A[B]C\nA > [B]C -> X\n", 1, "X[B]C");
  expect("... the ']' skips the rest of the entered branch", "axiom: A[BDE[F]]C\nA > [B]C -> X\n", 1, "X[BDE[F]]C");
  expect("... and the branch must hold the pattern", "axiom: A[D]C\nA > [B]C -> X\n", 1, "A[D]C");
  expect("... an open '[' matches a branch's first module", "axiom: A[B]\nA > [B -> X\n", 1, "X[B]");
  expect("ignored symbols are skipped", "ignore: +-\naxiom: B+C-D\nB < C > D -> X\n", 1, "B+X-D");
  expect("... and not without ignore", "axiom: B+C-D\nB < C > D -> X\n", 1, "B+C-D");
  expect("multi-module contexts with parameters", "axiom: A(1)B(2)C(4)D(8)E(16)\nA(a) B(b) < C(c) > D(d) E(e) -> C(a + b + c + d + e)\n",
         1, "A(1)B(2)C(31)D(8)E(16)");
  expect("% cuts the rest of its branch", "axiom: F[A]F\nA -> B%C[D]E\n", 1, "F[B]F");
  expect("% in a nested branch keeps the closing bracket", "axiom: F[A[K]L]M\nA -> %\n", 1, "F[]M");
  expect("% outside any branch cuts to the end", "axiom: FAG[H]\nA -> [X]%\n", 1, "F[X]");
  expect("defines in expressions and the axiom", "define a = 2\ndefine b = a * 3\naxiom: A(b)\nA(x) -> A(x + a)\n", 1,
         "A(8)");
  expect("weighted arrow with one candidate", "axiom: A\nA -(0.3)-> B\n", 1, "B");
  expect("# is a symbol when attached, a comment after a blank", "axiom: F#F # comment\nF -> !F\n", 1, "!F#!F");
  {
    const char *on[1] = {"a"};
    double ov[1] = {5};
    char *s = derive("define a = 2\ndefine b = a * 3\naxiom: A(b)\n", 0, 1, 1, on, ov);
    t_true("an overridden define changes the later ones (a = 5 -> b = 15)", s && !strcmp(s, "A(15)"));
    free(s);
  }
  {
    /* uniform(): in range, deterministic from the seed */
    const char *g = "axiom: D(10)\nD(n) : n > 0 -> D(n - 1) D(n - 1)\nD(n) : n == 0 -> A(uniform(2, 3))\n";
    char *a = derive(g, 11, 3, 0, NULL, NULL), *b = derive(g, 11, 3, 0, NULL, NULL), *c = derive(g, 11, 4, 0, NULL, NULL);
    t_true("same seed, same string; another seed, another string", a && b && c && !strcmp(a, b) && strcmp(a, c));
    int inr = a != NULL, cnt = 0;
    for (const char *p = a; p && (p = strstr(p, "A(")); p += 2, cnt++) {
      double v = strtod(p + 2, NULL);
      inr &= v >= 2 && v < 3;
    }
    t_true("uniform(2, 3) draws lie in [2, 3), 1024 of them", inr && cnt == 1024);
    free(a), free(b), free(c);
  }
  {
    /* the homomorphism: applied once to the derived string, not derived */
    const char *t = "axiom: A\nA -> AB\nhomomorphism:\nA -> F(2)\nB -> f[B]\n";
    sessile_lsys *g = NULL;
    t_must("parse", sessile_lsys_parse(t, strlen(t), "t.lsys", 0, NULL, NULL, &g));
    sessile_lsys_string a = {0}, b = {0};
    uint64_t rng = 1;
    char *sa = NULL, *sb = NULL;
    t_must("derive", sessile_lsys_derive(g, 2, &rng, 1000, &a));
    t_must("homomorphism", sessile_lsys_homomorphism(g, &a, &rng, 1000, &b));
    sessile_lsys_string_format(&a, &sa), sessile_lsys_string_format(&b, &sb);
    t_true("homomorphism: derivation ABB unchanged by it, drawn as F(2)f[B]f[B]", sa && sb && !strcmp(sa, "ABB") &&
           !strcmp(sb, "F(2)f[B]f[B]") && sessile_lsys_has_homomorphism(g));
    free(sa), free(sb);
    sessile_lsys_string_free(&a), sessile_lsys_string_free(&b);
    sessile_lsys_destroy(g);
  }
  chi_square();
  {
    /* the limit: doubling 30 times refuses with an estimate */
    sessile_lsys *g = NULL;
    const char *t = "axiom: A\nA -> AA\n";
    t_must("parse", sessile_lsys_parse(t, strlen(t), "t.lsys", 0, NULL, NULL, &g));
    sessile_lsys_string s = {0};
    uint64_t rng = 1;
    sessile_status st = sessile_lsys_derive(g, 30, &rng, 100000, &s);
    printf("  limit: %s\n", sessile_error_message());
    t_true("a string beyond max_modules is refused (SESSILE_ERR_TOO_LARGE, with an estimate)",
           st == SESSILE_ERR_TOO_LARGE && strstr(sessile_error_message(), "estimate"));
    rng = 1;
    st = sessile_lsys_derive(g, 16, &rng, 100000, &s);
    t_true("... and 2^16 modules within it are derived", st == SESSILE_OK && s.n == 65536);
    sessile_lsys_string_free(&s);
    sessile_lsys_destroy(g);
  }
  return t_finish(NULL);
}
