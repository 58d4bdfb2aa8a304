// One tetrahedron per invocation: flag[t] = 1 when its signed volume (eq 1)
// is <= 0 or not finite (§3.1.2: an inverted tetrahedron), else 0.
#include "sds_common.glsl"
#include "sds_load.glsl"

// Tet t (every t: nothing past ntets or once a batch stopped).
void inverted_at(uint t) {
  if (t >= pc.ntets || (pc.batch != 0u && ev[0] != 0u)) return; // a batch that stopped
  uint q0 = LD_TOPO(4u * t), q1 = LD_TOPO(4u * t + 1u), q2 = LD_TOPO(4u * t + 2u), q3 = LD_TOPO(4u * t + 3u);
  REAL a[3], b[3], c[3];
  for (int i = 0; i < 3; i++) {
    a[i] = LD_X(3u * q1 + i) - LD_X(3u * q0 + i);
    b[i] = LD_X(3u * q2 + i) - LD_X(3u * q0 + i);
    c[i] = LD_X(3u * q3 + i) - LD_X(3u * q0 + i);
  }
  uint inv = tet_inverted(a, b, c);
  flag[t] = inv;
  if (pc.batch != 0u && inv != 0u) { // counted and listed: the check stops the batch on it unless it is a lasting sliver
    uint i = atomicAdd(ev[2], 1u);
    if (i < uint(SDS_SL_MAX)) sl[SL_LIST + i] = t;
  }
}

#ifndef INVERTED_NO_MAIN
void main() { inverted_at(sessile_gid()); }
#endif
