// The masked 7-point operator of host/la/stencil.c, shared by its kernels
// (stencil7*.comp).
// Node (i,j,k) of an n0 x n1 x n2 grid has index i + n0 (j + n1 k).  Every
// wall node and every node with mask != 0 is a Dirichlet node: its row and
// column are the identity (symmetric elimination), so for a free node
//   (A x)_i = h (6 x_i - sum of x over its free face neighbours)
// which is the P1 stiffness of the Kuhn box (docs/fem.md), and (A x)_i = x_i
// on Dirichlet nodes.  Push block and bindings: shaders/la/kernels.def.

bool st_wall(uint i, uint j, uint k) {
  return i == 0u || j == 0u || k == 0u || i == pc.n0 - 1u || j == pc.n1 - 1u || k == pc.n2 - 1u;
}

// Neighbour value if it is a free node, else 0.  Only called for free
// (hence interior) nodes, so every neighbour exists.
REAL st_nb(uint node, uint i, uint j, uint k) {
  return (st_wall(i, j, k) || mask[node] != 0u) ? REAL(0) : x[pc.xoff + node];
}

REAL st_apply(uint node) {
  uint i = node % pc.n0, t = node / pc.n0;
  uint j = t % pc.n1, k = t / pc.n1;
  REAL xi = x[pc.xoff + node];
  if (st_wall(i, j, k) || mask[node] != 0u) return xi;
  uint s1 = pc.n0, s2 = pc.n0 * pc.n1;
  REAL sum = st_nb(node - 1u, i - 1u, j, k) + st_nb(node + 1u, i + 1u, j, k)
           + st_nb(node - s1, i, j - 1u, k) + st_nb(node + s1, i, j + 1u, k)
           + st_nb(node - s2, i, j, k - 1u) + st_nb(node + s2, i, j, k + 1u);
  return pc.h * (REAL(6) * xi - sum);
}
