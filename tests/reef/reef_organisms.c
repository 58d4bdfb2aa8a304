/* The reef's organisms through the CLI's callback (cli_reef_organisms.c)
 * over a registry of two generators: exposure thickens (the sphere's radius
 * exactly doubles at exposure 1; a venation coral's volume rises), the same
 * seed gives the same mesh, and a bad entry names its JSON path. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "cli_reef.h"
#include "sessile/coral/venation.h"
#include "sessile/sphere/sphere.h"
#include "testutil.h"

const sessile_generator *const cli_generators[] = {&sessile_gen_sphere, &sessile_gen_coral_venation, NULL};

static double max_radius(const sessile_surface *s) {
  double r = 0;
  for (uint32_t v = 0; v < s->nv; v++) r = fmax(r, sqrt(s->pos[3 * v] * s->pos[3 * v] + s->pos[3 * v + 1] * s->pos[3 * v + 1] +
                                                         s->pos[3 * v + 2] * s->pos[3 * v + 2]));
  return r;
}

static double volume(const sessile_surface *s) {
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  return st.volume;
}

int main(void) {
  cli_reef_organisms ctx = {0};
  sessile_surface a = {0}, b = {0}, c = {0};
  sessile_reef_scalars sa = {0}, sb = {0}, sc = {0};
  const char *sph[] = {"level=2", "noise=0.05", "iterations=3"};
  t_must("sphere, exposure 0", cli_reef_organism(&ctx, "sphere", sph, 3, 7, 0, &a, &sa));
  t_must("sphere, exposure 1", cli_reef_organism(&ctx, "sphere", sph, 3, 7, 1, &b, &sb));
  t_must("sphere, exposure 0 again", cli_reef_organism(&ctx, "sphere", sph, 3, 7, 0, &c, &sc));
  t_true("a sphere's PLY has no scalars", sa.n == 0 && sb.n == 0 && sc.n == 0);
  sessile_reef_scalars_free(&sa), sessile_reef_scalars_free(&sb), sessile_reef_scalars_free(&sc);
  t_true("the same seed, the same mesh", a.nv == c.nv && !memcmp(a.pos, c.pos, 3 * (size_t)a.nv * sizeof *a.pos));
  t_check("exposure 1 doubles the sphere's radius", fabs(max_radius(&b) / max_radius(&a) - 2), 1e-9);
  sessile_surface_free(&a), sessile_surface_free(&b), sessile_surface_free(&c);
  const char *ven[] = {"search=host", "iterations=12"};
  t_must("venation, exposure 0", cli_reef_organism(&ctx, "coral venation", ven, 2, 3, 0, &a, &sa));
  t_must("venation, exposure 1", cli_reef_organism(&ctx, "coral venation", ven, 2, 3, 1, &b, &sb));
  /* venation's PLY carries thickness_index per vertex: the organism keeps it */
  int has = sa.n == 1 && !strcmp(sa.names[0], "thickness_index") && sb.n == 1;
  for (uint32_t v = 0; has && v < a.nv; v++) has = sa.values[0][v] >= 0 && isfinite(sa.values[0][v]);
  t_true("a venation coral keeps its PLY's thickness_index, one per vertex", has);
  sessile_reef_scalars_free(&sa), sessile_reef_scalars_free(&sb), sessile_reef_scalars_free(&sc);
  printf("venation volume %.4g -> %.4g cm^3\n", volume(&a), volume(&b));
  t_true("a venation coral thickens with exposure", volume(&b) > 2 * volume(&a) && volume(&a) > 0);
  sessile_surface_free(&a), sessile_surface_free(&b);
  t_true("organisms made", ctx.made == 5);

  char *bad_set[] = {"level=2", "nosuch=1"};
  sessile_reef_entry e = {.name = "x", .generator = "sphere", .settings = bad_set, .nsettings = 2};
  t_true("an unknown parameter names pool[3].parameters[1]",
         cli_reef_check_entry("s.json", 3, &e) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[3].parameters[1]"));
  e.generator = "sponge particles";
  t_true("a generator not in the registry names pool[3].generator",
         cli_reef_check_entry("s.json", 3, &e) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[3].generator"));
  e.generator = "sphere", e.nsettings = 1;
  t_ok("a good entry", cli_reef_check_entry("s.json", 3, &e));
  return t_finish(NULL);
}
