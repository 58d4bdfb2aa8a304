/* Malformed grammars (host/coral/lsys_parse.c): each refused with
 * SESSILE_ERR_USAGE and the message "where:line:column: what" pointing at
 * the offending byte; the shipped grammars all parse and derive. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/coral/lsystem.h"
#include "testutil.h"

static void bad(const char *text, size_t len, const char *where_prefix, const char *word) {
  sessile_lsys *g = NULL;
  sessile_status s = sessile_lsys_parse(text, len, "g.lsys", 0, NULL, NULL, &g);
  const char *m = sessile_error_message();
  char what[160];
  snprintf(what, sizeof what, "refused at %s (%s)", where_prefix, word);
  int ok = s == SESSILE_ERR_USAGE && g == NULL && !strncmp(m, where_prefix, strlen(where_prefix)) && strstr(m, word) &&
           !strchr(m, '\n');
  if (!ok) printf("  got status %d, message '%s'\n", s, m);
  else printf("  %s\n", m);
  t_true(what, ok);
  sessile_lsys_destroy(g);
}
#define BAD(t, w, word) bad(t, sizeof(t) - 1, w, word)

int main(void) {
  BAD("axiom: A(1\n", "g.lsys:1:9: ", "without its ')'");
  BAD("axiom: A\nA(x) -> B(x+)\n", "g.lsys:2:13: ", "nexpected end");
  BAD("axiom: A\nA(x) -> B(y)\n", "g.lsys:2:11: ", "y");
  BAD("axiom: A\nfoo: 3\n", "g.lsys:2:1: ", "unknown directive");
  BAD("# comment\nA -> B\n", "g.lsys:2:", "no 'axiom:'");
  BAD("axiom: A\nA(x, x) -> B\n", "g.lsys:2:6: ", "named twice");
  BAD("axiom: A\n  < B -> C\n", "g.lsys:2:3: ", "without a left context");
  BAD("axiom: A\nA -> B(1,)\n", "g.lsys:2:10: ", "empty parameter");
  BAD("axiom: A\ndefine 1x = 2\n", "g.lsys:2:8: ", "needs a name");
  BAD("axiom: A\ndefine x 2\n", "g.lsys:2:10: ", "'=' expected");
  BAD("axiom: A\ndefine x = 1\ndefine x = 2\n", "g.lsys:3:8: ", "defined twice");
  BAD("axiom: A\niterations: 2.5\n", "g.lsys:2:13: ", "integer");
  BAD("axiom: A\nA B -> C\n", "g.lsys:2:1: ", "one module");
  BAD("axiom: A\nA -> B\nthis is not\n", "g.lsys:3:1: ", "neither a production");
  BAD("axiom: A\naxiom: B\n", "g.lsys:2:1: ", "second 'axiom:'");
  BAD("axiom: A\nA : -> B\n", "g.lsys:2:3: ", "without a condition");
  BAD("axiom: A\nA -()-> B\n", "g.lsys:2:5: ", "empty weight");
  BAD("axiom: A\nA(x) : x > -> B\n", "g.lsys:2:", "xpected");
  BAD("axiom: A\nA -> B(1) C(2\n", "g.lsys:2:12: ", "without its ')'");
  BAD("axiom: A\nA(2) -> B\n", "g.lsys:2:3: ", "parameter name");
  BAD("axiom: A\nA -> B\x01\n", "g.lsys:2:7: ", "printable");
  BAD("axiom: A\r\nA -> B\0C\n", "g.lsys:2:7: ", "NUL");
  BAD("axiom: A\nangle: 1e400\n", "g.lsys:2:", "1e400");
  BAD("axiom: A\nhomomorphism:\nhomomorphism:\n", "g.lsys:3:1: ", "second 'homomorphism:'");
  BAD("axiom: A\nhomomorphism: A\n", "g.lsys:2:15: ", "alone");
  BAD("axiom: A\nB [ < A -> C\n", "g.lsys:2:1: ", "left context");
  BAD("axiom: A\nA > B] -> C\n", "g.lsys:2:3: ", "without its '['");
  {
    /* a define that does not exist cannot be overridden */
    const char *t = "axiom: A\n", *on[1] = {"nope"};
    double ov[1] = {1};
    sessile_lsys *g = NULL;
    sessile_status s = sessile_lsys_parse(t, strlen(t), "g.lsys", 1, on, ov, &g);
    t_true("overriding an unknown define is refused", s == SESSILE_ERR_USAGE && !g && strstr(sessile_error_message(), "nope"));
  }
  /* every shipped grammar parses and derives to something drawable */
  t_true("three shipped grammars", sessile_lsys_builtin_count() == 3);
  for (int i = 0; i < sessile_lsys_builtin_count(); i++) {
    size_t len = 0;
    const char *text = sessile_lsys_builtin_text(i, &len), *name = sessile_lsys_builtin_name(i);
    char where[64];
    snprintf(where, sizeof where, "%s.lsys", name);
    sessile_lsys *g = NULL;
    sessile_status s = sessile_lsys_parse(text, len, where, 0, NULL, NULL, &g);
    sessile_lsys_string str = {0};
    uint64_t rng = 1;
    if (s == SESSILE_OK) s = sessile_lsys_derive(g, sessile_lsys_iterations(g), &rng, 4000000, &str);
    uint32_t nF = 0;
    for (uint32_t k = 0; k < str.n; k++) nF += str.sym[k] == 'F';
    printf("  %s: %d iterations, %u modules, %u F\n", name, g ? sessile_lsys_iterations(g) : -1, str.n, nF);
    char what[96];
    snprintf(what, sizeof what, "shipped grammar %s parses and derives (more than 100 F)", name);
    t_true(what, s == SESSILE_OK && nF > 100);
    sessile_lsys_string_free(&str);
    sessile_lsys_destroy(g);
  }
  return t_finish(NULL);
}
