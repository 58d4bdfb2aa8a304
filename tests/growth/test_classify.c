/* Solid classification (GPU kernel and host reference) of box nodes against
 * closed surfaces.
 *  - GPU mask == reference mask, node for node (same algorithm, same
 *    arithmetic: expected identical, tolerance 0 differing nodes; with
 *    --fp32 the kernel works in float, and nodes within 1e-5 cm of the
 *    surface are left out of the comparison).
 *  - Independent check: the generalised winding number (solid-angle sum,
 *    Van Oosterom-Strackee) for every node farther than 1e-6 from the
 *    surface; a closed surface gives |w| within 1e-6 of 0 or 1, and the mask
 *    must equal round(|w|) (tolerance 0 mismatches).
 *  - Shapes: a polar icosphere centred on a grid node with its poles on grid
 *    nodes (lines through vertices and along edges: degenerate hits), radial
 *    bumps r = R(1 + 0.4 sin 3theta cos 4phi), a star with overhangs (4
 *    crossings per line), a sphere flattened onto the box floor.
 *  - Too many crossings is an error (never a silent wrong mask).
 *  - Timing (printed, never asserted): 65x65x49 nodes with 10k and 41k
 *    triangles. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/growth/growth_gpu.h"
#include "sessile/growth/growth_ref.h"
#include "shapes.h"
#include "testutil.h"

static sessile_la *la;
static sessile_growth_gpu *gg;
/* fp32 contexts classify with float positions and arithmetic: nodes within
 * this distance of the surface may legitimately differ from the double
 * reference (6 cm * 6e-8 rounding, amplified by the edge functions). */
static double fp32_band = 0;

/* Squared distance from p to triangle abc (Ericson, Real-Time Collision
 * Detection, 5.1.5). */
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double dist2_tri(const double *p, const double *a, const double *b, const double *c) {
  double ab[3], ac[3], ap[3], q[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
#define RET(X) do { for (int i = 0; i < 3; i++) q[i] = (X); goto done; } while (0)
  if (d1 <= 0 && d2 <= 0) RET(a[i]);
  double bp[3];
  for (int i = 0; i < 3; i++) bp[i] = p[i] - b[i];
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) RET(b[i]);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { double v = d1 / (d1 - d3); RET(a[i] + v * ab[i]); }
  double cp[3];
  for (int i = 0; i < 3; i++) cp[i] = p[i] - c[i];
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) RET(c[i]);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { double w = d2 / (d2 - d6); RET(a[i] + w * ac[i]); }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    RET(b[i] + w * (c[i] - b[i]));
  }
  {
    double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
    RET(a[i] + ab[i] * v + ac[i] * w);
  }
#undef RET
done:;
  double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
  return dot3(d, d);
}

/* near[node] = 1 where the node is within eps of the surface (checked only
 * for nodes in each triangle's bounding box grown by eps). */
static void mark_near(const sessile_box *b, const sessile_surface *s, double eps, uint8_t *near) {
  memset(near, 0, sessile_box_nodes(b));
  for (uint32_t f = 0; f < s->nf; f++) {
    const double *v[3] = {s->pos + 3 * s->tri[3 * f], s->pos + 3 * s->tri[3 * f + 1],
                          s->pos + 3 * s->tri[3 * f + 2]};
    long lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
      double mn = fmin(v[0][a], fmin(v[1][a], v[2][a])) - eps;
      double mx = fmax(v[0][a], fmax(v[1][a], v[2][a])) + eps;
      lo[a] = (long)ceil((mn - b->origin[a]) / b->h);
      hi[a] = (long)floor((mx - b->origin[a]) / b->h);
      if (lo[a] < 0) lo[a] = 0;
      if (hi[a] > (long)b->n[a] - 1) hi[a] = (long)b->n[a] - 1;
    }
    for (long k = lo[2]; k <= hi[2]; k++)
      for (long j = lo[1]; j <= hi[1]; j++)
        for (long i = lo[0]; i <= hi[0]; i++) {
          uint32_t node = sessile_box_index(b, (uint32_t)i, (uint32_t)j, (uint32_t)k);
          double p[3];
          sessile_box_node_pos(b, node, p);
          if (dist2_tri(p, v[0], v[1], v[2]) <= eps * eps) near[node] = 1;
        }
  }
}

/* Generalised winding number of the surface at p (Van Oosterom & Strackee's
 * solid angle of each triangle, summed, over 4 pi). */
static double winding(const sessile_surface *s, const double *p) {
  double sum = 0;
  for (uint32_t f = 0; f < s->nf; f++) {
    double a[3], b[3], c[3];
    for (int i = 0; i < 3; i++) {
      a[i] = s->pos[3 * s->tri[3 * f] + i] - p[i];
      b[i] = s->pos[3 * s->tri[3 * f + 1] + i] - p[i];
      c[i] = s->pos[3 * s->tri[3 * f + 2] + i] - p[i];
    }
    double la_ = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b)), lc = sqrt(dot3(c, c));
    double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
    double num = dot3(a, bc);
    double den = la_ * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la_;
    sum += 2.0 * atan2(num, den);
  }
  return sum / (4.0 * 3.14159265358979323846);
}

/* Nodes where the masks differ, outside the fp32 band. */
static uint32_t mask_diff(const sessile_box *b, const sessile_surface *s, const uint32_t *gpu,
                          const uint32_t *ref) {
  uint32_t nodes = sessile_box_nodes(b), diff = 0, banded = 0;
  uint8_t *near = calloc(nodes, 1);
  if (fp32_band > 0) mark_near(b, s, fp32_band, near);
  for (uint32_t i = 0; i < nodes; i++) {
    if (gpu[i] == ref[i]) continue;
    if (near[i]) banded++;
    else diff++;
  }
  if (fp32_band > 0)
    printf("   fp32: %u differing nodes within %.0e cm of the surface (not counted)\n", banded, fp32_band);
  free(near);
  return diff;
}

static void check_shape(const char *name, const sessile_box *b, const sessile_surface *s,
                        int winding_check) {
  char what[160];
  uint32_t nodes = sessile_box_nodes(b);
  uint32_t *ref = malloc(nodes * sizeof *ref), *gpu = malloc(nodes * sizeof *gpu);
  sessile_buffer *solid = NULL;
  t_must("solid buffer", sessile_buffer_create(sessile_la_gpu(la), (size_t)nodes * 4,
                                             SESSILE_BUFFER_DEVICE, &solid));
  t_must("reference classify", sessile_growth_ref_classify(b, s, ref));
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, s));
  t_must("gpu classify", sessile_growth_gpu_classify(gg, b, solid));
  t_must("download mask", sessile_buffer_download(solid, 0, gpu, (size_t)nodes * 4));
  uint32_t diff = mask_diff(b, s, gpu, ref), inside = 0;
  for (uint32_t i = 0; i < nodes; i++) inside += ref[i];
  printf("-- %s: %u nodes, %u triangles, %u solid nodes\n", name, nodes, s->nf, inside);
  snprintf(what, sizeof what, "%s: GPU mask vs reference, differing nodes", name);
  t_check(what, diff, 0);
  t_true("  (shape has solid nodes)", inside > 0);
  if (winding_check) {
    uint8_t *near = malloc(nodes);
    mark_near(b, s, 1e-6, near);
    uint32_t skipped = 0, bad = 0, mism = 0;
    double worst = 0;
    for (uint32_t i = 0; i < nodes; i++) {
      if (near[i]) { skipped++; continue; }
      double p[3];
      sessile_box_node_pos(b, i, p);
      double w = fabs(winding(s, p)), r = round(w), e = fabs(w - r);
      if (e > worst) worst = e;
      if (e > 1e-6 || r > 1) bad++;
      else if ((uint32_t)r != ref[i]) mism++;
    }
    printf("   winding check: %u nodes within 1e-6 of the surface skipped\n", skipped);
    snprintf(what, sizeof what, "%s: |w| distance from an integer (closed surface)", name);
    t_check(what, worst, 1e-6);
    snprintf(what, sizeof what, "%s: mask vs winding number, mismatching nodes", name);
    t_check(what, mism + bad, 0);
    free(near);
  }
  sessile_buffer_destroy(solid);
  free(ref), free(gpu);
}

static void shapes(void) {
  /* Box: h = 0.25, origin 0; node (12, 12, 14) = (3, 3, 3.5). */
  sessile_box b = {.origin = {0, 0, 0}, .h = 0.25, .n = {25, 25, 29}};
  sessile_surface s = {0};
  const double c[3] = {3.0, 3.0, 3.5};
  shape_radial(4, 3.0, c, NULL, &s); /* poles at (3, 3, 0.5) and (3, 3, 6.5): grid nodes */
  check_shape("polar icosphere on grid lines", &b, &s, 1);
  shape_radial(3, 2.0, c, NULL, &s); /* coarse: long edges along grid lines x = 3 */
  check_shape("coarse polar icosphere", &b, &s, 1);
  const double c2[3] = {3.05, 2.95, 3.4};
  shape_radial(4, 2.2, c2, bumps, &s);
  check_shape("radial bumps 1 + 0.4 sin3t cos4p", &b, &s, 1);
  shape_radial(4, 3.0, c, star, &s);
  check_shape("star with overhangs", &b, &s, 1);
  /* flattened onto the floor: bottom cap clamped to z = 0 exactly */
  const double c3[3] = {3.0, 3.0, 2.0};
  shape_radial(4, 2.5, c3, NULL, &s);
  for (uint32_t v = 0; v < s.nv; v++)
    if (s.pos[3 * v + 2] < 0) s.pos[3 * v + 2] = 0;
  check_shape("sphere flattened on the box floor", &b, &s, 1);
  /* the flat bottom's nodes at z = 0 under the sponge count as solid */
  uint32_t *m = malloc(sessile_box_nodes(&b) * sizeof *m);
  t_must("classify", sessile_growth_ref_classify(&b, &s, m));
  t_true("floor node under the flattened sphere (3, 3, 0) is solid",
         m[sessile_box_index(&b, 12, 12, 0)] == 1);
  t_true("floor node outside it (0.5, 0.5, 0) is fluid", m[sessile_box_index(&b, 2, 2, 0)] == 0);
  free(m);
  sessile_surface_free(&s);
}

/* Many stacked thin shells in one column: more than 64 crossings must fail. */
static void too_many(void) {
  sessile_box b = {.origin = {0, 0, 0}, .h = 1.0, .n = {3, 3, 3}};
  sessile_surface s = {0}, one = {0};
  const double c[3] = {1.0, 1.0, 1.0};
  shape_must(sessile_surface_reserve(&s, 12 * 40, 20 * 40));
  for (int q = 0; q < 40; q++) { /* 40 nested spheres: 80 crossings on the axis */
    shape_radial(1, 0.9 - 0.02 * q, c, NULL, &one);
    for (uint32_t v = 0; v < one.nv * 3; v++) s.pos[3 * s.nv + v] = one.pos[v];
    for (uint32_t f = 0; f < one.nf * 3; f++) s.tri[3 * s.nf + f] = one.tri[f] + s.nv;
    s.nv += one.nv, s.nf += one.nf;
  }
  uint32_t m[27];
  sessile_status st = sessile_growth_ref_classify(&b, &s, m);
  t_true("reference: > 64 crossings in a column is SESSILE_ERR_NUMERIC", st == SESSILE_ERR_NUMERIC);
  printf("   message: %s\n", sessile_error_message());
  sessile_buffer *solid = NULL;
  t_must("solid buffer", sessile_buffer_create(sessile_la_gpu(la), 27 * 4, SESSILE_BUFFER_DEVICE, &solid));
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, &s));
  st = sessile_growth_gpu_classify(gg, &b, solid);
  t_true("GPU: > 64 crossings in a column is SESSILE_ERR_NUMERIC", st == SESSILE_ERR_NUMERIC);
  printf("   message: %s\n", sessile_error_message());
  sessile_buffer_destroy(solid);
  sessile_surface_free(&s), sessile_surface_free(&one);
}

static void timing(int level) {
  sessile_box b = {.origin = {0, 0, 0}, .h = 0.25, .n = {65, 65, 49}};
  sessile_surface s = {0};
  const double c[3] = {8.03, 7.98, 6.01};
  shape_radial(level, 5.0, c, bumps, &s);
  uint32_t nodes = sessile_box_nodes(&b);
  uint32_t *ref = malloc(nodes * sizeof *ref), *gpu = malloc(nodes * sizeof *gpu);
  sessile_buffer *solid = NULL;
  t_must("solid buffer", sessile_buffer_create(sessile_la_gpu(la), (size_t)nodes * 4,
                                             SESSILE_BUFFER_DEVICE, &solid));
  t_must("set_surface", sessile_growth_gpu_set_surface(gg, &s));
  double best = 1e30;
  for (int r = 0; r < 3; r++) {
    t_must("gpu classify", sessile_growth_gpu_classify(gg, &b, solid));
    double t = sessile_growth_gpu_classify_seconds(gg);
    best = t < best ? t : best;
  }
  double t0 = sessile_wall_seconds();
  t_must("reference classify", sessile_growth_ref_classify(&b, &s, ref));
  double tref = sessile_wall_seconds() - t0;
  t_must("download", sessile_buffer_download(solid, 0, gpu, (size_t)nodes * 4));
  uint32_t diff = mask_diff(&b, &s, gpu, ref);
  char what[160];
  snprintf(what, sizeof what, "65x65x49 nodes, %u triangles: GPU vs reference, differing nodes", s.nf);
  t_check(what, diff, 0);
  printf("TIME classify 65x65x49 nodes, %u triangles: GPU call %.4f s (best of 3, binning and "
         "upload included), host reference %.4f s\n", s.nf, best, tref);
  sessile_buffer_destroy(solid);
  free(ref), free(gpu);
  sessile_surface_free(&s);
}

int main(int argc, char **argv) {
  int prec = argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0;
  sessile_gpu *g = t_gpu(prec);
  if (sessile_gpu_info_of(g)->precision == 32) fp32_band = 1e-5;
  t_must("la", sessile_la_create(g, &la));
  t_must("growth gpu", sessile_growth_gpu_create(la, &gg));
  shapes();
  too_many();
  timing(5);
  timing(6);
  sessile_growth_gpu_destroy(gg);
  sessile_la_destroy(la);
  return t_finish(g);
}
