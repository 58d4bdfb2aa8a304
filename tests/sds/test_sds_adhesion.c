/* The obstacle's adhesion and friction (docs/sds.md, "Adhesion and
 * friction") against their definitions, on a ball held over a flat plane
 * (two triangles at z = 0, normal +z) with no springs: every cell's one
 * step is then known in closed form.  A cell at height z with contact
 * distance delta = contact_scale r:
 *   z < delta:            a_z += k_wall (delta - z)              (the penalty)
 *   delta <= z < 2 delta: a_z -= A tent((z - delta) / delta)     (adhesion,
 *                         tent(u) = 2u below 1/2, 2 (1 - u) above)
 *   z < 2 delta:          v_x, v_y of v + dt a divided by 1 + friction dt
 * plus the viscosity -c v, and x += dt v.  The GPU's step (sessile_sds_gpu_step)
 * and the host's (sessile_sds_step_ref) must both give it to 1e-12 of the
 * speed, for heights that put cells in every zone (each zone must be hit);
 * the stable bounds of host and device agree with an adhesion whose slope
 * 2 A / delta exceeds k_wall (the bound's max branch); adhesion and friction
 * without an obstacle change nothing (bit for bit); and a ball resting
 * off-centre on a rock under gravity rolls off when it is frictionless and
 * stays with adhesion and friction. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/sds/sds.h"
#include "testutil.h"

static const double plane_pos[12] = {-10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0};
static const uint32_t plane_tri[6] = {0, 1, 2, 0, 2, 3};
static const double V0[3] = {0.3, -0.2, 0.1};

static void params_of(sessile_sds_params *p, int obstacle) {
  sessile_sds_params_default(p);
  p->k_edge = 0, p->k_vol = 0, p->gravity = 0, p->damp_vol = 0, p->damp_visc = 0.5;
  p->self_collide = 0;
  p->adhesion = 5, p->friction = 200;
  if (obstacle) p->obstacle.nv = 4, p->obstacle.nf = 2, p->obstacle.pos = plane_pos, p->obstacle.tri = plane_tri;
}

/* The closed form of one step of cell c (x, v at the step's start) into xe,
 * ve; returns its zone: 0 penalty, 1 rising tent, 2 falling tent, 3 free. */
static int expected(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, double dt, double *xe, double *ve) {
  const double *x = o->x + 3 * (size_t)c, *v = o->v + 3 * (size_t)c;
  double delta = p->contact_scale * o->r[c], z = x[2], a[3];
  for (int i = 0; i < 3; i++) a[i] = -p->damp_visc * v[i];
  int zone = 3;
  if (z < delta)
    a[2] += p->k_wall * (delta - z), zone = 0;
  else if (z < 2 * delta) {
    double u = (z - delta) / delta;
    a[2] -= p->adhesion * (u < 0.5 ? 2 * u : 2 * (1 - u));
    zone = u < 0.5 ? 1 : 2;
  }
  for (int i = 0; i < 3; i++) ve[i] = v[i] + dt * a[i];
  if (zone < 3) ve[0] /= 1 + dt * p->friction, ve[1] /= 1 + dt * p->friction;
  for (int i = 0; i < 3; i++) xe[i] = x[i] + dt * ve[i];
  return zone;
}

int main(int argc, char **argv) {
  int fp32 = 0;
  sessile_gpu *g = t_gpu_args(argc, argv, &fp32);
  const double dt = 1e-3, tol = fp32 ? 1e-5 : 1e-12;
  int hits[4] = {0, 0, 0, 0};
  double rmean = 0;
  {
    const double ctr[3] = {0, 0, 0};
    sessile_sds o = {0};
    t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
    for (uint32_t c = 0; c < o.ncells; c++) rmean += o.r[c] / o.ncells;
    sessile_sds_free(&o);
  }
  /* the ball's lowest cell at 0.5, 1.2 and 1.7 mean contact distances
   * above the plane: the rings above it fall in the other zones */
  const double lift[3] = {0.5, 1.2, 1.7};
  for (int k = 0; k < 3; k++) {
    const double ctr[3] = {0.0123, 0.0271, 1.0 + lift[k] * rmean};
    sessile_sds o = {0}, h = {0}, d = {0};
    t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
    t_must("ball (host)", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &h));
    t_must("ball (device)", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &d));
    for (uint32_t c = 0; c < o.ncells; c++)
      for (int i = 0; i < 3; i++) o.v[3 * (size_t)c + i] = h.v[3 * (size_t)c + i] = V0[i];
    sessile_sds_params p;
    params_of(&p, 1);
    size_t n3 = 3 * (size_t)o.ncells;
    double *xe = t_dalloc(n3), *ve = t_dalloc(n3), vmax = 0;
    int here[4] = {0, 0, 0, 0};
    for (uint32_t c = 0; c < o.ncells; c++) here[expected(&o, &p, c, dt, xe + 3 * (size_t)c, ve + 3 * (size_t)c)]++;
    for (int i = 0; i < 3; i++) vmax = fmax(vmax, fabs(V0[i]));
    for (int z = 0; z < 4; z++) hits[z] += here[z];
    char what[200];
    /* the host's step */
    sessile_sds_step_ref(&h, &p, dt);
    snprintf(what, sizeof what,
             "lift %.1f: host step = closed form (%d penalty, %d rising, %d falling, %d free; |dv| / |v|)", lift[k],
             here[0], here[1], here[2], here[3]);
    t_check(what, t_maxdiff(h.v, ve, n3) / vmax, 1e-12);
    snprintf(what, sizeof what, "lift %.1f: host step's positions (|dx| / dt |v|)", lift[k]);
    t_check(what, t_maxdiff(h.x, xe, n3) / (dt * vmax), 1e-9);
    /* the device's step */
    sessile_sds_gpu *s = NULL;
    t_must("gpu create", sessile_sds_gpu_create(g, &o, &p, &s));
    double mv = 0;
    t_must("gpu step", sessile_sds_gpu_step(s, dt, &mv));
    t_must("gpu download", sessile_sds_gpu_download(s, &d));
    snprintf(what, sizeof what, "lift %.1f: GPU step = closed form (|dv| / |v|)", lift[k]);
    t_check(what, t_maxdiff(d.v, ve, n3) / vmax, tol);
    snprintf(what, sizeof what, "lift %.1f: GPU step's positions (|dx| / dt |v|)", lift[k]);
    t_check(what, t_maxdiff(d.x, xe, n3) / (dt * vmax), fp32 ? 1e-2 : 1e-9);
    sessile_sds_gpu_destroy(s);
    /* without an obstacle the two keys do nothing: the frictionless free
     * step, bit for bit against the same step with both zero */
    if (k == 0) {
      sessile_sds_params q0, q1;
      params_of(&q1, 0);
      params_of(&q0, 0);
      q0.adhesion = 0, q0.friction = 0;
      sessile_sds a = {0}, b = {0};
      t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &a));
      t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &b));
      sessile_sds_gpu *s0 = NULL, *s1 = NULL;
      t_must("gpu create", sessile_sds_gpu_create(g, &o, &q0, &s0));
      t_must("gpu create", sessile_sds_gpu_create(g, &o, &q1, &s1));
      t_must("gpu step", sessile_sds_gpu_step(s0, dt, NULL));
      t_must("gpu step", sessile_sds_gpu_step(s1, dt, NULL));
      t_must("gpu download", sessile_sds_gpu_download(s0, &a));
      t_must("gpu download", sessile_sds_gpu_download(s1, &b));
      t_true("no obstacle: adhesion and friction change no bit of the step",
             !memcmp(a.x, b.x, n3 * sizeof *a.x) && !memcmp(a.v, b.v, n3 * sizeof *a.v));
      sessile_sds_gpu_destroy(s0), sessile_sds_gpu_destroy(s1);
      sessile_sds_free(&a), sessile_sds_free(&b);
    }
    free(xe), free(ve);
    sessile_sds_free(&o), sessile_sds_free(&h), sessile_sds_free(&d);
  }
  t_true("every zone reached: penalty, adhesion rising, adhesion falling, free",
         hits[0] > 0 && hits[1] > 0 && hits[2] > 0 && hits[3] > 0);
  /* the stable bound with an adhesion steeper than the wall (2 A / delta >
   * k_wall): host and device agree, and it is below the wall-only bound */
  if (!fp32) {
    const double ctr[3] = {0.0123, 0.0271, 1.0 + 1.2 * rmean};
    sessile_sds o = {0};
    t_must("ball", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
    sessile_sds_params p;
    params_of(&p, 1);
    p.k_edge = 1, p.k_vol = 2;
    double b_wall = sessile_sds_stable_dt(&o, &p);
    p.adhesion = 2 * p.k_wall * rmean; /* 2 A / delta = 4 k_wall at the mean radius */
    double b_host = sessile_sds_stable_dt(&o, &p), b_dev = 0;
    sessile_sds_gpu *s = NULL;
    t_must("gpu create", sessile_sds_gpu_create(g, &o, &p, &s));
    t_must("gpu bound", sessile_sds_gpu_stable_dt(s, &b_dev));
    sessile_sds_gpu_destroy(s);
    char what[160];
    snprintf(what, sizeof what, "stable bound with a steep adhesion: device = host (%.6g s; rel)", b_host);
    t_check(what, fabs(b_dev - b_host) / b_host, 1e-12);
    snprintf(what, sizeof what, "  and below the wall-only bound (%.6g < %.6g s)", b_host, b_wall);
    t_true(what, b_host < b_wall);
    sessile_sds_free(&o);
  }
  /* What they are for: a stiff ball resting off-centre on top of a rock
   * under gravity rolls off a frictionless rock, and stays where it was put
   * on a sticking one (adhesion twice gravity, friction 1000/s). */
  if (!fp32) {
    const double rc[3] = {0, 0, 0};
    sessile_surface rock = {0};
    t_must("rock", sessile_surface_icosphere(3, 1.5, rc, &rock));
    double off[2] = {0, 0}, off0 = 0, zc[2] = {0, 0};
    for (int stick = 0; stick < 2; stick++) {
      const double ctr[3] = {0.15, 0.05, 2.08};
      sessile_sds o = {0};
      t_must("ball", sessile_sds_from_icosphere(2, 0.5, ctr, 0, 0, 0, 1.0, &o));
      sessile_sds_params p;
      sessile_sds_params_default(&p); /* gravity 10 */
      p.k_edge = 300, p.k_vol = 600, p.damp_visc = 0.5, p.damp_vol = 0.01, p.k_wall = 3000;
      p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
      p.adhesion = stick ? 2 * p.gravity : 0, p.friction = stick ? 1000 : 0;
      double cen[3] = {0, 0, 0};
      for (uint32_t c = 0; c < o.ncells; c++)
        for (int i = 0; i < 3; i++) cen[i] += o.x[3 * (size_t)c + i] / o.ncells;
      off0 = hypot(cen[0], cen[1]);
      sessile_sds_gpu *s = NULL;
      t_must("gpu", sessile_sds_gpu_create(g, &o, &p, &s));
      double step = p.dt, t = 0;
      while (t < 4) t_must("advance", sessile_sds_gpu_advance(s, 100, &step, &t));
      t_must("download", sessile_sds_gpu_download(s, &o));
      cen[0] = cen[1] = cen[2] = 0;
      for (uint32_t c = 0; c < o.ncells; c++)
        for (int i = 0; i < 3; i++) cen[i] += o.x[3 * (size_t)c + i] / o.ncells;
      off[stick] = hypot(cen[0], cen[1]), zc[stick] = cen[2];
      printf("%s rock: the ball's centre %.3f u off the rock's axis after %.2f s (%.3f at the start), z %.3f\n",
             stick ? "sticking" : "frictionless", off[stick], t, off0, cen[2]);
      sessile_sds_gpu_destroy(s);
      sessile_sds_free(&o);
    }
    char what[160];
    snprintf(what, sizeof what, "a frictionless rock: the ball rolls off (%.3f u off its axis from %.3f)", off[0], off0);
    t_true(what, off[0] > 1.0);
    /* on top: near the rock's axis (the soft ball leans downhill a little,
     * 0.06-0.09 u here whatever the friction) and above the rock's top */
    snprintf(what, sizeof what, "a sticking rock: the ball stays on top (%.3f u off its axis from %.3f, centre z %.3f)",
             off[1], off0, zc[1]);
    t_true(what, off[1] < 0.5 && zc[1] > 1.5);
    sessile_surface_free(&rock);
  }
  return t_finish(g);
}
