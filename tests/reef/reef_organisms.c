/* The reef's organisms through the CLI's callback (cli_reef_organisms.c)
 * over a registry of three generators (plus the pool's own-command ones,
 * coral lsystem and sds run): exposure thickens (the sphere's radius exactly
 * doubles at exposure 1; a venation coral's, an L-system coral's and a grown
 * sponge's volume rise), the same seed gives the same mesh, an SDS model
 * runs from its arguments, and a bad entry names its JSON path. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "cli_reef.h"
#include "sessile/coral/venation.h"
#include "sessile/growth/grow.h"
#include "sessile/sphere/sphere.h"
#include "testutil.h"

const sessile_generator *const cli_generators[] = {&sessile_gen_sphere, &sessile_gen_coral_venation,
                                                   &sessile_gen_grow, NULL};

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

/* Tubes need not be closed: their area is what thickness raises. */
static double area(const sessile_surface *s) {
  sessile_surface_stats st;
  sessile_surface_stats_of(s, &st);
  return st.area;
}

/* An entry of generator gen with its parameters (and arguments). */
static sessile_reef_entry entry(const char *gen, const char **set, int nset, const char **args, int nargs) {
  return (sessile_reef_entry){.name = "x", .generator = (char *)gen, .settings = (char **)set, .nsettings = nset,
                              .arguments = (char **)args, .narguments = nargs};
}

/* The organism's size (m: volume or area) at exposure 0 and 1 (seed 3); 0 when either fails. */
static int thickens(cli_reef_organisms *ctx, const sessile_reef_entry *e, double (*m)(const sessile_surface *),
                    double *v0, double *v1) {
  sessile_surface a = {0}, b = {0};
  sessile_reef_scalars sa = {0}, sb = {0};
  int ok = cli_reef_organism(ctx, e, 3, 0, &a, &sa) == SESSILE_OK && cli_reef_organism(ctx, e, 3, 1, &b, &sb) == SESSILE_OK;
  *v0 = ok ? m(&a) : 0, *v1 = ok ? m(&b) : 0;
  printf("%s %s %.4g -> %.4g\n", e->generator, m == area ? "area" : "volume", *v0, *v1);
  sessile_reef_scalars_free(&sa), sessile_reef_scalars_free(&sb);
  sessile_surface_free(&a), sessile_surface_free(&b);
  return ok;
}

int main(void) {
  sessile_gpu *gpu = t_gpu(64);
  cli_reef_organisms ctx = {0};
  sessile_surface a = {0}, b = {0}, c = {0};
  sessile_reef_scalars sa = {0}, sb = {0}, sc = {0};
  const char *sph[] = {"level=2", "noise=0.05", "iterations=3"};
  sessile_reef_entry es = entry("sphere", sph, 3, NULL, 0);
  t_must("sphere, exposure 0", cli_reef_organism(&ctx, &es, 7, 0, &a, &sa));
  t_must("sphere, exposure 1", cli_reef_organism(&ctx, &es, 7, 1, &b, &sb));
  t_must("sphere, exposure 0 again", cli_reef_organism(&ctx, &es, 7, 0, &c, &sc));
  t_true("a sphere's PLY has one scalar, its radius (docs/io.md), and no colours", sa.n == 1 && sb.n == 1 &&
         sc.n == 1 && !strcmp(sa.names[0], "radius"));
  sessile_reef_scalars_free(&sa), sessile_reef_scalars_free(&sb), sessile_reef_scalars_free(&sc);
  t_true("the same seed, the same mesh", a.nv == c.nv && !memcmp(a.pos, c.pos, 3 * (size_t)a.nv * sizeof *a.pos));
  t_check("exposure 1 doubles the sphere's radius", fabs(max_radius(&b) / max_radius(&a) - 2), 1e-9);
  sessile_surface_free(&a), sessile_surface_free(&b), sessile_surface_free(&c);
  const char *ven[] = {"search=host", "iterations=12"};
  sessile_reef_entry ev = entry("coral venation", ven, 2, NULL, 0);
  t_must("venation, exposure 0", cli_reef_organism(&ctx, &ev, 3, 0, &a, &sa));
  t_must("venation, exposure 1", cli_reef_organism(&ctx, &ev, 3, 1, &b, &sb));
  /* venation's PLY carries thickness_index per vertex: the organism keeps it */
  int has = sa.n == 1 && !strcmp(sa.names[0], "thickness_index") && sb.n == 1;
  for (uint32_t v = 0; has && v < a.nv; v++) has = sa.values[0][v] >= 0 && isfinite(sa.values[0][v]);
  t_true("a venation coral keeps its PLY's thickness_index, one per vertex", has);
  sessile_reef_scalars_free(&sa), sessile_reef_scalars_free(&sb), sessile_reef_scalars_free(&sc);
  printf("venation volume %.4g -> %.4g cm^3\n", volume(&a), volume(&b));
  t_true("a venation coral thickens with exposure", volume(&b) > 2 * volume(&a) && volume(&a) > 0);
  sessile_surface_free(&a), sessile_surface_free(&b);
  t_true("organisms made", ctx.made == 5);

  double v0, v1;
  const char *ls[] = {"grammar=lophelia1", "iterations=3"};
  sessile_reef_entry le = entry("coral lsystem", ls, 2, NULL, 0);
  t_true("coral lsystem (not in the registry) is a pool entry", thickens(&ctx, &le, area, &v0, &v1));
  t_true("an L-system coral thickens with exposure (thickness x 2: its tubes' area)", v1 > 1.5 * v0 && v0 > 0);
  const char *gr[] = {"box_resolution=1", "box_cells_x=16", "box_cells_y=16", "box_cells_z=12", "sponge_radius=3",
                      "fluid_at_snapshots=false", "iterations=3"};
  sessile_reef_entry ge = entry("grow", gr, 7, NULL, 0);
  ctx.gpu = gpu;
  t_true("grow is a pool entry", thickens(&ctx, &ge, volume, &v0, &v1));
  t_true("a grown sponge thickens with exposure (growth_rate and max_growth x 2)", v1 > v0 && v0 > 0);
  const char *sa_[] = {"limb", "--t-end", "5", "--frames", "1"};
  sessile_reef_entry se = entry("sds run", NULL, 0, sa_, 5);
  sessile_surface m = {0};
  sessile_reef_scalars ms = {0};
  t_must("sds run limb from its arguments", cli_reef_organism(&ctx, &se, 1, 0, &m, &ms));
  t_true("an SDS organism has a closed surface", m.nf > 0 && volume(&m) > 0);
  sessile_reef_scalars_free(&ms), sessile_surface_free(&m);
  ctx.gpu = NULL;
  t_true("sds run needs the reef's device", cli_reef_check_entry("s.json", 2, &se, 0) == SESSILE_ERR_USAGE &&
                                                strstr(sessile_error_message(), "s.json: pool[2].generator"));
  t_ok("sds run with the device", cli_reef_check_entry("s.json", 2, &se, 1));
  const char *bad_args[] = {"limb", "--nosuch"};
  se.arguments = (char **)bad_args, se.narguments = 2;
  t_true("an unknown argument names pool[2].arguments[1]",
         cli_reef_check_entry("s.json", 2, &se, 1) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[2].arguments[1]"));
  se.narguments = 0;
  t_true("sds run without a model names pool[2].arguments",
         cli_reef_check_entry("s.json", 2, &se, 1) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[2].arguments"));
  le.arguments = (char **)bad_args, le.narguments = 1;
  t_true("coral lsystem takes no arguments: pool[2].arguments[0]",
         cli_reef_check_entry("s.json", 2, &le, 1) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[2].arguments[0]"));

  char *bad_set[] = {"level=2", "nosuch=1"};
  sessile_reef_entry e = {.name = "x", .generator = "sphere", .settings = bad_set, .nsettings = 2};
  t_true("an unknown parameter names pool[3].parameters[1]",
         cli_reef_check_entry("s.json", 3, &e, 0) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[3].parameters[1]"));
  e.generator = "sponge particles";
  t_true("a generator not in the registry names pool[3].generator",
         cli_reef_check_entry("s.json", 3, &e, 0) == SESSILE_ERR_USAGE &&
             strstr(sessile_error_message(), "s.json: pool[3].generator"));
  e.generator = "sphere", e.nsettings = 1;
  t_ok("a good entry", cli_reef_check_entry("s.json", 3, &e, 0));
  return t_finish(gpu);
}
