/* Parameter tables (sessile/run/param_table.h) on a small table of every kind:
 * defaults, text and JSON parsing (strict: duplicates, trailing bytes, NUL,
 * kinds, integers, open bounds), the cross-parameter hook, printing to a
 * failing stream, and the config round trip that a resume relies on (exact
 * to the last bit), a stored config made before a parameter existed taking
 * the table's `before` value for it (and its own when it has it).  Also: the grow table's defaults are the kernels'
 * defaults (one source), and an error message may quote the previous one. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/growth/growth_ref.h"
#include "sessile/run/param_table.h"
#include "sessile/run/run.h"
#include "sessile/growth/grow_params.h"
#include "testutil.h"

typedef struct demo {
  double x;
  int n, flag, kind;
} demo;
static const char *const kinds[] = {"alpha", "beta", NULL};
static sessile_status demo_validate(const void *v) {
  const demo *d = v;
  SESSILE_CHECK(d->n <= 10 * d->x, SESSILE_ERR_USAGE, "n (%d) must be at most 10 x (%g)", d->n, d->x);
  return SESSILE_OK;
}
static const sessile_param_desc descs[] = {
    {"x", SESSILE_PT_REAL, offsetof(demo, x), 1.5, 0, 100, SESSILE_PARAM_LO_OPEN, "cm", "ours", "a length", NULL},
    {"n", SESSILE_PT_INT, offsetof(demo, n), 3, -5, 50, 0, "", "ours", "a count", NULL},
    {"flag", SESSILE_PT_BOOL, offsetof(demo, flag), 1, 0, 1, 0, "", "ours", "a switch", NULL},
    {"kind", SESSILE_PT_ENUM, offsetof(demo, kind), 1, 0, 1, 0, "", "ours", "a choice", kinds},
};
/* "length" is x's earlier name (sessile_param_alias): still read everywhere. */
static const sessile_param_alias aliases[] = {{"length", "x"}, {NULL, NULL}};
/* "kind" came later, with a default (beta) the code before it did not
 * behave as: a stored config without it resumes with alpha. */
static const sessile_param_before kind_before[] = {{"kind", "alpha"}, {NULL, NULL}};
static const sessile_param_table table = {"demo", sizeof(demo), 4, descs, demo_validate, aliases, kind_before};

/* JSON text refused with a message holding `part`, values left as they were
 * up to the failing key. */
static void json_refused(const char *what, const char *text, size_t len, const char *part) {
  demo d;
  sessile_params_defaults(&table, &d);
  sessile_status s = sessile_params_apply_json_text(&table, &d, text, len, "t.json");
  int ok = s == SESSILE_ERR_USAGE && strstr(sessile_error_message(), part) != NULL &&
           strchr(sessile_error_message(), '\n') == NULL;
  if (!ok) printf("  got status %d, message '%s'\n", (int)s, sessile_error_message());
  t_true(what, ok);
}

static void text_refused(const char *what, const char *key, const char *value) {
  demo d;
  sessile_params_defaults(&table, &d);
  demo before = d;
  sessile_status s = sessile_params_set_text(&table, &d, key, value);
  t_true(what, s == SESSILE_ERR_USAGE && !memcmp(&d, &before, sizeof d));
}

int main(void) {
  demo d;
  sessile_params_defaults(&table, &d);
  t_true("defaults from the table", d.x == 1.5 && d.n == 3 && d.flag == 1 && d.kind == 1);
  t_ok("the defaults pass the checks", sessile_params_check(&table, &d));

  t_ok("--set x=2.25", sessile_params_set_kv(&table, &d, "x=2.25"));
  t_ok("--set n=-5 (closed lower end)", sessile_params_set_text(&table, &d, "n", "-5"));
  t_ok("--set flag=no", sessile_params_set_text(&table, &d, "flag", "no"));
  t_ok("--set kind=ALPHA (names ignore case)", sessile_params_set_text(&table, &d, "kind", "ALPHA"));
  t_true("text values stored", d.x == 2.25 && d.n == -5 && d.flag == 0 && d.kind == 0);
  text_refused("x=0 is refused: an open lower end", "x", "0");
  text_refused("x=100.0000001 is refused", "x", "100.0000001");
  text_refused("n=2.5 is not an integer", "n", "2.5");
  text_refused("n=0x10: no hexadecimal", "n", "0x10");
  text_refused("x=0x1p3: no hexadecimal float", "x", "0x1p3");
  text_refused("x=inf", "x", "inf");
  text_refused("x=nan", "x", "nan");
  text_refused("x=' 1' (blank)", "x", " 1");
  text_refused("x=1e999 (overflow)", "x", "1e999");
  text_refused("n=99999999999999999999", "n", "99999999999999999999");
  text_refused("flag=maybe", "flag", "maybe");
  text_refused("kind=gamma", "kind", "gamma");
  text_refused("unknown key", "nope", "1");
  text_refused("empty value", "x", "");
  t_true("--set without '=' is refused", sessile_params_set_kv(&table, &d, "x") == SESSILE_ERR_USAGE);
  t_true("--set '=1' is refused", sessile_params_set_kv(&table, &d, "=1") == SESSILE_ERR_USAGE);

  const char good[] = "{\"x\": 4, \"n\": 7, \"flag\": false, \"kind\": \"beta\"}\n";
  sessile_params_defaults(&table, &d);
  t_ok("a JSON object applies", sessile_params_apply_json_text(&table, &d, good, strlen(good), "t.json"));
  t_true("JSON values stored", d.x == 4 && d.n == 7 && d.flag == 0 && d.kind == 1);
  json_refused("duplicate keys", "{\"x\": 1, \"x\": 2}", 16, "given twice");
  json_refused("a name and its earlier name together", "{\"x\": 1, \"length\": 2}", 21, "also as 'length'");
  json_refused("an earlier name and the name together", "{\"length\": 2, \"x\": 1}", 21, "'x' is given twice");
  sessile_params_defaults(&table, &d);
  t_ok("an earlier name in JSON applies", sessile_params_apply_json_text(&table, &d, "{\"length\": 7}", 13, "t.json"));
  t_true("... to the parameter it names now", d.x == 7);
  t_ok("an earlier name with --set", sessile_params_set_kv(&table, &d, "length=9"));
  t_true("... sets the parameter it names now", d.x == 9);
  t_true("find resolves an alias to the new descriptor", sessile_params_find(&table, "length") == &descs[0]);
  t_true("an alias of a name not in the table is no parameter", sessile_params_find(&table, "kindness") == NULL);
  /* the grow table's earlier names (docs/fluid.md) each name a parameter that
   * exists, and none is itself a parameter's name */
  int nalias = 0, alias_ok = 1;
  for (const sessile_param_alias *a = sessile_grow_param_table.aliases; a && a->old_name; a++, nalias++) {
    const sessile_param_desc *pd = sessile_params_find(&sessile_grow_param_table, a->old_name);
    alias_ok &= pd && !strcmp(pd->name, a->name) && strcmp(a->old_name, a->name) != 0;
    for (int i = 0; i < sessile_grow_param_table.count; i++)
      alias_ok &= strcmp(sessile_grow_param_table.params[i].name, a->old_name) != 0;
  }
  t_true("the grow table's aliases resolve to its parameters", nalias == 5 && alias_ok);
  json_refused("bytes after the value", "{\"x\": 1} x", 10, "not valid JSON");
  json_refused("two objects", "{}{}", 4, "not valid JSON");
  json_refused("a NUL byte inside", "{\"x\": 1}\0 ", 10, "NUL byte");
  json_refused("an array, not an object", "[1]", 3, "one JSON object");
  json_refused("a number given as a string", "{\"x\": \"1\"}", 10, "must be a number");
  json_refused("a bool given as 1", "{\"flag\": 1}", 11, "true or false");
  json_refused("an enum given as a number", "{\"kind\": 0}", 11, "must be a string");
  json_refused("a non-integer for an integer", "{\"n\": 2.5}", 10, "not an integer");
  json_refused("an integer past int's range", "{\"n\": 1e300}", 12, "not an integer");
  json_refused("an unknown key", "{\"nope\": 1}", 11, "unknown parameter 'nope'");
  json_refused("malformed JSON names line and column", "{\n \"x\": ,}", 10, "t.json:2:");
  json_refused("an empty text", "", 0, "not valid JSON");
  json_refused("the cross-parameter hook runs in check, not here: a bad enum name", "{\"kind\": \"zeta\"}", 16,
               "not one of alpha, beta");
  sessile_params_defaults(&table, &d);
  d.n = 40; /* > 10 x = 15 */
  t_true("the table's validate hook runs", sessile_params_check(&table, &d) == SESSILE_ERR_USAGE &&
                                               strstr(sessile_error_message(), "at most 10 x"));

  /* The config round trip: every bit of a real value comes back. */
  sessile_params_defaults(&table, &d);
  d.x = 0.1 + 0.2; /* 0.30000000000000004 */
  cJSON *cfg = sessile_params_to_config(&table, &d);
  char *text = cJSON_PrintUnformatted(cfg);
  demo back;
  sessile_params_defaults(&table, &back);
  back.x = 9;
  t_ok("the config reads back", sessile_params_apply_json_text(&table, &back, text, strlen(text), "cfg"));
  t_true("the config round trip is exact", !memcmp(&back, &d, sizeof d));
  free(text);
  cJSON_Delete(cfg);

  /* A stored run configuration made before "kind" existed resumes with the
   * old behaviour (alpha), one that has it with its own; the grow table's
   * fluid_newton_forcing is fixed for runs made before it. */
  const char *old_cfg = "{\"seed\": \"3\", \"iterations\": 5, \"every\": 1, \"parameters\": {\"x\": 2}}";
  const char *new_cfg = "{\"seed\": \"3\", \"iterations\": 5, \"every\": 1, \"parameters\": {\"kind\": \"beta\"}}";
  uint64_t seed;
  int its, every;
  cJSON *oc = cJSON_Parse(old_cfg), *nc = cJSON_Parse(new_cfg);
  t_ok("a stored config without kind", sessile_run_config_take(oc, &table, &d, &seed, &its, &every));
  t_true("... resumes with the before value (alpha), its x kept", d.kind == 0 && d.x == 2 && seed == 3 && its == 5);
  t_ok("a stored config with kind", sessile_run_config_take(nc, &table, &d, &seed, &its, &every));
  t_true("... keeps its own (beta)", d.kind == 1 && d.x == 1.5);
  sessile_params_defaults(&table, &d);
  t_true("a new run's default is beta", d.kind == 1);
  cJSON *gc = cJSON_Parse("{\"seed\": \"1\", \"iterations\": 5, \"every\": 1, \"parameters\": {\"growth_rate\": 0.5}}");
  sessile_grow_params gold;
  memset(&gold, 0xff, sizeof gold);
  t_ok("a grow config from before fluid_newton_forcing",
       sessile_run_config_take(gc, &sessile_grow_param_table, &gold, &seed, &its, &every));
  t_true("... resumes with the fixed forcing and no nested start",
         gold.fluid_newton_forcing == 0 && gold.fluid_nested == 0 && gold.growth_rate == 0.5);
  sessile_params_default(&gold);
  t_true("... where a new grow run's are ew and nested", gold.fluid_newton_forcing == 1 && gold.fluid_nested == 1);
  cJSON_Delete(gc);
  cJSON_Delete(oc);
  cJSON_Delete(nc);

  /* Printing reports a failing stream (`--print-config > /dev/full`). */
  FILE *full = fopen("/dev/full", "w");
  if (full) {
    t_true("printing to /dev/full is an I/O error", sessile_params_print(&table, &d, full) == SESSILE_ERR_IO);
    fclose(full);
  }

  /* One source: the kernels' defaults are the grow table's. */
  sessile_grow_params gp;
  sessile_params_default(&gp);
  sessile_growth_params kp;
  sessile_growth_params_default(&kp);
  t_true("kernel defaults = table defaults (l_max, max_growth, thresholds)",
         kp.l_max == gp.l_max && kp.max_growth == gp.max_growth && kp.nutrient_threshold == gp.nutrient_threshold &&
             kp.growth_rate == gp.growth_rate && kp.probe_offset == gp.concentration_offset_distance);
  t_true("kinetic_order=0 is refused by the grow table (n > 0)", sessile_params_set(&gp, "kinetic_order", "0") == SESSILE_ERR_USAGE);
  t_true("growth_constant=0 is refused (K > 0)", sessile_params_set(&gp, "growth_constant", "0") == SESSILE_ERR_USAGE);
  sessile_params_default(&gp);
  gp.sponge_radius = 19; /* the 38.4 cm box minus the wall margin cannot hold it */
  t_true("a sponge without its wall margin is refused", sessile_params_validate(&gp) == SESSILE_ERR_USAGE);
  sessile_params_default(&gp);
  gp.box_resolution = 6, gp.box_cells_x = gp.box_cells_y = gp.box_cells_z = 4096;
  t_true("a box past 32-bit indices is refused", sessile_params_validate(&gp) == SESSILE_ERR_USAGE &&
                                                  strstr(sessile_error_message(), "nodes"));

  /* A message may quote the previous one (it printed "...: tory" once). */
  sessile_error_set(SESSILE_ERR_IO, "cannot write 'directory/file'");
  sessile_error_set(SESSILE_ERR_IO, "iteration 3: %s", sessile_error_message());
  t_true("an error message can quote the last one",
         !strcmp(sessile_error_message(), "iteration 3: cannot write 'directory/file'"));
  return t_finish(NULL);
}
