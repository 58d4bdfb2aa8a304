/* The shipped process models (host/sds/models/ *.sds) parse, and hold what
 * docs/sds_rules.md says: the limb bud rules r1-r3 (r4, the stripe timer,
 * the bud morphogen where the figure needs them), the authors' physics
 * constants as plain keys, and the growing-tip directions. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "sessile/sds/sds_process.h"
#include "testutil.h"

static char root[512];

static sessile_sds_model *load(const char *name) {
  char path[700];
  snprintf(path, sizeof path, "%s/host/sds/models/%s", root, name);
  sessile_sds_model *m = NULL;
  sessile_status s = sessile_sds_model_load(path, &m);
  t_true(name, s == SESSILE_OK);
  if (s != SESSILE_OK) printf("  %s\n", sessile_error_message());
  return m;
}

static double param(const sessile_sds_model *m, const char *k, int i) {
  const sessile_sds_param *p = sessile_sds_model_param_find(m, k);
  return p && p->nvalues > i ? p->values[i] : NAN;
}

static int has_rule_core(const sessile_sds_model *m) {
  return sessile_sds_model_morph_index(m, "phi") >= 0 && sessile_sds_model_state_index(m, "tip") >= 0 &&
         sessile_sds_model_nrules(m) >= 3;
}

int main(void) {
  /* the repository root, from this file's path (tests/sds/test_rules_models.c) */
  snprintf(root, sizeof root, "%s", __FILE__);
  char *cut = strstr(root, "/tests/sds/");
  if (cut) *cut = 0;
  const char *names[] = {"limb.sds",   "six_limbs_box.sds", "rock.sds",
                         "attractor.sds", "budded.sds", "limb_extension.sds", "rock_stripes.sds"};
  const int tips[] = {1, 6, 6, 6, 6, 1, 6};
  for (int i = 0; i < 7; i++) {
    sessile_sds_model *m = load(names[i]);
    if (!m) continue;
    char what[200];
    snprintf(what, sizeof what, "%s: phi, tip and at least r1-r3", names[i]);
    t_true(what, has_rule_core(m));
    snprintf(what, sizeof what, "%s: %d growing tips", names[i], tips[i]);
    t_true(what, sessile_sds_model_ntips(m) == tips[i]);
    snprintf(what, sizeof what, "%s: edge 1, volume 2, damping 0.001, surface 1 (the prototype's)", names[i]);
    t_true(what, param(m, "edge_stiffness", 0) == 1 && param(m, "volume_stiffness", 0) == 2 &&
                     param(m, "damping", 0) == 0.001 && param(m, "surface_multiplier", 0) == 1);
    double tl = 0;
    for (int t = 0; t < sessile_sds_model_ntips(m); t++) {
      const double *d = sessile_sds_model_tip(m, t);
      tl = fmax(tl, fabs(sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - 1));
    }
    snprintf(what, sizeof what, "%s: tip directions are unit", names[i]);
    t_check(what, tl, 1e-15);
    sessile_morph_coef co = sessile_sds_model_coef(m);
    snprintf(what, sizeof what, "%s: coefficient table matches the morphogen count", names[i]);
    t_true(what, co.nmorph == sessile_sds_model_nmorph(m) && co.diffusion && co.decay && co.capped);
    if (i == 0) {
      t_true("limb: exactly one morphogen, two states (tip, birth_radius), three rules",
             sessile_sds_model_nmorph(m) == 1 && sessile_sds_model_nstate(m) == 2 && sessile_sds_model_nrules(m) == 3);
      t_true("limb: phi diffusion 0.05, decay 0.3, capped", co.diffusion[0] == 0.05 && co.decay[0] == 0.3 &&
                                                                 co.capped[0] == 1);
    }
    if (i == 1) t_true("six limbs: a box of 6 numbers", sessile_sds_model_param_find(m, "box")->nvalues == 6);
    if (i == 2) {
      int k = sessile_sds_model_morph_index(m, "clock");
      t_true("rock: a rock of 4 numbers", sessile_sds_model_param_find(m, "rock")->nvalues == 4);
      t_true("rock: r4 present (4 limb rules + 4 stripe rules)", sessile_sds_model_nrules(m) == 8);
      t_true("rock: the clock is an uncapped, non-diffusing timer starting at 1",
             k >= 0 && co.diffusion[k] == 0 && co.capped[k] == 0 && sessile_sds_model_morph_start(m, k) == 1);
    }
    if (i == 3) t_true("attractor: point and strength", sessile_sds_model_param_find(m, "attractor")->nvalues == 4);
    if (i == 4) t_true("budded: a bud morphogen", sessile_sds_model_morph_index(m, "bud") >= 0);
    if (i == 5)
      t_true("limb_extension: phi the axis, a state extending",
             sessile_sds_model_axis(m) == sessile_sds_model_morph_index(m, "phi") &&
                 sessile_sds_model_state_index(m, "extending") >= 0);
    if (i == 6) {
      /* rock.sds's rules with the timer's period doubled (docs/sds_rules.md) */
      int k = sessile_sds_model_morph_index(m, "clock");
      t_true("rock_stripes: a rock, rock.sds's eight rules", sessile_sds_model_param_find(m, "rock")->nvalues == 4 &&
                                                                  sessile_sds_model_nrules(m) == 8);
      t_true("rock_stripes: the clock decays at 0.015 (half rock.sds's 0.03), uncapped, from 1",
             k >= 0 && co.decay[k] == 0.015 && co.capped[k] == 0 && sessile_sds_model_morph_start(m, k) == 1);
    }
    sessile_sds_model_destroy(m);
  }
  return t_finish(NULL);
}
