/* The rules' bytecode (host/sds/rules_compile.c, rules_vm.c) against the
 * host's muparser evaluator: for every shipped model and for a model of
 * expressions that exercises each operator, function and muparser
 * optimisation the compiler rebuilds, on seeded random cell states, the
 * actions (growth, sources, sets, divisions) must be the same doubles, bit
 * for bit.  Refusals name the rule.  Then the kernel
 * (shaders/sds/rules_vm.comp, fp64, under the validation layer) against the
 * host's evaluation and actions on the same models: bit for bit, masses
 * included (sessile_sds_mass), a batch's second step stopped by a division,
 * 40 steps of rules, morphogen step and actions on a fixed lattice the same
 * bits every step (limb, rock, budded), and a model with exp() refused on
 * the device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rules_vm_cells.h"
#include "sds/sds_gpu_rules.h"
#include "sds_kernels.h"
#include "sessile/rng.h"
#include "testutil.h"

/* ulps between two doubles of one sign */
static double ulps(double a, double b) {
  int64_t x, y;
  memcpy(&x, &a, 8), memcpy(&y, &b, 8);
  return (double)llabs(x - y);
}

/* A short run on the fixed lattice: each step the rules, the morphogen step
 * (sessile_morph_step on the host, from the sources each side computed) and
 * the actions, by the host and by the kernel; radii, amounts, states and
 * division requests must stay the same bits every step. */
/* The kernel under test: the generated one or the interpreter
 * (sessile_sds_rules_kernel); every device check runs with both. */
static int kind;
static const char *const kind_names[] = {"generated", "bytecode"};

static void device_run(sessile_gpu *g, const sessile_sds_model *m, const char *name, int steps) {
  rvm_cells H = rvm_cells_make(m, 9, 8, 7, 77), D = rvm_cells_make(m, 9, 8, 7, 77);
  sessile_morph_cells ch = rvm_morph_cells(&H), cd = rvm_morph_cells(&D); /* radii: each side's own */
  sessile_morph_coef co = sessile_sds_model_coef(m);
  size_t n = (size_t)H.n, nm = (size_t)H.nm, ns = (size_t)H.ns;
  double dt = 0.5 * sessile_morph_dt_max(&ch, &co), *tmp = t_dalloc(n * nm + 1), *src = t_dalloc(n * nm + 1);
  double *rm = t_dalloc(2 * n), *req = t_dalloc(SDS_REQ * n);
  sds_gpu_rules *r = NULL;
  sessile_cmd *cmd = NULL;
  t_must("the rules kernel", sds_gpu_rules_create_kind(g, m, kind, &r));
  t_must("a command buffer", sessile_cmd_create(g, &cmd));
  t_must("cells up", sds_gpu_rules_set_cells(r, &ch, D.phi, D.state, 1.0));
  int ok = 1, same_steps = 0;
  size_t divisions = 0;
  for (int k = 0; k < steps && ok; k++) {
    double time = k * dt;
    sessile_sds_actions a = {0};
    t_must("the host's evaluation", sessile_sds_rules_eval(m, &ch, H.phi, H.state, time, &a));
    t_must("the host's morphogen step", sessile_morph_step(&ch, &co, H.phi, a.produce, dt, tmp, NULL));
    memcpy(H.phi, tmp, n * nm * sizeof *tmp);
    sessile_sds_actions_apply(m, &a, dt, H.r, H.phi, H.state);
    uint32_t ev[SDS_EV_COUNT], nreq = 0;
    t_must("record", sessile_cmd_begin(cmd));
    t_must("record", sds_gpu_rules_record_clear(r, cmd));
    t_must("record", sds_gpu_rules_record_eval(r, cmd, NULL, NULL, time));
    t_must("record", sessile_cmd_end(cmd));
    t_must("run", sessile_cmd_submit_wait(cmd));
    t_must("events", sds_gpu_rules_read_events(r, ev, req, &nreq));
    ok = nreq == a.ndivides;
    for (uint32_t i = 0; ok && i < nreq; i++)
      ok =
          req[SDS_REQ * i] == a.divides[i].cell && !memcmp(&req[SDS_REQ * i + 2], a.divides[i].dir, 3 * sizeof(double));
    divisions += nreq;
    sessile_buffer *bphi = sds_gpu_rules_buffer(r, SDS_RULES_PHI);
    if (nm) {
      t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_SRC), 0, src, n * nm));
      t_must("down", sessile_buffer_download_reals(bphi, 0, D.phi, n * nm));
      t_must("the device side's morphogen step", sessile_morph_step(&cd, &co, D.phi, src, dt, tmp, NULL));
      t_must("up", sessile_buffer_upload_reals(bphi, 0, tmp, n * nm));
    }
    t_must("record", sessile_cmd_begin(cmd));
    t_must("record", sds_gpu_rules_record_apply(r, cmd, NULL, NULL, dt));
    t_must("record", sessile_cmd_end(cmd));
    t_must("run", sessile_cmd_submit_wait(cmd));
    if (nm) t_must("down", sessile_buffer_download_reals(bphi, 0, D.phi, n * nm));
    if (ns) t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_STATE), 0, D.state, n * ns));
    t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_RM), 0, rm, 2 * n));
    for (size_t c = 0; c < n; c++) D.r[c] = rm[2 * c];
    ok = ok && !memcmp(D.r, H.r, n * sizeof *D.r) && (!nm || !memcmp(D.phi, H.phi, n * nm * sizeof *D.phi)) &&
         (!ns || !memcmp(D.state, H.state, n * ns * sizeof *D.state));
    same_steps += ok;
    sessile_sds_actions_free(&a);
  }
  char what[300];
  snprintf(what, sizeof what,
           "%s: %d steps of rules, morphogens and actions, host and kernel: the same radii, "
           "amounts, states and division requests every step (%d the same; %zu requests)",
           name, steps, same_steps, divisions);
  t_true(what, ok && same_steps == steps);
  free(tmp), free(src), free(rm), free(req);
  sessile_cmd_destroy(cmd);
  sds_gpu_rules_destroy(r);
  rvm_cells_free(&H), rvm_cells_free(&D);
}

/* The kernel against the host: mode 0 then mode 1 (no morphogen step
 * between) in one submission, against sessile_sds_rules_eval and
 * sessile_sds_actions_apply with the loop's masses; steps: 2 records a
 * second step in the same submission, which must do nothing when the first
 * asked for a division (the batch stops). */
static void device_check(sessile_gpu *g, const sessile_sds_model *m, const char *name, uint64_t seed, int steps) {
  rvm_cells C = rvm_cells_make(m, 9, 8, 7, seed);
  sessile_morph_cells cl = rvm_morph_cells(&C);
  const double density = 1.3, time = 2.5, dt = 0.125;
  sds_gpu_rules *r = NULL;
  sessile_cmd *cmd = NULL;
  t_must("the rules kernel", sds_gpu_rules_create_kind(g, m, kind, &r));
  t_must("a command buffer", sessile_cmd_create(g, &cmd));
  t_must("cells up", sds_gpu_rules_set_cells(r, &cl, C.phi, C.state, density));
  t_must("record", sessile_cmd_begin(cmd));
  t_must("record", sds_gpu_rules_record_clear(r, cmd));
  for (int s = 0; s < steps; s++) {
    t_must("record", sds_gpu_rules_record_eval(r, cmd, NULL, NULL, time));
    t_must("record", sds_gpu_rules_record_apply(r, cmd, NULL, NULL, dt));
  }
  t_must("record", sessile_cmd_end(cmd));
  t_must("run", sessile_cmd_submit_wait(cmd));
  size_t n = (size_t)C.n, nm = (size_t)C.nm, ns = (size_t)C.ns;
  double *src = t_dalloc(n * nm + 1), *phi = t_dalloc(n * nm + 1), *st = t_dalloc(n * ns + 1), *rm = t_dalloc(2 * n);
  double *req = t_dalloc(SDS_REQ * n);
  uint32_t ev[SDS_EV_COUNT], nreq = 0;
  t_must("events", sds_gpu_rules_read_events(r, ev, req, &nreq));
  if (nm) t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_SRC), 0, src, n * nm));
  if (nm) t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_PHI), 0, phi, n * nm));
  if (ns) t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_STATE), 0, st, n * ns));
  t_must("down", sessile_buffer_download_reals(sds_gpu_rules_buffer(r, SDS_RULES_RM), 0, rm, 2 * n));

  sessile_sds_actions a = {0};
  t_must("the host's evaluation", sessile_sds_rules_eval(m, &cl, C.phi, C.state, time, &a));
  int ok = nreq == a.ndivides && ev[SDS_EV_NREQ] == a.ndivides && (ev[SDS_EV_FLAGS] == (a.ndivides ? 1u : 0u));
  ok = ok && (!nm || !memcmp(src, a.produce, n * nm * sizeof *src));
  for (uint32_t i = 0; ok && i < nreq; i++)
    ok = req[SDS_REQ * i] == a.divides[i].cell && req[SDS_REQ * i + 1] == a.divides[i].rule &&
         !memcmp(&req[SDS_REQ * i + 2], a.divides[i].dir, 3 * sizeof(double));
  sessile_sds_actions_apply(m, &a, dt, C.r, C.phi, C.state);
  ok = ok && (!nm || !memcmp(phi, C.phi, n * nm * sizeof *phi)) && (!ns || !memcmp(st, C.state, n * ns * sizeof *st));
  double mass_ulp = 0;
  size_t mass_exact = 0;
  for (size_t c = 0; c < n; c++) {
    ok = ok && !memcmp(&rm[2 * c], &C.r[c], sizeof(double));
    double mh = sessile_sds_mass(density, C.r[c]);
    mass_ulp = fmax(mass_ulp, ulps(rm[2 * c + 1], mh));
    mass_exact += rm[2 * c + 1] == mh;
  }
  char what[300];
  snprintf(what, sizeof what,
           "%s, seed %d, %zu cells, %d step(s): the kernel's sources, division requests, radii, "
           "amounts and states are the host's, bit for bit (%zu requests; %s)",
           name, (int)seed, n, steps, a.ndivides, steps > 1 && a.ndivides ? "the second step stopped" : "one step");
  t_true(what, ok);
  if (steps > 1 && a.ndivides)
    t_true("... the batch's second step found STOP and skipped", ev[SDS_EV_STOP] == 1 && ev[SDS_EV_SKIP] == 1);
  /* the kernel rounds r^3 once (Dekker's split), the host's
   * sessile_sds_mass too (fma): the same bits */
  snprintf(what, sizeof what, "%s: masses are the host's sessile_sds_mass, bit for bit (%zu of %zu)", name,
           mass_exact, n);
  t_true(what, mass_exact == n && mass_ulp == 0);
  sessile_sds_actions_free(&a);
  free(src), free(phi), free(st), free(rm), free(req);
  sessile_cmd_destroy(cmd);
  sds_gpu_rules_destroy(r);
  rvm_cells_free(&C);
}

/* Expressions over radius, volume, time, surface, phi, tip, s0.. and the
 * constants K and H: the optimiser's patterns (x*c*c, c*x/c, x+x, x*x,
 * x^0..4, 2*(3*x+1)), folding (of && too), signs, ?: nested, every
 * function. */
static const char *const exprs[] = {
    "radius * 3 * 5", "3 * radius * 5", "radius * 0.1 / 3", "4 * radius / 2", "radius + radius", "radius - radius",
    "2 * radius - radius", "radius * radius", "radius ^ 2", "radius^3", "radius^4", "radius^0", "radius^1", "-radius^2",
    "-radius*3", "-(radius+1)*3", "1 + 2*3 - 4/5", "phi > K*volume && tip == 0 || radius < 0.3",
    "tip ? radius : volume", "tip == 1 ? 2 : phi > 0.5 ? 3 : 4", "(tip ? 1 : 2) + 3", "min(radius, volume, phi)",
    "max(radius, 2)", "sum(radius, phi, 1)", "avg(radius, volume)", "abs(phi - 0.5)", "sign(phi - 0.5)",
    "rint(radius*10)", "sqrt(volume)", "_pi * radius^2", "_e + 2.5e-1 * radius", ".5*radius", "0.5 && 1",
    "0.5 && radius", "0.5 || 0", "+radius", "-(-radius)", "radius - -1", "1 - radius + 2", "(radius + 1) * 2",
    "2 * (3 * radius + 1)", "(radius * 3 + 1) / 2", "surface * 2 + time", "K * volume + phi * 2 - 1",
    "radius >= 0.5 != (phi <= 0.1)", "H * phi * H", "phi / H / 3", "1 / (phi + 1)", "volume - phi * H + K",
    "tip * 2 + tip", "phi*K - phi", "min(phi)", "max(tip, phi, radius, volume)", "K ? radius : 2", "0 ? 1 : radius",
    "abs(-0)", "exp(1) * radius",
    /* on the host only: no fp64 version on the device */
    "exp(-radius)", "phi^0.5", "2^(-radius)", "log(volume)", "sin(time) + cos(time)", "atan2(radius, phi)",
    "tan(phi) * sinh(phi)", "cosh(phi) - tanh(phi) + asin(phi / (phi + 1)) + acos(phi / (phi + 1)) + atan(phi)",
    "asinh(radius) + acosh(radius + 1) + atanh(phi / (phi + 2))", "log2(volume) + log10(volume) + ln(volume)",
    "radius ^ phi"};
enum { NEXPR = sizeof exprs / sizeof *exprs, NDEVICE = 57 /* the first NDEVICE have device versions */ };

static char *expr_model_text;

static char *expr_model(int nexpr) {
  size_t cap = 32768, n = 0;
  char *t = t_xalloc(cap);
  n += (size_t)snprintf(t + n, cap - n,
                        "const K = 0.03\nconst H = 1.7\nmorphogen phi diffusion=0.1 decay=0.1\n"
                        "state tip = 0\n");
  for (int s = 0; s < 24; s++) n += (size_t)snprintf(t + n, cap - n, "state s%d = 0\n", s);
  for (int i = 0; i < nexpr; i += 8) {
    n += (size_t)snprintf(t + n, cap - n, "rule q%d: 1 ->", i / 8);
    for (int j = i; j < nexpr && j < i + 8; j++)
      n += (size_t)snprintf(t + n, cap - n, "%s set s%d = %s", j > i ? ";" : "", j % 24, exprs[j]);
    n += (size_t)snprintf(t + n, cap - n, "\n");
  }
  n += (size_t)snprintf(t + n, cap - n, "rule g: phi > 0.2 -> grow radius * 0.01 + phi; produce phi K * tip\n");
  n += (size_t)snprintf(t + n, cap - n, "rule d: tip == 0 && radius > 0.5 -> divide away grad(phi)\n");
  return t;
}

int main(void) {
  char root[512];
  snprintf(root, sizeof root, "%s", __FILE__);
  char *cut = strstr(root, "/tests/sds/");
  if (cut) *cut = 0;
  const char *names[] = {"limb.sds",   "six_limbs_box.sds", "rock.sds",
                         "attractor.sds", "budded.sds", "limb_extension.sds", "rock_stripes.sds"};
  for (int i = 0; i < 7; i++) {
    char path[700];
    snprintf(path, sizeof path, "%s/host/sds/models/%s", root, names[i]);
    sessile_sds_model *m = NULL;
    t_must(names[i], sessile_sds_model_load(path, &m));
    char what[200];
    snprintf(what, sizeof what, "%s: the rules compile, every operation with a device version", names[i]);
    t_true(what, !sessile_sds_model_bytecode_refusal(m, 1));
    for (int seed = 1; seed <= 3; seed++) {
      rvm_cells C = rvm_cells_make(m, 9, 8, 7, (uint64_t)seed);
      snprintf(what, sizeof what, "%s: seed %d, %d cells: the bytecode's actions are muparser's, bit for bit", names[i],
               seed, C.n);
      t_true(what, rvm_same_actions(m, &C, 0.5 * seed));
      rvm_cells_free(&C);
    }
    sessile_sds_model_destroy(m);
  }

  char *text = expr_model(NEXPR);
  sessile_sds_model *m = NULL;
  t_must("the expression model", sessile_sds_model_parse(text, "exprs.sds", &m));
  t_true("the expression model compiles to bytecode", !sessile_sds_model_bytecode_refusal(m, 0));
  const char *why = sessile_sds_model_bytecode_refusal(m, 1);
  printf("  its device refusal: %s\n", why ? why : "(none)");
  t_true("... and is refused on the device, naming the rule of exp(-radius)",
         why && strstr(why, "rule q7:") && strstr(why, "'exp'"));
  for (int seed = 1; seed <= 4; seed++) {
    rvm_cells C = rvm_cells_make(m, 6, 5, 4, 100 + (uint64_t)seed);
    char what[200];
    snprintf(what, sizeof what, "%d expressions, seed %d: the bytecode's values are muparser's, bit for bit", NEXPR,
             seed);
    t_true(what, rvm_same_actions(m, &C, 1.25 * seed));
    rvm_cells_free(&C);
  }
  sessile_sds_model_destroy(m);
  free(text);

  /* what it does not rebuild stays on the host, with the rule named */
  m = NULL;
  t_must("a model with an assignment",
         sessile_sds_model_parse("state tip\nrule zz: (tip = 1) -> grow 1\n", "as.sds", &m));
  why = sessile_sds_model_bytecode_refusal(m, 0);
  printf("  %s\n", why ? why : "(none)");
  t_true("an assignment is refused, naming file, line and rule",
         why && strstr(why, "as.sds:2: rule zz") && strstr(why, "assignment"));
  sessile_sds_actions a = {0};
  rvm_cells C = rvm_cells_make(m, 2, 2, 2, 1);
  sessile_morph_cells cl = rvm_morph_cells(&C);
  t_true("... and its bytecode evaluation refused",
         sessile_sds_rules_eval_vm(m, &cl, C.phi, C.state, 0, &a) == SESSILE_ERR_USAGE);
  sessile_sds_actions_free(&a);
  rvm_cells_free(&C);
  sessile_sds_model_destroy(m);

  /* a value that is not finite stops both the same way */
  m = NULL;
  t_must("a model dividing by zero",
         sessile_sds_model_parse("morphogen p diffusion=0 decay=0\nrule r: 1 -> grow 1 / (p - p)\n", "z.sds", &m));
  C = rvm_cells_make(m, 2, 2, 2, 1);
  cl = rvm_morph_cells(&C);
  sessile_status s1 = sessile_sds_rules_eval(m, &cl, C.phi, C.state, 0, &a);
  char m1[400];
  snprintf(m1, sizeof m1, "%s", sessile_error_message());
  sessile_sds_actions_free(&a);
  sessile_status s2 = sessile_sds_rules_eval_vm(m, &cl, C.phi, C.state, 0, &a);
  sessile_sds_actions_free(&a);
  t_true("1/0 stops both with SESSILE_ERR_NUMERIC and the same message",
         s1 == SESSILE_ERR_NUMERIC && s2 == s1 && !strcmp(m1, sessile_error_message()));
  rvm_cells_free(&C);
  sessile_sds_model_destroy(m);

  /* on the device (fp64, under the validation layer) */
  sessile_gpu *g = t_gpu(64);
  for (kind = 0; kind < 2; kind++) {
    printf("the %s kernel:\n", kind_names[kind]);
    for (int i = 0; i < 5; i++) {
      char path[700], name[100];
      snprintf(path, sizeof path, "%s/host/sds/models/%s", root, names[i]);
      snprintf(name, sizeof name, "%s (%s)", names[i], kind_names[kind]);
      t_must(names[i], sessile_sds_model_load(path, &m));
      device_check(g, m, name, 7 + (uint64_t)i, 1);
      device_check(g, m, name, 7 + (uint64_t)i, 2);
      if (i == 0 || i == 2 || i == 4) device_run(g, m, name, 40);
      sessile_sds_model_destroy(m);
    }
    text = expr_model(NDEVICE);
    t_must("the device's expressions", sessile_sds_model_parse(text, "exprs.sds", &m));
    for (int seed = 1; seed <= 2; seed++)
      device_check(g, m, kind ? "the device's expressions (bytecode)" : "the device's expressions (generated)",
                   200 + (uint64_t)seed, 1);
    sessile_sds_model_destroy(m);
    free(text);
  }
  kind = 0;
  t_must("the host's expressions", sessile_sds_model_parse(expr_model_text = expr_model(NEXPR), "exprs.sds", &m));
  sds_gpu_rules *r = NULL;
  sessile_status sr = sds_gpu_rules_create(g, m, &r);
  t_true("a model with exp() is refused on the device, naming the rule",
         sr == SESSILE_ERR_USAGE && !r && strstr(sessile_error_message(), "rule q7"));
  sessile_sds_model_destroy(m);
  free(expr_model_text);
  return t_finish(g);
}
