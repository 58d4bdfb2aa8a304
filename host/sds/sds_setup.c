/* The SDS loop's set-up (sds_sim.h): the model's text, parameters and
 * physics checked without a device, the starting organism (the icosphere,
 * its realisation, or the model's surface) and its tips. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"
#include "sds/sds_surface_file.h"

static double mean_edge(const sessile_surface *srf);

double sds_param1(const sessile_sds_model *m, const char *name, double def) {
  const sessile_sds_param *q = sessile_sds_model_param_find(m, name);
  return q && q->nvalues >= 1 ? q->values[0] : def;
}

/* The physics from the parameter table's values and the model's scene
 * (box, rock, attractor: vectors the table does not hold). */
static sessile_status read_physics(sds_sim *s, const char *where) {
  const sessile_sds_model *m = s->model;
  const sessile_sds_run_params *q = &s->prm;
  sessile_sds_params_default(&s->p);
  s->p.k_edge = q->edge_stiffness;
  s->p.k_vol = q->volume_stiffness;
  s->p.surface_mult = q->surface_multiplier;
  s->p.uniform_stiffness = q->uniform_stiffness;
  s->p.damp_vol = q->damping;
  s->p.damp_visc = q->viscosity;
  s->p.gravity = q->gravity;
  s->p.dt = q->dt;
  s->p.max_move = q->max_move;
  s->p.stable_safety = q->stable_safety;
  s->p.mass_scaling_dt = q->mass_scaling_dt;
  s->density = q->density;
  s->p.self_collide = q->self_collide;
  s->p.adhesion = q->obstacle_adhesion;
  s->p.friction = q->obstacle_friction;
  const sessile_sds_param *box = sessile_sds_model_param_find(m, "box");
  if (box) {
    SESSILE_CHECK(box->nvalues == 6, SESSILE_ERR_USAGE, "%s:%d: box needs 6 values: xmin ymin zmin xmax ymax zmax",
                  where, box->line);
    s->p.box = 1;
    for (int k = 0; k < 3; k++) {
      s->p.box_lo[k] = box->values[k], s->p.box_hi[k] = box->values[3 + k];
      SESSILE_CHECK(s->p.box_lo[k] < s->p.box_hi[k], SESSILE_ERR_USAGE, "%s:%d: the box is empty along axis %d", where,
                    box->line, k);
    }
  }
  const sessile_sds_param *rock = sessile_sds_model_param_find(m, "rock");
  if (rock) {
    SESSILE_CHECK(rock->nvalues == 4 && rock->values[3] > 0, SESSILE_ERR_USAGE,
                  "%s:%d: rock needs 4 values: centre x y z and a radius > 0", where, rock->line);
    SESSILE_CALL(sessile_surface_icosphere(4, rock->values[3], rock->values, &s->rock));
    if (s->prm.start_symmetry >= 2) {
      /* a symmetric start on a symmetric rock (its centre on the axis: the
       * mirrors are about the rock's vertical axis) */
      double h = mean_edge(&s->rock);
      sessile_surface_free(&s->rock);
      SESSILE_CALL(sessile_sds_symmetric_sphere(s->prm.start_symmetry, rock->values[3], h, rock->values, &s->rock));
    }
    s->p.obstacle.nv = s->rock.nv, s->p.obstacle.nf = s->rock.nf;
    s->p.obstacle.pos = s->rock.pos, s->p.obstacle.tri = s->rock.tri;
  } else {
    SESSILE_CHECK(q->obstacle_adhesion == 0 && q->obstacle_friction == 0, SESSILE_ERR_USAGE,
                  "%s: obstacle_adhesion and obstacle_friction act on a rock, and the model has none", where);
  }
  const sessile_sds_param *att = sessile_sds_model_param_find(m, "attractor");
  if (att) {
    SESSILE_CHECK(att->nvalues == 4, SESSILE_ERR_USAGE, "%s:%d: attractor needs 4 values: x y z strength", where,
                  att->line);
    memcpy(s->attractor, att->values, sizeof s->attractor);
    s->p.nattract = 1, s->p.attract_pos = s->attractor, s->p.k_attract = att->values[3];
  }
  return SESSILE_OK;
}

/* Tips: the surface cell farthest along each tip direction from the
 * centroid (ties to the lower index) gets tip = 1, and the attraction point
 * pulls the tips. */
sessile_status sds_mark_tips(sds_sim *s, const char *where) {
  sessile_sds *o = &s->o;
  int nt = sessile_sds_model_ntips(s->model);
  if (nt == 0) return SESSILE_OK;
  SESSILE_CHECK(s->tip_state >= 0, SESSILE_ERR_USAGE, "%s: the model names tips but has no 'state tip'", where);
  double cen[3] = {0, 0, 0};
  for (uint32_t c = 0; c < o->ncells; c++)
    for (int k = 0; k < 3; k++) cen[k] += o->x[3 * (size_t)c + k] / o->ncells;
  for (int i = 0; i < nt; i++) {
    const double *d = sessile_sds_model_tip(s->model, i);
    double best = -INFINITY;
    uint32_t bc = UINT32_MAX;
    for (uint32_t c = 0; c < o->ncells; c++) {
      if (!o->surface[c]) continue;
      double q[3], l = 0, dot = 0;
      for (int k = 0; k < 3; k++) q[k] = o->x[3 * (size_t)c + k] - cen[k], l += q[k] * q[k];
      l = sqrt(l);
      for (int k = 0; k < 3; k++) dot += q[k] * d[k];
      if (l > 0 && dot / l > best) best = dot / l, bc = c;
    }
    SESSILE_CHECK(bc != UINT32_MAX, SESSILE_ERR_USAGE, "%s: no surface cell for tip %d", where, i + 1);
    o->state[(size_t)bc * o->nstate + (uint32_t)s->tip_state] = 1;
    if (s->p.nattract) o->attract[bc] = 0;
  }
  return SESSILE_OK;
}

/* §3.6 automated: a tip with no interior cell below it gets one by dividing
 * the cell the check names, inward. */
sessile_status sds_cells_below_tips(sds_sim *s) {
  sessile_sds *o = &s->o;
  sessile_morph_cells cells = sds_cells_of(s);
  sessile_sds_tip_check *chk = NULL;
  int n = 0;
  SESSILE_CALL(sessile_sds_tips_below(&cells, o->surface, NULL, o->state, (int)o->nstate, s->tip_state, 0.7, &chk, &n));
  sessile_status st = SESSILE_OK;
  for (int i = 0; i < n && st == SESSILE_OK; i++) {
    if (chk[i].below >= 0) continue;
    st = sds_divide(s, (uint32_t)chk[i].split, chk[i].inward);
    if (st == SESSILE_OK) {
      /* the daughter that went inside is not a tip */
      uint32_t b = s->o.ncells - 1;
      s->o.state[(size_t)b * s->o.nstate + (uint32_t)s->tip_state] = 0;
      s->o.attract[b] = -1;
      st = sds_neighbours(s);
    }
  }
  free(chk);
  s->st->divisions = 0, s->div_interval = 0; /* set-up, not growth */
  return st;
}

/* Everything about the model that needs no device: the text, the physics
 * keys, the starting sphere, the run's length. */
sessile_status sds_check_model(sds_sim *s, const char *where, const sessile_sds_run_params *params, int *level,
                                  double *radius) {
  SESSILE_CALL(sessile_sds_model_parse(s->text, where, &s->model));
  if (params) {
    s->prm = *params;
    SESSILE_CALL(sessile_params_check(&sessile_sds_run_param_table, &s->prm));
  } else
    SESSILE_CALL(sessile_sds_run_params_of_model(s->text, where, &s->prm));
  SESSILE_CALL(read_physics(s, where));
  SESSILE_CHECK(s->prm.axial_stiffness == 1 || sessile_sds_model_axis(s->model) >= 0, SESSILE_ERR_USAGE,
                "%s: axial_stiffness %g needs a morphogen declared axis=1 (its gradient is the axis)", where,
                s->prm.axial_stiffness);
  SESSILE_CHECK(s->prm.axial_growth == 0 || sessile_sds_model_axis(s->model) >= 0, SESSILE_ERR_USAGE,
                "%s: axial_growth %g needs a morphogen declared axis=1 (its gradient is the axis)", where,
                s->prm.axial_growth);
  SESSILE_CHECK(s->prm.convergent_extension == 0 || (sessile_sds_model_axis(s->model) >= 0 &&
                                                     sessile_sds_model_state_index(s->model, SDS_STATE_EXTENDING) >= 0),
                SESSILE_ERR_USAGE,
                "%s: convergent_extension %g needs a morphogen declared axis=1 (its gradient is the axis) and a "
                "state `extending` (the rules set it where the tissue extends)", where, s->prm.convergent_extension);
  *level = s->prm.sphere_subdivisions + 1;
  *radius = s->prm.sphere_radius;
  double t_end = sds_param1(s->model, "t_end", 100), frames = sds_param1(s->model, "frames", 20);
  SESSILE_CHECK(t_end >= 0 && t_end <= 1e9 && frames >= 1 && frames <= 100000 && frames == floor(frames),
                SESSILE_ERR_USAGE, "%s: t_end must be in [0, 1e9] and frames an integer in 1..100000", where);
  return SESSILE_OK;
}

sessile_status sds_run_length(const sessile_sds_model *m, double t_end_in, int frames_in, double *t_end, int *frames) {
  *t_end = t_end_in >= 0 ? t_end_in : sds_param1(m, "t_end", 100);
  *frames = frames_in > 0 ? frames_in : (int)sds_param1(m, "frames", 20);
  SESSILE_CHECK(*t_end >= 0 && isfinite(*t_end) && *frames >= 1 && *frames <= 100000, SESSILE_ERR_USAGE,
                "sds: t_end must be >= 0 and frames in 1..100000");
  return SESSILE_OK;
}

/* A realisation of the starting sphere (the model's start_jitter J, docs/
 * sds_rules.md): each vertex moved along its radius by J x the mean edge
 * length x a normal deviate clipped to +-3, drawn from the seed's own stream
 * (2; the division directions draw from 1).  The sphere stays star-shaped
 * about its centre for J <= 0.2, so TetGen meshes it. */
static double mean_edge(const sessile_surface *srf) {
  double len = 0;
  for (uint32_t f = 0; f < srf->nf; f++)
    for (int k = 0; k < 3; k++) {
      const double *a = srf->pos + 3 * (size_t)srf->tri[3 * (size_t)f + k];
      const double *b = srf->pos + 3 * (size_t)srf->tri[3 * (size_t)f + (k + 1) % 3];
      len += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
  return len / (srf->nf ? 3.0 * srf->nf : 1.0);
}

static void jitter_sphere(sessile_surface *srf, double jitter, uint64_t seed) {
  double len = mean_edge(srf), c[3] = {0, 0, 0};
  for (uint32_t v = 0; v < srf->nv; v++)
    for (int k = 0; k < 3; k++) c[k] += srf->pos[3 * (size_t)v + k] / srf->nv;
  uint64_t rng = sessile_rng_stream(seed, 2);
  for (uint32_t v = 0; v < srf->nv; v++) {
    double *x = srf->pos + 3 * (size_t)v, d[3], n = 0;
    for (int k = 0; k < 3; k++) d[k] = x[k] - c[k], n += d[k] * d[k];
    n = sqrt(n);
    double z = fmax(-3.0, fmin(3.0, sessile_rng_normal(&rng)));
    if (n > 0)
      for (int k = 0; k < 3; k++) x[k] += jitter * len * z * d[k] / n;
  }
}

/* A realisation of the symmetric ball: its surface cells moved along their
 * radii as jitter_sphere moves the icosphere's vertices (h the edge, the
 * same stream), its tets kept, so that every realisation is the exact
 * start's complex (meshing the moved sphere anew gave starts of 182-228
 * cells at frame 0 where the exact one has 179, docs/sds.md).  A move that turns a
 * tet over is refused: the import would orient it the other way. */
static sessile_status jitter_ball(sds_sim *s, const char *where, int sym, double radius, double h, double jitter,
                                  uint32_t nm, uint32_t ns) {
  const double c0[3] = {0, 0, 0};
  double *x = NULL;
  uint32_t n = 0, nt = 0, *tet = NULL;
  SESSILE_CALL(sessile_sds_symmetric_ball_tets(sym, radius, h, c0, &x, &n, &tet, &nt));
  double *v0 = malloc((size_t)nt * sizeof *v0);
  sessile_status st = v0 ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory", where);
  for (uint32_t t = 0; st == SESSILE_OK && t < nt; t++) {
    const uint32_t *q = tet + 4 * (size_t)t;
    v0[t] = sds_vol4(x + 3 * (size_t)q[0], x + 3 * (size_t)q[1], x + 3 * (size_t)q[2], x + 3 * (size_t)q[3]);
  }
  uint64_t rng = sessile_rng_stream(s->seed, 2);
  for (uint32_t c = 0; st == SESSILE_OK && c < n; c++) {
    double *p = x + 3 * (size_t)c, d = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (d < radius * (1 - 1e-9)) continue; /* inside: kept */
    double z = fmax(-3.0, fmin(3.0, sessile_rng_normal(&rng)));
    for (int k = 0; k < 3; k++) p[k] += jitter * h * z * p[k] / d;
  }
  for (uint32_t t = 0; st == SESSILE_OK && t < nt; t++) {
    const uint32_t *q = tet + 4 * (size_t)t;
    double v = sds_vol4(x + 3 * (size_t)q[0], x + 3 * (size_t)q[1], x + 3 * (size_t)q[2], x + 3 * (size_t)q[3]);
    if (!(v * v0[t] > 0 && fabs(v) > 0.05 * fabs(v0[t])))
      st = sessile_error_set(SESSILE_ERR_USAGE, "%s: start_jitter %g flattens or turns over a tet of the symmetric "
                             "start (seed %llu); a smaller start_jitter keeps them", where, jitter,
                             (unsigned long long)s->seed);
  }
  if (st == SESSILE_OK) st = sessile_sds_from_tets(x, n, tet, nt, nm, ns, s->density, &s->o);
  free(v0), free(x), free(tet);
  return st;
}

/* The starting organism: the model's `surface = "FILE.ply"` (relative to
 * the model file's folder), or the icosphere (sphere_radius,
 * sphere_subdivisions), through TetGen.  A surface that is not closed and
 * consistently oriented, or that TetGen rejects, is a usage error. */
sessile_status sds_import_organism(sds_sim *s, const char *where, int level, double radius) {
  uint32_t nm = (uint32_t)sessile_sds_model_nmorph(s->model), ns = (uint32_t)sessile_sds_model_nstate(s->model);
  const sessile_sds_param *sf = sessile_sds_model_param_find(s->model, "surface");
  double jitter = s->prm.start_jitter;
  SESSILE_CHECK(!(sf && jitter > 0), SESSILE_ERR_USAGE,
                "%s: start_jitter moves the starting sphere's vertices; a model with its own surface has none to move",
                where);
  int sym = s->prm.start_symmetry;
  SESSILE_CHECK(sym != 1, SESSILE_ERR_USAGE, "%s: start_symmetry is 0 (the icosphere) or a number of mirrors >= 2",
                where);
  SESSILE_CHECK(!(sf && sym), SESSILE_ERR_USAGE, "%s: start_symmetry shapes the starting ball; a model with its own "
                "surface has none", where);
  if (!sf) {
    const double c0[3] = {0, 0, 0};
    if (jitter == 0 && sym == 0) return sessile_sds_from_icosphere(level, radius, c0, 0, nm, ns, s->density, &s->o);
    sessile_surface srf = {0};
    SESSILE_CALL(sessile_surface_icosphere(level, radius, c0, &srf));
    if (sym) {
      /* the symmetric ball at the icosphere's resolution: edges as long as its mean edge */
      double h = mean_edge(&srf);
      sessile_surface_free(&srf);
      if (jitter == 0) return sessile_sds_symmetric_ball(sym, radius, h, c0, nm, ns, s->density, &s->o);
      return jitter_ball(s, where, sym, radius, h, jitter, nm, ns);
    }
    jitter_sphere(&srf, jitter, s->seed);
    sessile_status st = sessile_sds_from_surface(&srf, NULL, 0, nm, ns, s->density, &s->o);
    sessile_surface_free(&srf);
    return st;
  }
  SESSILE_CHECK(sf->nvalues == 0 && sf->text[0], SESSILE_ERR_USAGE, "%s:%d: surface names a PLY file: surface = \"FILE.ply\"",
                where, sf->line);
  char path[4096];
  const char *slash = strrchr(where, '/');
  if (sf->text[0] == '/' || !slash) snprintf(path, sizeof path, "%s", sf->text);
  else snprintf(path, sizeof path, "%.*s/%s", (int)(slash - where), where, sf->text);
  sessile_surface srf;
  SESSILE_CALL(sds_read_surface_ply(path, &srf));
  /* closed and consistently oriented (any genus: the check's Euler number is
   * the surface's own, V - 3F/2 + F) */
  sessile_status st = sessile_surface_check(&srf, (int)srf.nv - (int)(srf.nf / 2), 0);
  if (st != SESSILE_OK)
    st = sessile_error_set(SESSILE_ERR_USAGE, "%s:%d: surface '%s' is not a closed, consistently oriented surface: %s",
                           where, sf->line, path, sessile_error_message());
  if (st == SESSILE_OK) {
    st = sessile_sds_from_surface(&srf, NULL, 0, nm, ns, s->density, &s->o);
    if (st == SESSILE_ERR_USAGE)
      st = sessile_error_set(st, "%s:%d: surface '%s': %s", where, sf->line, path, sessile_error_message());
  }
  sessile_surface_free(&srf);
  return st;
}

sessile_status sessile_sds_model_check(const char *text, const char *name, const sessile_sds_run_params *params,
                                       double t_end, uint64_t max_steps) {
  sds_sim s;
  memset(&s, 0, sizeof s);
  s.text = text, s.seed = 1; /* the estimate: any realisation of the start will do */
  int level;
  double radius;
  const char *where = name ? name : "model";
  sessile_status st = sds_check_model(&s, where, params, &level, &radius);
  if (st == SESSILE_OK) {
    /* the work it would take: steps at the integrator's stable step of the
     * starting organism (growth and division only make steps smaller) */
    st = sds_import_organism(&s, where, level, radius);
    if (st == SESSILE_OK) {
      if (t_end < 0) t_end = sds_param1(s.model, "t_end", 100);
      double sd = sessile_sds_stable_dt(&s.o, &s.p);
      double dt = fmin(s.p.stable_safety * sd, s.p.dt_max);
      double steps = dt > 0 ? t_end / dt : INFINITY;
      if (sd == 0)
        st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory for the stable step's bound", where);
      else if (!(steps <= (double)max_steps))
        st = sessile_error_set(SESSILE_ERR_USAGE,
                               "%s: reaching t = %g needs at least %.3g steps (stable step %.3g at the start), more "
                               "than --max-steps %llu: soften the springs or shorten the run",
                               where, t_end, steps, dt, (unsigned long long)max_steps);
    }
  }
  sessile_sds_model_destroy(s.model);
  sessile_surface_free(&s.rock);
  sessile_sds_free(&s.o);
  return st;
}

/* The starting organism's centroid and size (its largest distance from the
 * centroid): the blow-up test's yardstick. */
void sds_measure_start(sds_sim *s) {
  const sessile_sds *o = &s->o;
  for (int k = 0; k < 3; k++) s->c0[k] = 0;
  for (uint32_t c = 0; c < o->ncells; c++)
    for (int k = 0; k < 3; k++) s->c0[k] += o->x[3 * (size_t)c + k] / o->ncells;
  s->size0 = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (o->x[3 * (size_t)c + k] - s->c0[k]) * (o->x[3 * (size_t)c + k] - s->c0[k]);
    s->size0 = fmax(s->size0, sqrt(d2));
  }
}
