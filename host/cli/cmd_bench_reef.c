/* `sessile bench reef`: a reef of N placements over D distinct organisms
 * (issue 31): times placement, one growth step, exposure on the device and
 * its host reference in the same run, the organisms, and the glTF write, and
 * sets reef.glb's size beside the sum of its distinct meshes written alone.
 * Figures for docs/performance.md, never pass/fail. */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "cli.h"
#include "cli_reef.h"
#include "sessile/load.h"

#define CMD "bench reef"

static const char *help =
    "usage: sessile bench reef [--placements N] [--organisms D] [--quick] [--seed S] [--device D]\n"
    "\n"
    "Builds a reef in memory from a built-in scene (a square noise seabed sized for\n"
    "N placements, D pool entries on standard brushes: every 4th a venation coral,\n"
    "the others spheres of distinct noise, so D distinct organisms; three\n"
    "currents), and prints the time of: placement (the brushes), one growth step,\n"
    "exposure on the device and by the host reference (with their ratio and\n"
    "largest difference), generating the D organisms, and writing reef.glb (to a\n"
    "temporary folder), with reef.glb's size against the sum of its distinct\n"
    "meshes (the seabed and each organism) written each alone as a .glb.  The\n"
    "placements are cut to N after growth; grown ones share their entry's mesh\n"
    "here (in `sessile reef` each is a new organism), so the reef has D organism\n"
    "meshes.  The processor and load average are printed first.\n"
    "  --placements N  placements (default 10000)\n"
    "  --organisms D   distinct organisms, pool entries (default 100)\n"
    "  --quick         500 placements of 8 organisms: a smoke run for the tests\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

/* The scene: rows of brush strokes 2 m apart over an E x E m seabed,
 * E chosen for about 0.8 N brush placements (about 1.4 per m^2 at the
 * density below, measured); growth adds the rest. */
static char *scene_json(unsigned n, unsigned d) {
  double e = fmax(6, ceil(sqrt(0.8 * n / 1.4)));
  size_t cap = 4096 + (size_t)d * 320 + (size_t)(e / 2 + 2) * 96;
  char *t = malloc(cap);
  if (!t) return NULL;
  size_t k = (size_t)snprintf(t, cap,
                              "{\"seabed\": {\"noise\": {\"seed\": 3, \"resolution\": [257, 257], \"extent\": [%g, %g],"
                              " \"height_scale\": 2, \"base\": -6, \"wavelength\": 9, \"octaves\": 4}},\n \"pool\": [",
                              e, e);
  for (unsigned i = 0; i < d; i++)
    if (i % 4 == 0)
      k += (size_t)snprintf(t + k, cap - k,
                            "%s\n  {\"name\": \"e%u\", \"generator\": \"coral venation\", \"parameters\":"
                            " [\"search=host\", \"iterations=%u\"], \"colour\": [0.9, 0.45, 0.4, 1],"
                            " \"size\": [0.15, 0.25]}", i ? "," : "", i, 10 + i % 7);
    else
      k += (size_t)snprintf(t + k, cap - k,
                            "%s\n  {\"name\": \"e%u\", \"generator\": \"sphere\", \"parameters\":"
                            " [\"level=2\", \"iterations=2\", \"noise=%.4f\"], \"colour\": [0.3, 0.5, 0.9, 1],"
                            " \"size\": [0.15, 0.25]}", i ? "," : "", i, 0.01 + 0.002 * i);
  k += (size_t)snprintf(t + k, cap - k, "],\n \"brushes\": [");
  for (double y = 1; y < e - 0.5; y += 2)
    k += (size_t)snprintf(t + k, cap - k, "%s\n  {\"points\": [[1, %g], [%g, %g]], \"size\": 1, \"density\": 1.2,"
                          " \"density_unit\": \"per_m2\"}", y > 1 ? "," : "", y, e - 1, y);
  snprintf(t + k, cap - k,
           "],\n \"currents\": [{\"origin\": [0, %g, -3], \"direction\": [1, 0, 0], \"strength\": %g, \"nutrition_range\": 3},"
           " {\"origin\": [%g, 0, -2], \"direction\": [0, 1, 0], \"strength\": %g, \"nutrition_range\": 2},"
           " {\"origin\": [%g, %g, -1], \"direction\": [-0.7071067811865476, -0.7071067811865476, 0], \"strength\": %g,"
           " \"nutrition_range\": 4}],\n \"growth\": {\"steps\": 1, \"spacing\": 0.6}}\n",
           e / 2, e, e / 2, e, e, e, 1.5 * e);
  return t;
}

static long long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long long)st.st_size : -1;
}

/* reef.glb, then each distinct mesh alone (one node, its material) */
static sessile_status write_glb(const sessile_reef_gltf *g, const char *dir, double *seconds, long long *size,
                                long long *alone, long long *seabed) {
  char path[4200];
  snprintf(path, sizeof path, "%s/reef.glb", dir);
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_gltf_write(path, &g->scene));
  *seconds = sessile_wall_seconds() - t0, *size = file_size(path), *alone = 0;
  snprintf(path, sizeof path, "%s/alone.glb", dir);
  for (uint32_t m = 0; m < g->scene.nmeshes; m++) {
    sessile_gltf_mesh one = g->meshes[m];
    one.material = 0;
    sessile_gltf_scene s = {.meshes = &one, .nmeshes = 1, .materials = &g->materials[g->meshes[m].material],
                            .nmaterials = 1, .metres_per_unit = g->scene.metres_per_unit,
                            .generator = g->scene.generator};
    SESSILE_CALL(sessile_gltf_write(path, &s));
    *alone += file_size(path);
    if (m == 0) *seabed = file_size(path);
  }
  return SESSILE_OK;
}

static sessile_status bench(sessile_gpu *gpu, unsigned n, unsigned d, uint64_t seed, const char *dir) {
  char *text = scene_json(n, d);
  SESSILE_CHECK(text, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_reef_scene s;
  sessile_status st = sessile_reef_scene_parse(text, strlen(text), "bench scene", &s);
  free(text);
  SESSILE_CALL(st);
  sessile_reef_seabed b = {0};
  sessile_reef_placements pl = {0};
  sessile_reef_gltf g = {0};
  double t[6] = {0}, t0;
  uint32_t placed = 0, added = 0;
  long long size = 0, alone = 0, seabed = 0;
  st = sessile_reef_seabed_make(&s, &b);
  if (st == SESSILE_OK) {
    t0 = sessile_wall_seconds();
    st = sessile_reef_place(&s, &b, seed, &pl);
    t[0] = sessile_wall_seconds() - t0, placed = pl.n;
  }
  if (st == SESSILE_OK) {
    t0 = sessile_wall_seconds();
    st = sessile_reef_grow_step(&s, &b, 1, &pl, &added);
    t[1] = sessile_wall_seconds() - t0;
  }
  double diff = 0;
  if (st == SESSILE_OK) {
    if (pl.n > n) pl.n = n;
    for (uint32_t k = 0; k < pl.n; k++) pl.p[k].automatic = 0; /* one mesh per entry (see the help) */
    t0 = sessile_wall_seconds();
    sessile_reef_exposure_ref(&s, &b, &pl, 0);
    t[2] = sessile_wall_seconds() - t0;
    double *ref = malloc(((size_t)pl.n + 1) * sizeof *ref);
    st = ref ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    for (uint32_t k = 0; ref && k < pl.n; k++) ref[k] = pl.p[k].exposure;
    t0 = sessile_wall_seconds();
    if (st == SESSILE_OK) st = sessile_reef_exposure_gpu(gpu, &s, &b, &pl, 0);
    t[3] = sessile_wall_seconds() - t0;
    for (uint32_t k = 0; st == SESSILE_OK && k < pl.n; k++) diff = fmax(diff, fabs(ref[k] - pl.p[k].exposure));
    free(ref);
  }
  cli_reef_organisms org = {.gpu = gpu, .where = "bench scene"};
  if (st == SESSILE_OK) {
    t0 = sessile_wall_seconds();
    st = sessile_reef_gltf_make(&s, &b, &pl, cli_reef_organism, &org, &g);
    t[4] = sessile_wall_seconds() - t0;
    g.scene.generator = "sessile (bench reef)";
  }
  if (st == SESSILE_OK) st = write_glb(&g, dir, &t[5], &size, &alone, &seabed);
  if (st == SESSILE_OK) {
    printf("scene: seabed %.0f x %.0f m (%u x %u samples), %d entries, %d strokes, %d currents\n", s.extent[0],
           s.extent[1], b.nx, b.ny, s.nentries, s.nstrokes, s.ncurrents);
    printf("placements %u (brushes %u, growth step +%u, cut to %u); organism meshes %u\n", pl.n, placed, added, n,
           g.scene.nmeshes - 1);
    printf("%-22s %10s\n", "stage", "ms");
    printf("%-22s %10.2f\n", "placement (brushes)", 1e3 * t[0]);
    printf("%-22s %10.2f\n", "growth (one step)", 1e3 * t[1]);
    printf("%-22s %10.2f\n", "exposure host ref", 1e3 * t[2]);
    printf("%-22s %10.2f\n", "exposure device", 1e3 * t[3]);
    printf("%-22s %10.2f\n", "organisms (generate)", 1e3 * t[4]);
    printf("%-22s %10.2f\n", "glTF write", 1e3 * t[5]);
    printf("exposure: host ref / device %.3f; largest difference %.2e\n", t[3] > 0 ? t[2] / t[3] : 0, diff);
    printf("reef.glb %lld bytes; its %u distinct meshes written alone %lld bytes; ratio %.3f\n", size,
           g.scene.nmeshes, alone, alone > 0 ? (double)size / alone : 0);
    /* the seabed's share taken out of both: what instancing the organisms costs */
    printf("without the seabed (%lld bytes alone): %lld / %lld bytes; ratio %.3f\n", seabed, size - seabed,
           alone - seabed, alone > seabed ? (double)(size - seabed) / (alone - seabed) : 0);
  }
  sessile_reef_gltf_free(&g);
  sessile_reef_placements_free(&pl);
  sessile_reef_seabed_free(&b);
  sessile_reef_scene_free(&s);
  return st;
}

int cmd_bench_reef(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  unsigned n = 10000, d = 100, seed = 1;
  int quick = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (cli_stray_value(CMD, argv, i)) return EXIT_USAGE;
    int r = cli_gpu_option(CMD, argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (cli_once(CMD, a, a)) return EXIT_USAGE;
    if (!strcmp(a, "--quick")) {
      quick = 1;
      continue;
    }
    unsigned *to = !strcmp(a, "--placements") ? &n : !strcmp(a, "--organisms") ? &d : !strcmp(a, "--seed") ? &seed : NULL;
    if (!to) return cli_usage_error(CMD, "unknown option '%.60s'", a);
    const char *v = cli_value(CMD, argc, argv, &i);
    if (!v || cli_parse_uint(CMD, a, v, to == &seed ? 0 : 1, to == &n ? 200000 : to == &d ? 1000 : 100000000, to))
      return EXIT_USAGE;
  }
  if (quick) n = 500, d = 8;
  const char *tmp = getenv("TMPDIR");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/sessile-bench-reef-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  if (!mkdtemp(dir)) return cli_fail(sessile_error_set(SESSILE_ERR_IO, "cannot make a temporary folder"));
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&go, &g);
  if (s == SESSILE_OK) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(g);
    char cpu[256];
    printf("machine: %s\n", sessile_cpu_describe(cpu, sizeof cpu));
    double load[3];
    sessile_load_average(load);
    printf("sessile bench reef: device %s (%s), driver %s, fp%d; load average %.2f %.2f %.2f\n", gi->name, gi->type,
           gi->driver, gi->precision, load[0], load[1], load[2]);
    printf("%u placements, %u distinct organisms, seed %u\n", n, d, seed);
    fflush(stdout);
    s = bench(g, n, d, seed, dir);
  }
  sessile_gpu_destroy(g);
  cli_reef_remove_tree(dir);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
