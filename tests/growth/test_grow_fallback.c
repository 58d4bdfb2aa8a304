/* The conforming domain's fallback: a self-intersecting sponge (an
 * icosphere whose top vertex is pushed down through its own bottom) is
 * rejected by TetGen; the growth loop must then solve that iteration's flow
 * on the immersed domain, say so in the manifest (and on the terminal), and
 * go on: never crash, never lose the run.  TetGen running out of memory or
 * failing internally (injected) is no rejection: the run stops with
 * SESSILE_ERR_NO_MEMORY / SESSILE_ERR_INTERNAL. */
#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/growth/grow.h"
#include "sessile/run/run.h"
#include "mesh/tetgen_plc.h"
#include "testutil.h"

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  if (b && fread(b, 1, (size_t)n, f) != (size_t)n) n = 0;
  if (b) b[n] = 0;
  fclose(f);
  return b;
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  sessile_grow_params p;
  sessile_params_default(&p);
  t_ok("diffusion_limited=false", sessile_params_set(&p, "diffusion_limited", "false"));
  t_ok("domain=conforming", sessile_params_set(&p, "domain", "conforming"));
  /* A small box and few Newton steps keep this test short: it is about the
   * fallback, not the flow's accuracy (tests/fem/test_ns.c). */
  t_ok("box_resolution=1", sessile_params_set(&p, "box_resolution", "1"));
  t_ok("box_cells_x=16", sessile_params_set(&p, "box_cells_x", "16"));
  t_ok("box_cells_y=16", sessile_params_set(&p, "box_cells_y", "16"));
  t_ok("box_cells_z=12", sessile_params_set(&p, "box_cells_z", "12"));
  t_ok("sponge_radius=3", sessile_params_set(&p, "sponge_radius", "3"));
  t_ok("fluid_newton_max_it=2", sessile_params_set(&p, "fluid_newton_max_it", "2"));

  /* A level-3 icosphere of radius 4 floating at z = 8, its top vertex pushed
   * to z = 2, through the bottom of the sphere: a closed manifold that
   * intersects itself. */
  sessile_surface s = {0};
  const double c[3] = {9.6, 9.6, 8.0};
  t_ok("icosphere", sessile_surface_icosphere(3, 4.0, c, &s));
  uint32_t top = 0;
  for (uint32_t v = 1; v < s.nv; v++)
    if (s.pos[3 * v + 2] > s.pos[3 * top + 2]) top = v;
  s.pos[3 * top + 2] = 2.0;

  char dir[] = "/tmp/sessile-fallback-XXXXXX";
  t_true("temporary folder", mkdtemp(dir) != NULL);
  sessile_grow_options o;
  sessile_grow_options_default(&o);
  sessile_run_options ro = {.dir = dir, .generator = "grow", .version = "test"};
  sessile_run *run = NULL;
  t_ok("run directory", sessile_run_open(&ro, &run));
  o.run = run;
  o.iterations = 1;
  o.every = 1;
  o.fields = 0;
  o.slices = "z";
  o.initial = &s;
  /* The loop requires a surface free of self-intersection after every
   * iteration, and contact inhibition keeps a clean one clean; this one is
   * crossed on purpose, and its crossing stays (the guard adds none). */
  o.check_every_iteration = 0;
  sessile_grow_summary sum;
  sessile_status st = sessile_grow_run(g, &p, &o, NULL, &sum);
  st = sessile_run_close(run, st);
  t_ok("the run goes on past TetGen's rejection", st);
  char path[256];
  snprintf(path, sizeof path, "%s/manifest.json", dir);
  char *text = slurp(path);
  cJSON *m = text ? cJSON_Parse(text) : NULL;
  t_true("manifest.json is written and parses", m != NULL);
  snprintf(path, sizeof path, "%s/records.jsonl", dir);
  char *rtext = slurp(path);
  cJSON *it = rtext ? cJSON_Parse(rtext) : NULL; /* one line: iteration 1's record */
  cJSON *fl = it ? cJSON_GetObjectItem(it, "fluid") : NULL;
  cJSON *fb = fl ? cJSON_GetObjectItem(fl, "fallback") : NULL;
  cJSON *dom = fl ? cJSON_GetObjectItem(fl, "domain") : NULL;
  if (fb) printf("fallback reason: %s\n", fb->valuestring);
  t_true("iteration 1 records the fallback with TetGen's reason", cJSON_IsString(fb) && strlen(fb->valuestring) > 0);
  t_true("iteration 1's flow used the immersed domain", cJSON_IsString(dom) && !strcmp(dom->valuestring, "immersed"));
  t_true("the run is complete", m && !strcmp(cJSON_GetObjectItem(m, "state")->valuestring, "completed"));
  snprintf(path, sizeof path, "%s/slices/iter_0001_z.exr", dir);
  FILE *f = fopen(path, "rb");
  t_true("the slice with the flow's channels was written", f != NULL);
  if (f) fclose(f);
  cJSON_Delete(m);
  cJSON_Delete(it);
  free(text);
  free(rtext);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) printf("note: could not remove %s\n", dir);

  /* Only a rejected geometry falls back: TetGen running out of memory
   * (std::bad_alloc) or failing internally stops the run with that status,
   * injected through tg_fault_inject (mesh/tetgen_plc.h) on the same run. */
  static const struct { int fault; sessile_status want; const char *name; } faults[] = {
      {TG_FAULT_BAD_ALLOC, SESSILE_ERR_NO_MEMORY, "TetGen out of memory (std::bad_alloc)"},
      {2, SESSILE_ERR_INTERNAL, "TetGen internal error"}};
  for (size_t k = 0; k < sizeof faults / sizeof faults[0]; k++) {
    char d2[] = "/tmp/sessile-fallback-XXXXXX";
    t_true("temporary folder", mkdtemp(d2) != NULL);
    sessile_run_options ro2 = {.dir = d2, .generator = "grow", .version = "test"};
    sessile_run *run2 = NULL;
    t_ok("run directory", sessile_run_open(&ro2, &run2));
    o.run = run2;
    tg_fault_inject = faults[k].fault;
    sessile_error_clear();
    st = sessile_grow_run(g, &p, &o, NULL, &sum);
    tg_fault_inject = 0;
    st = sessile_run_close(run2, st);
    printf("%s: %s: %s\n", faults[k].name, sessile_status_name(st), sessile_error_message());
    char what[160];
    snprintf(what, sizeof what, "%s stops the run with %s, not a fallback", faults[k].name,
             sessile_status_name(faults[k].want));
    t_true(what, st == faults[k].want);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", d2);
    if (system(cmd) != 0) printf("note: could not remove %s\n", d2);
  }
  sessile_surface_free(&s);
  return t_finish(g);
}
