// The exponentially fitted weights of the advected nutrient (cutcell_adv.comp,
// docs/nutrient.md): the edge from node n in direction d (axis a, sign s),
// of length theta h, carries B(s P theta) / theta where P = u_a(n) h / D and
// B(x) = x / (e^x - 1) (Scharfetter-Gummel / Il'in-Allen-Southwell); on a
// zero-flux wall (the opposite neighbour missing) the mirror image's mean
// (B(P) + B(-P)) / 2.  Mirrored by host/fem/nutrient_cut_ref.c.
#ifndef CUT_ADV_GLSL
#define CUT_ADV_GLSL

#if SESSILE_F64
// e^x - 1 without cancellation: Taylor (degree 17) for |x| < 1/2, else
// Cody-Waite reduction to |r| <= ln2/2 and Taylor (error < 1e-24).
double adv_expm1_small(double x) {
  double p = 1.0LF;
  for (int j = 17; j >= 2; j--) p = 1.0LF + p * x / double(j);
  return x * p;
}
double adv_expm1(double x) {
  if (abs(x) < 0.5LF) return adv_expm1_small(x);
  double k = floor(x * 1.44269504088896340736LF + 0.5LF);
  double r = (x - k * 6.93147180369123816490e-01LF) - k * 1.90821492927058770002e-10LF;
  return ldexp(adv_expm1_small(r) + 1.0LF, int(k)) - 1.0LF;
}
#else
float adv_expm1(float x) {
  if (abs(x) < 0.5) {
    float p = 1.0;
    for (int j = 9; j >= 2; j--) p = 1.0 + p * x / float(j);
    return x * p;
  }
  return exp(x) - 1.0;
}
#endif

// B(x) = x / (e^x - 1), B(0) = 1; 0 past x = 700 and -x below -700 (where e^x
// leaves double's range: B(x) = x e^-x underflows, B(-x) = x + B(x)).
REAL adv_bernoulli(REAL x) {
  if (x == REAL(0)) return REAL(1);
  if (x > REAL(700)) return REAL(0);
  if (x < REAL(-700)) return -x;
  return x / adv_expm1(x);
}

// The factor of the weight of node n's edge in direction d at fraction th.
REAL adv_factor(uint node, uint c[3], uint d, REAL th) {
  uint a = d >> 1u;
  REAL p = vel[3u * node + a] * pc.pe;
  REAL sp = (d & 1u) != 0u ? p : -p;
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
  bool wall = (d & 1u) != 0u ? c[a] == 0u : c[a] + 1u == n[a];
  if (wall && th == REAL(1)) return REAL(0.5) * (adv_bernoulli(p) + adv_bernoulli(-p));
  return adv_bernoulli(sp * th);
}
#endif
