/* A seabed from a user's mesh (docs/reef.md, "Seabed"): an OBJ plane over
 * [2, 12] x [5, 13] is moved to start at (0, 0) and sampled exactly; bases
 * lie on it, up axes are its normal; a mesh that does not cover its
 * bounding box, and a file that is no mesh, are refused naming
 * seabed.mesh.path. */
#include <math.h>
#include <stdio.h>
#include <unistd.h>
#include "reef_test_scene.h"

static double plane(double x, double y) { return -3 - 0.125 * x + 0.0625 * y; } /* in the file's x, y */

static void write_obj(const char *path, int both) {
  FILE *f = fopen(path, "w");
  const double v[4][2] = {{2, 5}, {12, 5}, {12, 13}, {2, 13}};
  for (int k = 0; k < 4; k++) fprintf(f, "v %g %g %.17g\n", v[k][0], v[k][1], plane(v[k][0], v[k][1]));
  fprintf(f, "f 1 2 3\n");
  if (both) fprintf(f, "f 1 3 4\n");
  fclose(f);
}

static sessile_status parse(const char *obj, sessile_reef_scene *s) {
  char json[1024];
  snprintf(json, sizeof json,
           "{\"seabed\": {\"mesh\": {\"path\": \"%s\", \"resolution\": [21, 17]}},"
           " \"pool\": [{\"name\": \"a\", \"generator\": \"g\", \"size\": [0.1, 0.2]}],"
           " \"brushes\": [{\"points\": [[5, 4]], \"size\": 4, \"density\": 300}]}", obj);
  return sessile_reef_scene_parse(json, strlen(json), "scene.json", s);
}

int main(void) {
  char dir[] = "/tmp/sessile-reef-test-XXXXXX", obj[64], bad[64];
  t_true("a temporary folder", mkdtemp(dir) != NULL);
  snprintf(obj, sizeof obj, "%s/bed.obj", dir), snprintf(bad, sizeof bad, "%s/bad.ply", dir);
  write_obj(obj, 1);
  sessile_reef_scene s;
  sessile_reef_seabed b;
  sessile_reef_placements pl;
  t_must("parse", parse(obj, &s));
  t_true("extent from the mesh", s.extent[0] == 10 && s.extent[1] == 8);
  t_must("seabed", sessile_reef_seabed_make(&s, &b));
  double herr = 0;
  for (uint32_t j = 0; j < b.ny; j++)
    for (uint32_t i = 0; i < b.nx; i++) herr = fmax(herr, fabs(b.h[j * b.nx + i] - plane(2 + i * 0.5, 5 + j * 0.5)));
  t_check("samples on the mesh (m)", herr, 1e-12);
  t_must("place", sessile_reef_place(&s, &b, 3, &pl));
  double base = 0, angle = 0, l = sqrt(0.125 * 0.125 + 0.0625 * 0.0625 + 1);
  double n[3] = {0.125 / l, -0.0625 / l, 1 / l};
  for (uint32_t k = 0; k < pl.n; k++) {
    const sessile_reef_placement *p = &pl.p[k];
    base = fmax(base, fabs(p->pos[2] - plane(p->pos[0] + 2, p->pos[1] + 5)));
    angle = fmax(angle, acos(fmin(1, p->up[0] * n[0] + p->up[1] * n[1] + p->up[2] * n[2])) * 57.29577951308232);
  }
  printf("%u placements on the mesh seabed\n", pl.n);
  t_true("placed", pl.n > 50);
  t_check("bases on the mesh (m)", base, 1e-4);
  t_check("up axis vs the mesh's normal (degrees)", angle, 1);
  sessile_reef_placements_free(&pl), sessile_reef_seabed_free(&b), sessile_reef_scene_free(&s);

  write_obj(obj, 0);
  sessile_status st = parse(obj, &s);
  t_true("half a cover is refused naming seabed.mesh.path",
         st == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "scene.json: seabed.mesh.path: is no heightfield"));
  FILE *f = fopen(bad, "w");
  fputs("ply\nformat ascii 1.0\nelement vertex 1\nend_header\nnot a number\n", f);
  fclose(f);
  st = parse(bad, &s);
  printf("%s\n", sessile_error_message());
  t_true("a file that is no mesh is refused naming seabed.mesh.path",
         st == SESSILE_ERR_USAGE && strstr(sessile_error_message(), "scene.json: seabed.mesh.path"));
  remove(obj), remove(bad), rmdir(dir);
  return t_finish(NULL);
}
