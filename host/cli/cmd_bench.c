/* `sessile bench la`: device kernels and solvers against the C reference. */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "cli_reef.h"
#include "sessile/bench/bench.h"

static const char *help =
    "usage: sessile bench la|grow|fluid|coral|sponge|sds|render|reef ...   ('sessile bench NAME --help')\n"
    "       sessile bench la [--size N] [--repeat R] [--no-solvers] [--mg K] [--device D] [--precision 32|64]\n"
    "\n"
    "Times every linear-algebra kernel on the device and its plain-C reference\n"
    "(OpenMP, all cores) in the same run, and prints for each: time per call\n"
    "(GPU from timestamps, C wall clock), GFLOP/s, effective GB/s (minimum\n"
    "traffic) and the ratio C time / GPU time (> 1: the device is faster).\n"
    "  --size N      grid edge: vectors of N^3, 7-point and P1-tet matrices on N^3 (default 64)\n"
    "  --repeat R    repetitions per kernel (default 20)\n"
    "  --no-solvers  skip the solves: PCG (7-point N^3); BiCGSTAB and GMRES(30) with Jacobi\n"
    "                and with ILU(0) (conv-diff (N/2)^3 at cell Peclet 2 and 10; the Jacobi\n"
    "                variants are the in-run baseline of the ILU(0) lines), and multigrid PCG\n"
    "  --mg K        multigrid PCG against Jacobi-PCG on the cut-cell sphere problem at the first\n"
    "                K of 33x33x25, 65x65x49, 129x129x97 nodes (default 3; 0 skips)\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

int cmd_bench(int argc, char **argv, const cli_gpu_opts *global) {
  if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
    if (argc < 2) return cli_usage_error("bench", "name a benchmark: la, grow, fluid, coral, sponge, sds, render or reef");
    fputs(help, stdout);
    return EXIT_OK;
  }
  if (strcmp(argv[1], "grow") == 0) return cmd_bench_grow(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "fluid") == 0) return cmd_bench_fluid(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "coral") == 0) return cmd_bench_coral(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "sponge") == 0) return cmd_bench_sponge(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "sds") == 0) return cmd_bench_sds(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "render") == 0) return cmd_bench_render(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "reef") == 0) return cmd_bench_reef(argc - 1, argv + 1, global);
  if (strcmp(argv[1], "la") != 0)
    return cli_usage_error("bench", "unknown benchmark '%s' (available: la, grow, fluid, coral, sponge, sds, render, reef)", argv[1]);
  cli_gpu_opts o = *global;
  sessile_bench_la_options bo = {.size = 64, .repeat = 20, .solvers = 1, .mg_sizes = 3};
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i];
    if (cli_stray_value("bench la", argv, i)) return EXIT_USAGE;
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option("bench la", argc, argv, &i, &o);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (strcmp(a, "--no-solvers") && cli_once("bench la", a, a)) return EXIT_USAGE;
    if (strcmp(a, "--no-solvers") == 0) bo.solvers = 0;
    else if (strcmp(a, "--size") == 0) {
      if (cli_parse_uint("bench la", a, i + 1 < argc ? argv[++i] : NULL, 2, 400, &bo.size)) return EXIT_USAGE;
    } else if (strcmp(a, "--mg") == 0) {
      if (cli_parse_uint("bench la", a, i + 1 < argc ? argv[++i] : NULL, 0, 3, &bo.mg_sizes)) return EXIT_USAGE;
    } else if (strcmp(a, "--repeat") == 0) {
      if (cli_parse_uint("bench la", a, i + 1 < argc ? argv[++i] : NULL, 1, 10000, &bo.repeat)) return EXIT_USAGE;
    } else return cli_usage_error("bench la", "unknown option '%s'", a);
  }
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&o, &g);
  if (s == SESSILE_OK) s = sessile_bench_la(g, &bo, stdout);
  sessile_gpu_destroy(g);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
