/* Embedding libsessile (docs/install.md): an icosphere from the mesh layer,
 * its invariants and statistics, written as a PLY with normals and one
 * per-vertex property by the io layer.  No Vulkan device is needed.
 *
 *   cc example.c $(pkg-config --cflags --libs sessile) -o example
 *   ./example ball.ply [LEVEL]
 */
#include <stdio.h>
#include <stdlib.h>
#include <sessile/io/io.h>
#include <sessile/mesh/surface.h>
#include <sessile/status.h>

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s OUT.ply [LEVEL 1..7]\n", argv[0]);
    return 2;
  }
  int level = argc > 2 ? atoi(argv[2]) : 4;
  const double center[3] = {0, 0, 1};
  sessile_surface s = {0};
  double *normals = NULL, *height = NULL;
  /* One error path: each call returns a status; the message says what failed. */
  sessile_status st = sessile_surface_icosphere(level, 1.0, center, &s);
  if (st == SESSILE_OK) st = sessile_surface_check(&s, 2, 0.0); /* closed, genus 0 */
  if (st == SESSILE_OK) {
    normals = malloc(sizeof *normals * 3 * s.nv);
    height = malloc(sizeof *height * s.nv);
    if (!normals || !height) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  if (st == SESSILE_OK) {
    sessile_surface_normals(&s, normals);
    for (uint32_t v = 0; v < s.nv; v++) height[v] = s.pos[3 * v + 2];
    const char *names[] = {"height"};
    const double *values[] = {height};
    st = sessile_write_ply(argv[1], &s, normals, 1, names, values);
  }
  if (st == SESSILE_OK) {
    sessile_surface_stats stats;
    sessile_surface_stats_of(&s, &stats);
    printf("vertices %u triangles %u area %.6f volume %.6f\n", stats.nv, stats.nf, stats.area, stats.volume);
  } else {
    fprintf(stderr, "example: %s: %s\n", sessile_status_name(st), sessile_error_message());
  }
  free(normals);
  free(height);
  sessile_surface_free(&s);
  return st == SESSILE_OK ? 0 : 1;
}
