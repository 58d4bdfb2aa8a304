/* The welded surface's benchmark (`sessile bench coral weld`, sessile/bench/bench.h):
 * a random 10 k-segment branching skeleton on a 256-cell grid (longest
 * axis), on the device by stage and by the plain-C reference in the same
 * run (docs/weld.md). */
#include <string.h>
#include "mesh/weld_internal.h"
#include "sessile/bench/bench.h"

sessile_status sessile_bench_weld(sessile_gpu *g, int quick, FILE *out) {
  uint32_t nseg = quick ? 500 : 10000, cells = quick ? 64 : 256;
  sessile_skeleton s = {0};
  sessile_surface m = {0}, r = {0};
  sessile_status st = weld_random_tree(1, nseg, 1.0, &s);
  sessile_weld_params p = {.cell = 0, .max_cells = cells, .blend = 0.3};
  weld_times tm = {0};
  double t_ref = 0;
  if (st == SESSILE_OK) {
    /* once to warm the pipelines (and the cache), then timed */
    st = weld_gpu(g, &s, &p, &m, NULL, &tm);
    if (st == SESSILE_OK) st = weld_gpu(g, &s, &p, &m, NULL, &tm);
  }
  if (st == SESSILE_OK) {
    double t0 = sessile_wall_seconds();
    st = sessile_skeleton_weld_ref(&s, &p, &r, NULL);
    t_ref = sessile_wall_seconds() - t0;
  }
  weld_grid gr;
  double bytes;
  memset(&gr, 0, sizeof gr);
  if (st == SESSILE_OK) st = weld_grid_plan(&s, &p, &gr, &bytes);
  if (st == SESSILE_OK) st = weld_grid_lists(&s, &gr); /* for the list statistics */
  if (st == SESSILE_OK) {
    double work = 0;
    uint32_t nbk = gr.nb[0] * gr.nb[1] * gr.nb[2], busy = 0;
    for (uint32_t b = 0; b < nbk; b++) {
      work += (double)(gr.boff[b + 1] - gr.boff[b]) * WELD_BRICK * WELD_BRICK * WELD_BRICK;
      busy += gr.boff[b + 1] > gr.boff[b];
    }
    int same = m.nv == r.nv && m.nf == r.nf && !memcmp(m.tri, r.tri, (size_t)m.nf * 12) &&
               !memcmp(m.pos, r.pos, (size_t)m.nv * 24);
    fprintf(out, "weld: %u segments, grid %ux%ux%u nodes (cell %.4g cm, blend %.2g cm): %u vertices, %u triangles\n",
            s.n, gr.n[0], gr.n[1], gr.n[2], gr.h, p.blend, m.nv, m.nf);
    fprintf(out, "  bricks %u (%u with capsules), about %.1f capsules per node\n", nbk, busy,
            work / (double)gr.nodes);
    fprintf(out, "  gpu %.3f s (lists+upload %.3f, sdf %.3f, count+scan %.3f, emit %.3f, download %.3f)\n", tm.total,
            tm.total - tm.sdf - tm.count - tm.emit - tm.download, tm.sdf, tm.count, tm.emit, tm.download);
    fprintf(out, "  host reference %.3f s (OpenMP); ratio %.2fx; same mesh as the reference (bytes): %s\n", t_ref,
            t_ref / tm.total, same ? "yes" : "NO");
  }
  weld_grid_free(&gr);
  sessile_surface_free(&m), sessile_surface_free(&r), sessile_skeleton_free(&s);
  return st;
}
