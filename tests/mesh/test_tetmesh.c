/* The structured box as a general tet mesh: every tet positively oriented,
 * volumes summing to the box, boundary faces covering the box surface with
 * outward orientation (divergence theorem), node tags equal to the box's. */
#include <math.h>
#include <stdlib.h>
#include "sessile/mesh/tetmesh.h"
#include "testutil.h"

int main(void) {
  const double origin[3] = {1.0, -2.0, 0.5};
  const uint32_t cells[3] = {3, 4, 2};
  sessile_box box;
  t_ok("box", sessile_box_make(origin, 1.5, cells, 2, &box));
  sessile_tetmesh m = {0};
  t_ok("tetmesh_from_box", sessile_tetmesh_from_box(&box, &m));
  double mx[3];
  sessile_box_max(&box, mx);
  double vbox = (mx[0] - origin[0]) * (mx[1] - origin[1]) * (mx[2] - origin[2]);
  double vmin = INFINITY, vsum = 0;
  for (uint32_t t = 0; t < m.ntets; t++) {
    double v = sessile_tetmesh_tet_volume(&m, t);
    vsum += v;
    if (v < vmin) vmin = v;
  }
  t_true("6 tets per cube", m.ntets == 6 * sessile_box_cells(&box));
  t_check("smallest tet volume is h^3/6 (every tet positive)", fabs(vmin - box.h * box.h * box.h / 6) / vbox, 1e-14);
  t_check("tet volumes sum to the box volume (relative)", fabs(vsum - vbox) / vbox, 1e-13);
  /* Divergence theorem over the boundary faces: sum n dA = 0 and
   * sum (x . n) dA / 3 = volume, both only if the faces cover the surface
   * once and face outward. */
  double nsum[3] = {0, 0, 0}, flux = 0, area[6] = {0};
  for (uint32_t f = 0; f < m.nbfaces; f++) {
    const double *a = m.xyz + 3 * m.bface[3 * f], *b = m.xyz + 3 * m.bface[3 * f + 1],
                 *c = m.xyz + 3 * m.bface[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {(u[1] * v[2] - u[2] * v[1]) / 2, (u[2] * v[0] - u[0] * v[2]) / 2, (u[0] * v[1] - u[1] * v[0]) / 2};
    for (int k = 0; k < 3; k++) nsum[k] += n[k];
    flux += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 3;
    int tag = m.bface_tag[f];
    area[tag == 1 ? 0 : tag == 2 ? 1 : tag == 4 ? 2 : tag == 8 ? 3 : tag == 16 ? 4 : 5] += sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  t_check("boundary: sum of n dA is zero", fabs(nsum[0]) + fabs(nsum[1]) + fabs(nsum[2]), 1e-12);
  t_check("boundary: divergence theorem gives the volume", fabs(flux - vbox) / vbox, 1e-13);
  double lx = mx[0] - origin[0], ly = mx[1] - origin[1], lz = mx[2] - origin[2];
  t_check("inlet area", fabs(area[0] - ly * lz), 1e-12);
  t_check("outlet area", fabs(area[1] - ly * lz), 1e-12);
  t_check("substratum area", fabs(area[2] - lx * ly), 1e-12);
  t_check("side walls area", fabs(area[3] - 2 * lx * lz), 1e-12);
  t_check("top area", fabs(area[4] - lx * ly), 1e-12);
  t_true("every face has exactly one known tag", area[5] == 0);
  int tags_ok = 1;
  for (uint32_t k = 0; k < box.n[2]; k++)
    for (uint32_t j = 0; j < box.n[1]; j++)
      for (uint32_t i = 0; i < box.n[0]; i++)
        tags_ok &= m.node_tags[sessile_box_index(&box, i, j, k)] == sessile_box_node_tags(&box, i, j, k);
  t_true("node tags equal the box's node tags", tags_ok);
  sessile_tetmesh_free(&m);
  return t_finish(NULL);
}
