/* Host references of shaders/fem/cutcell.comp and ghost.comp (the cut-cell
 * nutrient's boundary setup and its extension across the surface), in
 * double, operation by operation, for the tests. */
#include <math.h>
#include "sessile/fem/nutrient_cut.h"

typedef struct {
  const sessile_box *box;
  const sessile_cut_bc *bc;
} ctx;

static double zk(const ctx *x, uint32_t k) { return x->box->h * k; }

static int node_dirichlet(const ctx *x, const uint32_t c[3], double *value) {
  const uint32_t *n = x->box->n;
  *value = 0;
  if (c[2] == 0) return 1;
  *value = 1;
  if (x->bc->far_field == SESSILE_FAR_FIELD_WALLS)
    return c[0] == 0 || c[1] == 0 || c[0] == n[0] - 1 || c[1] == n[1] - 1 || c[2] == n[2] - 1;
  if (x->bc->far_field == SESSILE_FAR_FIELD_INLET && c[0] == 0) return 1;
  if (x->bc->far_field == SESSILE_FAR_FIELD_PROFILE && c[0] == 0) {
    double z = zk(x, c[2]) / x->bc->height;
    *value = z < 1 ? z : 1;
    return 1;
  }
  return !(zk(x, c[2]) < x->bc->height - 1e-9 * x->box->h);
}

static double face(const ctx *x, const uint32_t c[3], int a) {
  double f = 1;
  for (int b = 0; b < 3; b++)
    if (b != a && (c[b] == 0 || c[b] == x->box->n[b] - 1)) f *= 0.5;
  return f;
}

static double theta_of(const ctx *x, const double *theta, size_t node, int d) {
  double t = theta[6 * node + d];
  if (!(t < 1)) t = 1;
  return t > x->bc->theta_min ? t : x->bc->theta_min;
}

static size_t stride(const sessile_box *b, int a) {
  return a == 0 ? 1 : a == 1 ? b->n[0] : (size_t)b->n[0] * b->n[1];
}

/* cut_adv.glsl: B(x) = x / (e^x - 1), and the factor of an edge's weight. */
double sessile_cut_bernoulli(double x) {
  if (x == 0) return 1;
  if (x > 700) return 0;
  if (x < -700) return -x;
  return x / expm1(x);
}

static double adv_factor(const ctx *x, const double *vel, double pe, size_t node,
                         const uint32_t c[3], int d, double th) {
  int a = d >> 1, plus = d & 1;
  double p = vel[3 * node + a] * pe, sp = plus ? p : -p;
  int wall = plus ? c[a] == 0 : c[a] + 1 == x->box->n[a];
  if (wall && th == 1) return 0.5 * (sessile_cut_bernoulli(p) + sessile_cut_bernoulli(-p));
  return sessile_cut_bernoulli(sp * th);
}

/* Both setups: vel NULL is the Laplace one (cutcell.comp), else cutcell_adv.comp. */
static void setup(const sessile_box *box, const sessile_cut_bc *bc, const uint32_t *solid,
                  const double *theta, const double *vel, double pe, uint32_t *mask, double *diag,
                  double *coef, double *lift, double *value) {
  ctx x = {box, bc};
  size_t nodes = sessile_box_nodes(box);
  for (size_t node = 0; node < nodes; node++) {
    uint32_t c[3] = {(uint32_t)(node % box->n[0]), (uint32_t)(node / box->n[0] % box->n[1]),
                     (uint32_t)(node / ((size_t)box->n[0] * box->n[1]))};
    double g;
    uint32_t code = node_dirichlet(&x, c, &g) ? SESSILE_CUT_NODE
                    : solid[node] ? SESSILE_CUT_SOLID : SESSILE_CUT_FREE;
    if (code == SESSILE_CUT_SOLID) g = 0;
    mask[node] = code;
    if (coef)
      for (int dir = 0; dir < 6; dir++) coef[6 * node + dir] = 0;
    if (code != SESSILE_CUT_FREE) {
      diag[node] = 1;
      if (lift) lift[node] = 0, value[node] = g;
      continue;
    }
    double d = 0, b = 0;
    for (int dir = 0; dir < 6; dir++) {
      int a = dir >> 1, plus = dir & 1;
      if (plus ? c[a] + 1 >= box->n[a] : c[a] == 0) continue;
      size_t m = plus ? node + stride(box, a) : node - stride(box, a);
      uint32_t cm[3] = {c[0], c[1], c[2]};
      cm[a] = plus ? c[a] + 1 : c[a] - 1;
      double gm, f = face(&x, c, a), w = 1, th = 1;
      if (node_dirichlet(&x, cm, &gm)) {
        if (bc->far_field != SESSILE_FAR_FIELD_WALLS && a == 2 && plus && cm[2] != 0) {
          double t = (bc->height - zk(&x, c[2])) / box->h;
          t = t < 1 ? t : 1;
          th = t > bc->theta_min ? t : bc->theta_min;
          w = 1 / th;
        }
        if (vel) w *= adv_factor(&x, vel, pe, node, c, dir, th);
        b += f * w * gm;
      } else {
        if (solid[m]) th = theta_of(&x, theta, node, dir), w = 1 / th;
        if (vel) w *= adv_factor(&x, vel, pe, node, c, dir, th);
      }
      if (coef) coef[6 * node + dir] = w;
      d += f * w;
    }
    diag[node] = d;
    if (lift) lift[node] = box->h * b, value[node] = 0;
  }
}

void sessile_cut_ref_setup(const sessile_box *box, const sessile_cut_bc *bc, const uint32_t *solid,
                           const double *theta, uint32_t *mask, double *diag, double *lift,
                           double *value) {
  setup(box, bc, solid, theta, NULL, 0, mask, diag, NULL, lift, value);
}

void sessile_cut_ref_setup_adv(const sessile_box *box, const sessile_cut_bc *bc,
                               const uint32_t *solid, const double *theta, const double *vel,
                               double pe, uint32_t *mask, double *diag, double *coef, double *lift,
                               double *value) {
  setup(box, bc, solid, theta, vel, pe, mask, diag, coef, lift, value);
}

void sessile_cut_ref_ghost(const sessile_box *box, const sessile_cut_bc *bc, const uint32_t *mask,
                           const double *theta, const double *c, double *ext) {
  ctx x = {box, bc};
  size_t nodes = sessile_box_nodes(box);
  for (size_t node = 0; node < nodes; node++) {
    if (mask[node] != SESSILE_CUT_SOLID) {
      ext[node] = c[node];
      continue;
    }
    uint32_t p[3] = {(uint32_t)(node % box->n[0]), (uint32_t)(node / box->n[0] % box->n[1]),
                     (uint32_t)(node / ((size_t)box->n[0] * box->n[1]))};
    double sum = 0;
    int count = 0;
    for (int dir = 0; dir < 6; dir++) {
      int a = dir >> 1, plus = dir & 1;
      if (plus ? p[a] + 1 >= box->n[a] : p[a] == 0) continue;
      size_t m = plus ? node + stride(box, a) : node - stride(box, a);
      if (mask[m] != SESSILE_CUT_FREE) continue;
      double t = theta_of(&x, theta, m, dir ^ 1);
      sum += c[m] - c[m] / t;
      count++;
    }
    ext[node] = count ? sum / count : 0;
  }
}
