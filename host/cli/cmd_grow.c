/* `sessile grow`: the accretive sponge on the paper's defaults, with presets,
 * JSON configs and --set overrides. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/grow.h"

static const char *help =
    "usage: sessile grow [--preset radiate|crella] [--config FILE.json] [--set KEY=VALUE]...\n"
    "                    [--seed N] [--iterations N] [--out DIR] [--every K] [--slices SPEC]\n"
    "                    [--no-fields] [--quiet] [--print-config] [--device D] [--validation]\n"
    "\n"
    "Grows a sponge by O'Hagan et al.'s accretive model: per iteration the box nodes\n"
    "inside the sponge become solid, the nutrient field is solved (diffusion limited:\n"
    "a Laplace problem), probed along each vertex normal, translocated over the\n"
    "surface, and each vertex grows by the Chindapol function; then the surface is\n"
    "remeshed.  Lengths are in cm; docs/model.md has every equation and parameter.\n"
    "The ocean current (stationary Navier-Stokes, docs/fluid.md) is solved at each\n"
    "snapshot for the velocity and pressure outputs (fluid_at_snapshots); with\n"
    "--set diffusion_limited=false it is solved every iteration and advects the\n"
    "nutrient (--set domain=conforming meshes the water around the sponge with\n"
    "TetGen; fluid_resolution=2 doubles the flow's resolution at ~10x the time).\n"
    "\n"
    "  --preset P        radiate: Table 1 as is (radiate accretive growth, default);\n"
    "                    crella: Halichondrid normals + randomised x/y position (§4.7)\n"
    "  --config FILE     JSON object of parameter overrides {\"t_give\": 0.1, ...}\n"
    "  --set KEY=VALUE   override one parameter (repeatable; applied after --config)\n"
    "  --print-config    list every parameter (value, unit, paper source) and exit\n"
    "  --seed N          seed of every random choice (default 1): same seed, same\n"
    "                    device, same bytes out\n"
    "  --iterations N    growth iterations (default 50)\n"
    "  --out DIR         run directory (default runs/<preset>); files there with the\n"
    "                    same names are replaced\n"
    "  --every K         snapshot every K iterations: sponge/iter_NNNN.ply,\n"
    "                    slices/iter_NNNN_<plane>.exr, fields/iter_NNNN.vtu (default 10;\n"
    "                    0: final mesh only)\n"
    "  --slices SPEC     EXR slice planes: 'x,y,z' through the sponge centre (default),\n"
    "                    'z=3.5,y=19.2' at given heights in cm, or '' for none\n"
    "  --no-fields       no VTU volume fields\n"
    "  --quiet           no progress output\n"
    "\n"
    "The run directory holds manifest.json (parameters, seed, device, per-iteration\n"
    "timings, solver iterations and true residuals, mesh statistics; rewritten after\n"
    "every iteration), sponge/final.ply and final.obj, and the snapshots above\n"
    "(fields/series.pvd opens the VTU series in ParaView).  Every file is written\n"
    "atomically.  Exit codes: 0 success, 1 runtime failure, 2 bad usage or input.\n";

int cmd_grow(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  sessile_grow_options o;
  sessile_grow_options_default(&o);
  const char *preset = "radiate", *config = NULL, *out = NULL;
  int print_config = 0;
  /* --set values are applied in order after the preset and the config. */
  const char **sets = calloc((size_t)argc + 1, sizeof *sets);
  if (!sets) return cli_usage_error("grow", "out of memory");
  int nsets = 0, rc = -1;
  for (int i = 1; i < argc && rc < 0; i++) {
    const char *a = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    unsigned u = 0;
    int r = cli_gpu_option("grow", argc, argv, &i, &go);
    if (r < 0) rc = EXIT_USAGE;
    else if (r > 0) continue;
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(help, stdout);
      rc = EXIT_OK;
    } else if (!strcmp(a, "--print-config")) print_config = 1;
    else if (!strcmp(a, "--quiet")) o.quiet = 1;
    else if (!strcmp(a, "--no-fields")) o.fields = 0;
    else if (!v) rc = cli_usage_error("grow", "%s needs a value", a);
    else if (!strcmp(a, "--preset")) preset = argv[++i];
    else if (!strcmp(a, "--config")) config = argv[++i];
    else if (!strcmp(a, "--out")) out = argv[++i];
    else if (!strcmp(a, "--slices")) o.slices = argv[++i];
    else if (!strcmp(a, "--set")) sets[nsets++] = argv[++i];
    else if (!strcmp(a, "--iterations")) {
      if (cli_parse_uint("grow", a, argv[++i], 0, 100000, &u)) rc = EXIT_USAGE;
      o.iterations = (int)u;
    } else if (!strcmp(a, "--every")) {
      if (cli_parse_uint("grow", a, argv[++i], 0, 100000, &u)) rc = EXIT_USAGE;
      o.every = (int)u;
    } else if (!strcmp(a, "--seed")) {
      char *end = NULL;
      const char *sv = argv[++i];
      unsigned long long seed = strtoull(sv, &end, 10);
      if (!*sv || *end || sv[0] == '-') rc = cli_usage_error("grow", "--seed: '%s' is not a non-negative integer", sv);
      o.seed = seed;
    } else rc = cli_usage_error("grow", "unknown option '%s'", a);
  }
  if (rc >= 0) {
    free(sets);
    return rc;
  }
  sessile_params p;
  sessile_status s = sessile_params_preset(&p, preset);
  if (s == SESSILE_OK && config) s = sessile_params_load_json(&p, config);
  for (int k = 0; s == SESSILE_OK && k < nsets; k++) s = cli_params_set_kv(&p, sets[k]);
  free(sets);
  if (s == SESSILE_OK) s = sessile_params_validate(&p);
  if (s != SESSILE_OK) return cli_fail(s);
  if (print_config) {
    sessile_params_print(&p, stdout);
    return EXIT_OK;
  }
  char outbuf[512];
  if (!out) {
    snprintf(outbuf, sizeof outbuf, "runs/%s", preset);
    out = outbuf;
  }
  o.out_dir = out;
  o.preset = preset;
  sessile_gpu *g = NULL;
  s = cli_gpu_create(&go, &g);
  sessile_grow_summary sum;
  if (s == SESSILE_OK) s = sessile_grow_run(g, &p, &o, NULL, &sum);
  sessile_gpu_destroy(g);
  if (s != SESSILE_OK) {
    if (!o.quiet) fputc('\n', stderr);
    return cli_fail(s);
  }
  if (!o.quiet)
    printf("grew %d iterations in %.1f s: %u vertices, %u triangles; box %u nodes; run in %s\n",
           sum.iterations, sum.total_seconds, sum.final_vertices, sum.final_triangles, sum.box_nodes,
           out);
  return EXIT_OK;
}
