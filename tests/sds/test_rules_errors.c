/* Bad model texts end with SESSILE_ERR_USAGE and one message that starts
 * with file:line:column (1-based) pointing at the fault, never a crash:
 * unknown morphogen, state or name in a condition; syntax errors in
 * conditions and actions; bad declarations and parameters. */
#include <stdio.h>
#include <string.h>
#include "sessile/sds/sds_process.h"
#include "testutil.h"

static const char *head = "morphogen phi diffusion=0.1 decay=0\nstate tip\n"; /* lines 1-2 */

static void bad(const char *body, const char *where, const char *needle) {
  char text[4096], want[64];
  snprintf(text, sizeof text, "%s%s", head, body);
  sessile_sds_model *m = NULL;
  sessile_status s = sessile_sds_model_parse(text, "bad.sds", &m);
  const char *msg = sessile_error_message();
  snprintf(want, sizeof want, "bad.sds:%s: ", where);
  char what[300];
  snprintf(what, sizeof what, "%-46.46s -> %s", body, where);
  for (char *q = what; *q; q++)
    if (*q == '\n') *q = ' ';
  int ok = s == SESSILE_ERR_USAGE && !m && !strncmp(msg, want, strlen(want)) && strstr(msg, needle) &&
           !strchr(msg, '\n');
  t_true(what, ok);
  printf("    %s\n", msg);
  sessile_sds_model_destroy(m);
}

int main(void) {
  bad("rule r1: tip == 1 -> set psi = 1\n", "3:26", "unknown morphogen or state variable 'psi'");
  bad("rule r1: tip == 1 -> produce tip 1\n", "3:30", "unknown morphogen 'tip'");
  bad("rule r1: tap == 1 -> set phi = 1\n", "3:10", "unknown name 'tap'");
  bad("rule r1: tip == 1 && phi > K -> grow 1\n", "3:28", "unknown name 'K'");
  bad("rule r1: tip == 1 -> divide grad(psi)\n", "3:34", "unknown morphogen 'psi'");
  bad("rule r1: tip == 1 -> divide phi\n", "3:29", "expected grad(MORPHOGEN)");
  bad("rule r1: tip == 1 -> reset phi\n", "3:28", "unknown timer 'phi'");
  bad("rule r1: tip == 1 -> explode\n", "3:22", "unknown action 'explode'");
  bad("rule r1: tip == 1 set phi = 1\n", "3:30", "expected '->'");
  bad("rule r1 tip == 1 -> set phi = 1\n", "3:9", "expected ':'");
  bad("rule r1: tip == -> set phi = 1\n", "3:17", "bad expression");
  bad("rule r1: (tip == 1 -> set phi = 1\n", "3:20", "bad expression");
  bad("rule r1: tip == 1 -> set phi = 1 +\n", "3:35", "bad expression");
  bad("rule r1: tip == 1 ->\n", "3:21", "expected an action");
  bad("rule r1: tip == 1 -> grow\n", "3:26", "empty expression");
  bad("\n# comment\nrule r1: 1 -> grow 1\nrule r1: 1 -> grow 1\n", "6:6", "declared twice");
  bad("morphogen phi diffusion=1 decay=0\nrule r1: 1 -> grow 1\n", "3:11", "declared twice");
  bad("morphogen psi diffusion=-1 decay=0\n", "3:25", "diffusion must be >= 0");
  bad("morphogen psi decay=0\n", "3:11", "needs diffusion=");
  bad("morphogen psi diffusion=0.1 decay=0 speed=3\n", "3:37", "unknown key 'speed'");
  bad("timer clock diffusion=1 decay=0.1\n", "3:13", "unknown key 'diffusion'");
  bad("timer clock decay=0.1 axis=1\n", "3:23", "unknown key 'axis'");
  bad("morphogen psi diffusion=0.1 decay=0 axis=2\n", "3:42", "axis is 0 or 1");
  bad("morphogen psi diffusion=0.1 decay=0 axis=1\nmorphogen chi diffusion=0.1 decay=0 axis=1\n", "4:37",
      "morphogen 'psi' is the axis already");
  bad("state radius\n", "3:7", "reserved word");
  bad("const K\n", "3:8", "expected '='");
  bad("tip 1 0\n", "3:8", "expected a direction");
  bad("tip 0 0 0\n", "3:1", "the tip direction is zero");
  bad("gravity = ten\n", "3:11", "expected a number for 'gravity'");
  bad("gravity = 1\ngravity = 2\n", "4:1", "set twice");
  bad("rock = \"boulder.ply\n", "3:8", "unterminated string");
  bad("frobnicate the cells\n", "3:1", "unknown keyword 'frobnicate'");
  bad("3 = 4\n", "3:1", "expected a declaration");
  bad("", "2:1", "no rules");
  /* a NUL-free but odd text: very long line */
  char longl[1500];
  memset(longl, 'a', sizeof longl - 2);
  longl[sizeof longl - 2] = '\n', longl[sizeof longl - 1] = 0;
  bad(longl, "3:1", "line longer than");
  /* good: the quoted parameter and a timer reset parse */
  sessile_sds_model *m = NULL;
  t_true("good: quoted parameter, timer, reset, produce, several actions",
         sessile_sds_model_parse("rock = \"boulder.ply\"\nmorphogen phi diffusion=0.1 decay=0\ntimer clock decay=0.1 "
                                 "start=2\nstate tip = 1\nrule a: tip == 1 && clock < 0.5 -> reset clock; produce phi "
                                 "0.5 * volume; set tip = 0\n",
                                 "good.sds", &m) == SESSILE_OK &&
             !strcmp(sessile_sds_model_param_find(m, "rock")->text, "boulder.ply") &&
             sessile_sds_model_morph_start(m, 1) == 2 && sessile_sds_model_state_start(m, 0) == 1);
  sessile_sds_model_destroy(m);
  m = NULL;
  t_true("good: the axis morphogen (axis=1) is found, none is -1",
         sessile_sds_model_parse("morphogen phi diffusion=0.1 decay=0\nmorphogen base diffusion=0.1 decay=1 axis=1\n"
                                 "rule a: 1 -> grow 1\n", "good.sds", &m) == SESSILE_OK &&
             sessile_sds_model_axis(m) == 1);
  sessile_sds_model_destroy(m);
  m = NULL;
  t_true("good: no axis",
         sessile_sds_model_parse("morphogen phi diffusion=0.1 decay=0 axis=0\nrule a: 1 -> grow 1\n", "good.sds", &m) ==
                 SESSILE_OK &&
             sessile_sds_model_axis(m) == -1);
  sessile_sds_model_destroy(m);
  t_true("missing file: SESSILE_ERR_USAGE",
         sessile_sds_model_load("no-such-model.sds", &m) == SESSILE_ERR_USAGE && !m);
  return t_finish(NULL);
}
