/* Is the fluid mesh a structured Kuhn box (sessile_tetmesh_from_box: node
 * i + n0 (j + n1 k) at origin + h (i, j, k), 6 tets per cube in
 * sessile_box_tet's order)?  Then the block multigrid preconditioner
 * (pc "mg", sessile/la/bmg.h) can coarsen it; any other mesh (TetGen's
 * conforming one) cannot, and the linear solve falls back (ns_linear.c). */
#include <math.h>

#include "fem/ns_internal.h"
#include "sessile/mesh/box.h"

void ns_detect_box(sessile_fluid *fl) {
  fl->grid[0] = fl->grid[1] = fl->grid[2] = 0;
  const double *x = fl->x;
  if (fl->nnodes < 8) return;
  double h = x[3] - x[0];
  if (!(h > 0)) return;
  double tol = 1e-6 * h;
  uint32_t n0 = 1, n1 = 1;
  while (n0 < fl->nnodes && fabs(x[3 * n0 + 1] - x[1]) < tol && fabs(x[3 * n0 + 2] - x[2]) < tol) n0++;
  while ((uint64_t)n0 * n1 < fl->nnodes && fabs(x[3 * (size_t)n0 * n1 + 2] - x[2]) < tol) n1++;
  if (n0 < 2 || n1 < 2 || fl->nnodes % (n0 * n1)) return;
  uint32_t n2 = fl->nnodes / (n0 * n1);
  if (n2 < 2 || (uint64_t)6 * (n0 - 1) * (n1 - 1) * (n2 - 1) != fl->ntets) return;
  sessile_box b = {.origin = {x[0], x[1], x[2]}, .h = h, .n = {n0, n1, n2}};
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    double c[3] = {i % n0, (i / n0) % n1, i / (n0 * n1)};
    for (int a = 0; a < 3; a++)
      if (fabs(x[3 * (size_t)i + a] - (b.origin[a] + h * c[a])) > tol) return;
  }
  uint32_t t = 0;
  for (uint32_t k = 0; k + 1 < n2; k++)
    for (uint32_t j = 0; j + 1 < n1; j++)
      for (uint32_t i = 0; i + 1 < n0; i++)
        for (int q = 0; q < 6; q++, t++) {
          uint32_t v[4];
          sessile_box_tet(&b, i, j, k, q, v);
          for (int a = 0; a < 4; a++)
            if (fl->tet[4 * (size_t)t + a] != v[a]) return;
        }
  fl->grid[0] = n0, fl->grid[1] = n1, fl->grid[2] = n2;
}
