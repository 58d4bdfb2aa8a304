// The Kuhn decomposition of a cube into 6 tetrahedra (corner c of the cube
// at node + (c & 1, c >> 1 & 1, c >> 2)), each listed with positive
// orientation; every edge joins corners A < B with A a subset of B, so it is
// the edge of type B ^ A from node + A: the triangulation is the same from
// both cubes sharing a face.  As weld_tables.c (host).
const uint KUHN[24] = uint[24](0u, 1u, 3u, 7u,  0u, 2u, 6u, 7u,  0u, 4u, 5u, 7u,
                               0u, 1u, 7u, 5u,  0u, 2u, 7u, 3u,  0u, 4u, 7u, 6u);

// Triangles of one tet with inside-corner count n: 1 for 1 or 3, 2 for 2.
uint tet_tris(uint n) { return n == 2u ? 2u : (n & 1u); }

uint cube_triangles(uint cube) {
  uint t = 0u;
  for (uint k = 0u; k < 6u; k++) {
    uint n = 0u;
    for (uint j = 0u; j < 4u; j++) n += (cube >> KUHN[4u * k + j]) & 1u;
    t += tet_tris(n);
  }
  return t;
}

// Even permutations of a positive tet's corners (so they stay positive):
// EVEN_LONE[i] starts with corner i; with (i, j, k, l), triangle
// (p_ij, p_ik, p_il) faces away from corner i.
const uint EVEN_LONE[16] = uint[16](0u, 1u, 2u, 3u,  1u, 0u, 3u, 2u,  2u, 0u, 1u, 3u,  3u, 0u, 2u, 1u);
// EVEN_PAIR[m]: for the inside pair with corner mask m, (i, j, k, l) even
// with {i, j} inside; triangles (p_ik, p_il, p_jl), (p_ik, p_jl, p_jk) face
// from {i, j} to {k, l}.
const uint EVEN_PAIR[64] = uint[64](
  0u,0u,0u,0u, 0u,0u,0u,0u, 0u,0u,0u,0u, 0u,1u,2u,3u,   // m 0..3: {0,1} at 3
  0u,0u,0u,0u, 0u,2u,3u,1u, 1u,2u,0u,3u, 0u,0u,0u,0u,   // 5: {0,2}  6: {1,2}
  0u,0u,0u,0u, 0u,3u,1u,2u, 1u,3u,2u,0u, 0u,0u,0u,0u,   // 9: {0,3}  10: {1,3}
  2u,3u,0u,1u, 0u,0u,0u,0u, 0u,0u,0u,0u, 0u,0u,0u,0u);  // 12: {2,3}

void tet_pair_order(uint m, out uint o[4]) {
  for (uint j = 0u; j < 4u; j++) o[j] = EVEN_PAIR[4u * m + j];
}
// n == 1: the lone corner is the inside one (returns 1); n == 3: the
// outside one (returns 3); o: the even order starting with it.
uint tet_lone_order(uint m, uint n, out uint o[4]) {
  uint lone_mask = n == 1u ? m : (~m & 15u);
  uint i = findLSB(lone_mask);
  for (uint j = 0u; j < 4u; j++) o[j] = EVEN_LONE[4u * i + j];
  return n;
}
