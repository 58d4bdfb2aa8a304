/* A batch of steps on the device (sessile_sds_gpu_batch, docs/sds.md "The
 * loop on the device") against the host-driven step (sessile_sds_gpu_advance,
 * one step per call): the same steps, times and states bit for bit (fp64),
 * the same inverted tets where a batch stops for them, a batch that stops at
 * the first step ending at or past its stop time; and the contact lists with
 * their skin against lists built fresh at every step: the same forces.
 * Fused kernels (sessile_sds_gpu_fuse) in the batch and not in the host-driven
 * step, and the other way round: still the same bits.
 * The scenes: a ball dropped on a rock (contacts, the lists' skin, steps
 * max_move undoes) and a soft ball crushed by gravity (inverted tets). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "collide_scenes.h"
#include "sessile/sds/sds_batch.h"

typedef struct counts { uint32_t batches, rejects, lists, inverted, steps; } counts;

static int same(const double *a, const double *b, size_t n) { return !memcmp(a, b, n * sizeof *a); }

/* Runs `total` accepted steps both ways from o, batches of k (their steps
 * checked in dispatches of their own when split; fused kernels as `fuse`
 * says, the host-driven step the other way when it says always or never);
 * every mismatch counts in *bad (printed once; on fp64 the first ends the
 * run). */
static counts compare(sessile_gpu *g, const sessile_sds *o0, const sessile_sds_params *p, uint32_t total,
                      uint32_t k, int split, sessile_sds_fuse fuse, int *bad) {
  counts n = {0};
  sessile_sds a = {0}, b = {0};
  t_must("copy", sessile_sds_copy(o0, &a));
  t_must("copy", sessile_sds_copy(o0, &b));
  sessile_sds_gpu *ga = NULL, *gb = NULL;
  t_must("gpu a", sessile_sds_gpu_create(g, &a, p, &ga));
  t_must("gpu b", sessile_sds_gpu_create(g, &b, p, &gb));
  sessile_sds_gpu_batch_split(gb, split);
  sessile_sds_gpu_fuse(gb, fuse);
  sessile_sds_gpu_fuse(ga, fuse == SESSILE_SDS_FUSE_NEVER    ? SESSILE_SDS_FUSE_ALWAYS
                           : fuse == SESSILE_SDS_FUSE_ALWAYS ? SESSILE_SDS_FUSE_NEVER
                                                             : SESSILE_SDS_FUSE_AUTO);
  double dta = p->dt, ta = 0;
  sessile_sds_batch bt = {.t_stop = INFINITY, .time = 0, .dt = p->dt};
  double *log = t_dalloc(2 * (size_t)k);
  bt.log = log;
  int exact = sessile_gpu_info_of(g)->precision == 64; /* fp32: the control in float, not the host's bits */
  while (n.steps < total && !(exact && *bad)) {
    bt.steps = k;
    t_must("batch", sessile_sds_gpu_batch(gb, &bt));
    n.batches++;
    n.rejects += (bt.events & SESSILE_SDS_EV_REJECT) != 0;
    n.lists += (bt.events & SESSILE_SDS_EV_LISTS) != 0;
    for (uint32_t j = 0; j < bt.done; j++) {
      double el = 0;
      t_must("advance", sessile_sds_gpu_advance(ga, 1, &dta, &el));
      ta += el;
      if (el != log[2 * j] || ta != log[2 * j + 1]) {
        if (!(*bad)++)
          printf("step %u: host-driven dt %.17g t %.17g, batch dt %.17g t %.17g\n", n.steps + j, el, ta, log[2 * j],
                 log[2 * j + 1]);
      }
      uint32_t *inv = NULL, ni = 0;
      t_must("inverted a", sessile_sds_gpu_inverted(ga, &inv, &ni));
      int last = j + 1 == bt.done;
      /* an inverted tet stops the batch after its step, and only then */
      if ((ni > 0) != (last && (bt.events & SESSILE_SDS_EV_INVERTED))) {
        if (!(*bad)++) printf("step %u: %u inverted tets, batch events %u\n", n.steps + j, ni, bt.events);
      }
      if (last && ni) {
        uint32_t *invb = NULL, nb = 0;
        t_must("inverted b", sessile_sds_gpu_inverted(gb, &invb, &nb));
        if (nb != ni || memcmp(inv, invb, ni * sizeof *inv)) (*bad)++;
        free(invb);
        n.inverted++;
      }
      free(inv);
    }
    n.steps += bt.done;
    t_must("download a", sessile_sds_gpu_download(ga, &a));
    t_must("download b", sessile_sds_gpu_download(gb, &b));
    if (!same(a.x, b.x, 3 * (size_t)a.ncells) || !same(a.v, b.v, 3 * (size_t)a.ncells)) {
      if (!(*bad)++) printf("after %u steps: the states differ\n", n.steps);
    }
    /* the next step asked: the host's proposal, or half the undone step */
    if (!(bt.events & SESSILE_SDS_EV_REJECT) && dta != bt.dt) {
      if (!(*bad)++) printf("after %u steps: next dt %.17g against %.17g\n", n.steps, dta, bt.dt);
    }
  }
  free(log);
  sessile_sds_gpu_destroy(ga), sessile_sds_gpu_destroy(gb);
  sessile_sds_free(&a), sessile_sds_free(&b);
  printf("%s, fused kernels %s: %u steps in %u batches of at most %u: %u stopped by an undone step, %u by stale lists, "
         "%u by inverted tets\n",
         split ? "split checks" : "folded checks", fuse == SESSILE_SDS_FUSE_NEVER ? "never" : fuse ? "always" : "auto", n.steps, n.batches, k, n.rejects, n.lists, n.inverted);
  return n;
}

/* A stop time inside a batch: it ends after the first step at or past it
 * (batches until then, as the loop's frames). */
static void stop_time(sessile_gpu *g, const sessile_sds *o, const sessile_sds_params *p) {
  double ends[64], log[2 * 64];
  uint32_t n = 0;
  for (int pass = 0; pass < 2; pass++) {
    sessile_sds_gpu *s = NULL;
    t_must("gpu", sessile_sds_gpu_create(g, o, p, &s));
    double t_stop = pass ? 0.5 * (ends[n / 2 - 1] + ends[n / 2]) : INFINITY; /* inside step n / 2's span */
    sessile_sds_batch bt = {.t_stop = t_stop, .dt = p->dt, .log = log};
    uint32_t m = 0;
    while (m < 32 && !(bt.events & SESSILE_SDS_EV_TIME)) {
      bt.steps = 32 - m;
      t_must("batch", sessile_sds_gpu_batch(s, &bt));
      for (uint32_t j = 0; j < bt.done; j++) ends[m + j] = log[2 * j + 1];
      m += bt.done;
    }
    sessile_sds_gpu_destroy(s);
    if (!pass) {
      n = m;
      continue;
    }
    printf("stop time %.9g: the batches ran %u steps, to t = %.9g\n", t_stop, m, bt.time);
    t_true("a stop time inside a batch: it stops with EV_TIME", (bt.events & SESSILE_SDS_EV_TIME) != 0);
    t_true("after the first step ending at or past it", m == n / 2 + 1 && bt.time == ends[n / 2]);
  }
}

/* The lists kept with their skin give the forces of lists built fresh at
 * every step (the fresh device's lists invalidated before each evaluation). */
static void skin(sessile_gpu *g, const sessile_sds *o0, const sessile_sds_params *p) {
  sessile_sds o = {0};
  t_must("copy", sessile_sds_copy(o0, &o));
  sessile_sds_gpu *s = NULL, *f = NULL;
  t_must("gpu", sessile_sds_gpu_create(g, &o, p, &s));
  t_must("gpu fresh", sessile_sds_gpu_create(g, &o, p, &f));
  double *fa = t_dalloc(3 * (size_t)o.ncells), *fb = t_dalloc(3 * (size_t)o.ncells), dt = p->dt;
  int differ = 0;
  uint64_t b0, part;
  sessile_sds_gpu_list_builds(s, &b0, &part);
  for (int k = 0; k < 150; k++) {
    t_must("advance", sessile_sds_gpu_advance(s, 1, &dt, NULL));
    t_must("download", sessile_sds_gpu_download(s, &o));
    t_must("forces", sessile_sds_gpu_forces(s, 1, fa));
    t_must("upload fresh", sessile_sds_gpu_upload(f, &o));
    sessile_sds_gpu_set_reads(f, 0); /* the lists built anew at the next evaluation */
    t_must("forces fresh", sessile_sds_gpu_forces(f, 1, fb));
    differ += !same(fa, fb, 3 * (size_t)o.ncells);
  }
  uint64_t b1;
  sessile_sds_gpu_list_builds(s, &b1, &part);
  printf("skin: %llu builds of the kept lists in 150 steps\n", (unsigned long long)(b1 - b0));
  t_true("the kept lists' forces are those of fresh lists at every one of 150 steps", differ == 0);
  t_true("the kept lists were built fewer times than the steps, more than once",
         b1 - b0 > 1 && b1 - b0 < 150);
  free(fa), free(fb);
  sessile_sds_gpu_destroy(s), sessile_sds_gpu_destroy(f);
  sessile_sds_free(&o);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  int fp64 = sessile_gpu_info_of(g)->precision == 64;
  sessile_sds o = {0};
  sessile_surface rock = {0};
  ball_and_rock(2, 0.5, 0.05, 0.62, &o, &rock);
  for (uint32_t c = 0; c < o.ncells; c++) o.v[3 * c + 2] = -4.0; /* thrown down */
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.k_edge = 300, p.k_vol = 600, p.damp_visc = 4, p.damp_vol = 0.01, p.k_wall = 3000;
  p.dt = p.dt_max; /* a first step max_move undoes */
  p.max_move = 0.02;
  p.obstacle.nv = rock.nv, p.obstacle.nf = rock.nf, p.obstacle.pos = rock.pos, p.obstacle.tri = rock.tri;
  int bad = 0;
  counts n = compare(g, &o, &p, 400, 64, 0, SESSILE_SDS_FUSE_AUTO, &bad);
  if (fp64) t_true("ball on a rock: batches give the host-driven steps bit for bit", bad == 0);
  t_true("the scene undoes steps and lets the lists go stale", n.rejects > 0 && n.lists > 0);
  bad = 0;
  n = compare(g, &o, &p, 200, 64, 1, SESSILE_SDS_FUSE_AUTO, &bad);
  if (fp64) t_true("ball on a rock, split checks: the host-driven steps bit for bit", bad == 0);
  t_true("the scene undoes steps and lets the lists go stale", n.rejects > 0 && n.lists > 0);
  bad = 0;
  n = compare(g, &o, &p, 200, 64, 0, SESSILE_SDS_FUSE_NEVER, &bad);
  if (fp64) t_true("ball on a rock, batches without fused kernels: the fused host-driven steps bit for bit", bad == 0);
  t_true("the scene undoes steps and lets the lists go stale", n.rejects > 0 && n.lists > 0);
  bad = 0;
  n = compare(g, &o, &p, 200, 64, 1, SESSILE_SDS_FUSE_ALWAYS, &bad);
  if (fp64) t_true("ball on a rock, split checks, fused: the unfused host-driven steps bit for bit", bad == 0);
  stop_time(g, &o, &p);
  skin(g, &o, &p);
  /* soft and heavy: the default springs under gravity 10 crush it */
  sessile_sds_params q;
  sessile_sds_params_default(&q);
  q.obstacle = p.obstacle;
  bad = 0;
  n = compare(g, &o, &q, 120, 64, 0, SESSILE_SDS_FUSE_AUTO, &bad);
  if (fp64) t_true("a crushed ball: batches give the host-driven steps bit for bit", bad == 0);
  t_true("the scene inverts tets", n.inverted > 0);
  bad = 0;
  n = compare(g, &o, &q, 60, 64, 1, SESSILE_SDS_FUSE_AUTO, &bad);
  if (fp64) t_true("a crushed ball, split checks: the host-driven steps bit for bit", bad == 0);
  t_true("the scene inverts tets", n.inverted > 0);
  bad = 0;
  n = compare(g, &o, &q, 120, 64, 0, SESSILE_SDS_FUSE_NEVER, &bad);
  if (fp64) t_true("a crushed ball without fused kernels: the fused host-driven steps bit for bit", bad == 0);
  t_true("the scene inverts tets", n.inverted > 0);
  sessile_sds_free(&o);
  sessile_surface_free(&rock);
  return t_finish(g);
}
