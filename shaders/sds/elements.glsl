// The element forces of a step in one dispatch: invocations 0 .. T-1 the
// tets (tet_force.glsl), T .. T+E-1 the edges (edge_force.glsl).  They write
// disjoint slots of elf and read nothing another writes, so one dispatch
// gives the bytes of two; on lavapipe a dispatch costs about 0.1 ms of
// thread wake-ups whatever its size, a tenth of a step at 200 cells
// (docs/sds.md, "Benchmark").
#include "tet_force.glsl"
#include "edge_force.glsl"

void main() {
  uint i = sessile_gid();
  if (i < pc.ntets) tet_force(i);
  else if (i - pc.ntets < pc.nedges) edge_force(i - pc.ntets);
}
