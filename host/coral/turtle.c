/* The 3-D turtle (ABOP ch. 1.5, Coralize §3.1) that turns a module string
 * into a skeleton.  The turtle's frame (H heading, L left, U = H x L) turns
 * with the rotation symbols; the tubes are oriented by a separate
 * rotation-minimising normal r carried along each branch by double
 * reflection (Wang et al. 2008), so rolls and bends do not twist them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/coral/lsystem.h"
#include "sessile/rng.h"
#include "sessile/mesh/skeleton.h"

typedef struct tstate {
  double pos[3], H[3], L[3], U[3];
  double r[3], t[3]; /* the RMF normal and the tangent it belongs to */
  double width;
  double end_width; /* radius at the end of the last segment on this path (< 0: none yet) */
  uint32_t depth;
} tstate;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static void normalize(double *a) {
  double l = sqrt(dot3(a, a));
  if (l > 0) a[0] /= l, a[1] /= l, a[2] /= l;
}

/* (a, b) -> (a cos t + b sin t, b cos t - a sin t): a rotation of the plane
 * spanned by a and b, about the third axis of the frame. */
static void turn(double *a, double *b, double deg) {
  double t = deg * (3.14159265358979323846 / 180.0), c = cos(t), s = sin(t);
  for (int k = 0; k < 3; k++) {
    double x = a[k], y = b[k];
    a[k] = x * c + y * s, b[k] = y * c - x * s;
  }
}

/* Keeps H, L, U orthonormal and right-handed against rounding drift. */
static void orthonormalize(tstate *s) {
  normalize(s->H);
  double k = dot3(s->L, s->H);
  for (int i = 0; i < 3; i++) s->L[i] -= k * s->H[i];
  normalize(s->L);
  cross3(s->H, s->L, s->U);
}

/* Rodrigues: v about the unit axis k by angle a (radians). */
static void rotate(double *v, const double *k, double a) {
  double kv[3], c = cos(a), s = sin(a), d = dot3(k, v);
  cross3(k, v, kv);
  for (int i = 0; i < 3; i++) v[i] = v[i] * c + kv[i] * s + k[i] * d * (1 - c);
}

/* Tropism (ABOP eq. before Fig. 2.8): H bends toward T by e |H x T|. */
static void tropism(tstate *s, const double *T, double e) {
  double k[3];
  cross3(s->H, T, k);
  double m = sqrt(dot3(k, k));
  if (!(m > 1e-15)) return;
  for (int i = 0; i < 3; i++) k[i] /= m;
  double a = e * m;
  rotate(s->H, k, a), rotate(s->L, k, a), rotate(s->U, k, a);
  orthonormalize(s);
}

/* The RMF normal carried from tangent t to d (unit): reflection in the
 * plane normal to the chord (identity on r, which is normal to t, and t ->
 * -t), then in the plane normal to d + t: together the rotation about
 * t x d that takes t to d.  A half turn (d = -t) keeps r. */
static void transport(tstate *s, const double *d) {
  double v[3] = {s->t[0] + d[0], s->t[1] + d[1], s->t[2] + d[2]};
  double c = dot3(v, v);
  if (c > 1e-24) {
    double k = 2 * dot3(v, s->r) / c;
    for (int i = 0; i < 3; i++) s->r[i] -= k * v[i];
  }
  double k = dot3(s->r, d);
  for (int i = 0; i < 3; i++) s->r[i] -= k * d[i];
  normalize(s->r);
  memcpy(s->t, d, sizeof s->t);
}

static double arg0(const sessile_lsys_string *s, uint32_t i, double def, uint64_t *rng) {
  uint8_t n = s->np[i];
  if (n == 0) return def;
  const double *p = s->par + s->off[i];
  return n >= 2 && p[1] != 0 ? sessile_rng_range(rng, p[0] - p[1], p[0] + p[1]) : p[0];
}

static double vary_width(double w, const sessile_turtle_params *p, uint64_t *rng) {
  if (p->thickness_variance > 0) w *= 1 + p->thickness_variance * sessile_rng_range(rng, -1, 1);
  return w < p->min_radius ? p->min_radius : w;
}

sessile_status sessile_turtle_interpret(const sessile_lsys_string *s, const sessile_turtle_params *p, uint64_t *rng,
                                        struct sessile_skeleton *out, sessile_turtle_stats *stats) {
  SESSILE_CHECK(p->step > 0 && p->thickness > 0 && p->min_radius > 0 && p->width_factor > 0 &&
                    isfinite(p->tropism_strength) && isfinite(p->angle),
                SESSILE_ERR_USAGE, "turtle: step, thickness, min_radius and width_factor must be positive");
  sessile_turtle_stats st = {0};
  double T[3] = {p->tropism[0], p->tropism[1], p->tropism[2]};
  normalize(T);
  int use_tropism = p->tropism_strength != 0 && dot3(T, T) > 0;
  tstate cur = {.H = {0, 0, 1}, .L = {0, 1, 0}, .U = {-1, 0, 0}, .r = {-1, 0, 0}, .t = {0, 0, 1}};
  cur.width = p->thickness < p->min_radius ? p->min_radius : p->thickness;
  cur.end_width = -1;
  tstate *stack = NULL;
  uint32_t top = 0, cap = 0;
  sessile_status status = SESSILE_OK;
  for (uint32_t i = 0; i < s->n && status == SESSILE_OK; i++) {
    switch (s->sym[i]) {
    case 'F':
    case 'f': {
      double len = arg0(s, i, 1, rng) * p->step;
      if (!(len > 0)) break;
      double a[3] = {cur.pos[0], cur.pos[1], cur.pos[2]};
      transport(&cur, cur.H);
      for (int k = 0; k < 3; k++) cur.pos[k] += len * cur.H[k];
      if (s->sym[i] == 'F') {
        double ra = p->taper && cur.end_width > 0 ? cur.end_width : cur.width;
        status = sessile_skeleton_add(out, a, cur.pos, ra, cur.width, cur.r, cur.depth);
        cur.end_width = cur.width;
        st.segments++, st.length += len;
        if (cur.depth > st.max_depth) st.max_depth = cur.depth;
        if (use_tropism) tropism(&cur, T, p->tropism_strength);
      }
      break;
    }
    case '+': turn(cur.H, cur.L, arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '-': turn(cur.H, cur.L, -arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '&': turn(cur.H, cur.U, -arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '^': turn(cur.H, cur.U, arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '\\': turn(cur.L, cur.U, arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '/': turn(cur.L, cur.U, -arg0(s, i, p->angle, rng)); orthonormalize(&cur); break;
    case '|':
      for (int k = 0; k < 3; k++) cur.H[k] = -cur.H[k], cur.L[k] = -cur.L[k];
      break;
    case '#':
      cur.width = vary_width(s->np[i] ? arg0(s, i, 1, rng) * p->thickness : cur.width / p->width_factor, p, rng);
      break;
    case '!':
      cur.width = vary_width(s->np[i] ? arg0(s, i, 1, rng) * p->thickness : cur.width * p->width_factor, p, rng);
      break;
    case '[':
      if (top == cap) {
        uint32_t nc = cap ? 2 * cap : 64;
        tstate *ns = realloc(stack, (size_t)nc * sizeof *ns);
        if (!ns) {
          status = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a turtle stack of %u", nc);
          break;
        }
        stack = ns, cap = nc;
      }
      stack[top++] = cur;
      cur.depth++;
      st.branches++;
      break;
    case ']':
      if (top) cur = stack[--top]; /* an unmatched ']' is ignored */
      break;
    default: break; /* other symbols only steer the derivation */
    }
  }
  free(stack);
  if (stats) *stats = st;
  return status;
}
