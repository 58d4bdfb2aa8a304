// The rules' bytecode, one invocation per cell (docs/sds_rules.md,
// "Bytecode").  Operation for operation as the plain-C reference
// (host/sds/rules_vm.c: muparser's operations) and the host's actions
// (host/sds/rules_eval.c: sessile_sds_rules_eval, sessile_sds_actions_apply;
// the gradient of host/sds/morph.c); `precise` everywhere a product meets a
// sum, so that no compiler fuses them.  mode 0 evaluates, mode 1 applies.
#include "sds_kernels.glsl"
// What mode 0 reads of the cells: through storage buffers, or (RULES_TEXEL,
// rules_morph.glsl) through the uniform texel buffers x_t, rm_t, phi_t,
// nbr_off_t and nbr_t; the same bits.
#if RULES_TEXEL
#include "texel_real.glsl"
#define RV_X(i) texel_real(x_t, (i))
#define RV_R(c) texel_real(rm_t, 2u * (c))
#define RV_PHI(i) texel_real(phi_t, (i))
#define RV_OFF(i) texelFetch(nbr_off_t, int(i)).x
#define RV_NBR(i) texelFetch(nbr_t, int(i)).x
#else
#define RV_X(i) x[i]
#define RV_R(c) rm[2u * (c)]
#define RV_PHI(i) phi[i]
#define RV_OFF(i) nbr_off[i]
#define RV_NBR(i) nbr[i]
#endif

// rules_vm.h's opcodes, functions and slots (keep in step: test_rules_vm
// runs every one of them against the reference)
#define VM_END 0u
#define VM_VAL 1u
#define VM_VAR 2u
#define VM_VARMUL 3u
#define VM_POW2 4u
#define VM_POW3 5u
#define VM_POW4 6u
#define VM_ADD 7u
#define VM_SUB 8u
#define VM_MUL 9u
#define VM_DIV 10u
#define VM_POW 11u
#define VM_LT 12u
#define VM_GT 13u
#define VM_LE 14u
#define VM_GE 15u
#define VM_NE 16u
#define VM_EQ 17u
#define VM_AND 18u
#define VM_OR 19u
#define VM_IF 20u
#define VM_JMP 21u
#define VM_FUN 22u
#define VM_SUM 23u
#define VM_AVG 24u
#define VM_MIN 25u
#define VM_MAX 26u
#define F_NEG 0u
#define F_ABS 1u
#define F_SIGN 2u
#define F_RINT 3u
#define F_SQRT 4u
// sessile_sds_action_kind
#define A_SET_MORPH 0u
#define A_SET_STATE 1u
#define A_PRODUCE 2u
#define A_GROW 3u
#define A_DIVIDE 4u
#define A_RESET 5u
#define SLOT_MORPH 4u
#define SLOT_STATE 20u

#ifndef SDS_VOL_OF
#define SDS_VOL_OF 1 // also morph_step.glsl's
REAL vol_of(REAL r) {
  precise REAL v = REAL(4.0lf / 3.0lf * 3.14159265358979311600lf) * r * r * r;
  return v;
}
#endif

// The step's time and dt: the push constants', or in a batch the control
// morph_bound left after the constants (kernels.def, SDS_CTL).
REAL step_time() { return pc.batch != 0u ? konst[pc.kctl + 2u] : pc.time; }
REAL step_dt() { return pc.batch != 0u ? konst[pc.kctl + 3u] : pc.dt; }

REAL slot_of(uint c, uint a) {
  if (a == 0u) return RV_R(c);
  if (a == 1u) return vol_of(RV_R(c));
  if (a == 2u) return step_time();
  if (a == 3u) return surf[c] != 0u ? REAL(1) : REAL(0);
  if (a < SLOT_STATE) return RV_PHI(c * pc.nmorph + a - SLOT_MORPH);
  return state[c * pc.nstate + a - SLOT_STATE];
}

REAL b2r(bool b) { return b ? REAL(1) : REAL(0); }

// One expression at p over cell c's slots (the compiler bounded the stack).
REAL vm_run(uint c, uint p) {
  REAL st[SDS_VM_STACK];
  int sp = -1;
  for (;;) {
    uint w0 = prog[p], b = prog[p + 1u], op = w0 & 255u, a = w0 >> 8;
    p += 2u;
    if (op == VM_END) return st[sp];
    if (op >= VM_ADD && op <= VM_OR) {
      REAL vb = st[sp];
      sp--;
      REAL va = st[sp];
      precise REAL v;
      if (op == VM_ADD) v = va + vb;
      else if (op == VM_SUB) v = va - vb;
      else if (op == VM_MUL) v = va * vb;
      else if (op == VM_DIV) v = va / vb;
      else if (op == VM_LT) v = b2r(va < vb);
      else if (op == VM_GT) v = b2r(va > vb);
      else if (op == VM_LE) v = b2r(va <= vb);
      else if (op == VM_GE) v = b2r(va >= vb);
      else if (op == VM_NE) v = b2r(!(va == vb)); // true for NaN, as in C
      else if (op == VM_EQ) v = b2r(va == vb);
      else if (op == VM_AND) v = b2r(!(va == REAL(0)) && !(vb == REAL(0)));
      else v = b2r(!(va == REAL(0)) || !(vb == REAL(0))); // VM_OR (VM_POW is host only)
      st[sp] = v;
    } else if (op == VM_VAL) {
      st[++sp] = konst[b];
    } else if (op == VM_VAR) {
      st[++sp] = slot_of(c, a);
    } else if (op == VM_VARMUL) {
      precise REAL t = slot_of(c, a) * konst[b];
      precise REAL u = t + konst[b + 1u];
      st[++sp] = u;
    } else if (op >= VM_POW2 && op <= VM_POW4) {
      REAL va = slot_of(c, a);
      precise REAL v = va * va;
      if (op >= VM_POW3) v = v * va;
      if (op == VM_POW4) v = v * va;
      st[++sp] = v;
    } else if (op == VM_IF) {
      REAL cnd = st[sp];
      sp--;
      if (cnd == REAL(0)) p = b;
    } else if (op == VM_JMP) {
      p = b;
    } else if (op == VM_FUN) {
      REAL v = st[sp];
      precise REAL h = v + REAL(0.5);
      if (a == F_NEG) v = -v;
      else if (a == F_ABS) v = (v >= REAL(0)) ? v : -v;
      else if (a == F_SIGN) v = (v < REAL(0)) ? REAL(-1) : (v > REAL(0)) ? REAL(1) : REAL(0);
      else if (a == F_RINT) v = floor(h);
      else v = sqrt(v); // F_SQRT (the others are host only)
      st[sp] = v;
    } else { // VM_SUM .. VM_MAX over a values
      int n = int(a), lo = sp - n + 1;
      precise REAL r = (op == VM_MIN || op == VM_MAX) ? st[lo] : REAL(0);
      for (int i = 0; i < n; i++) {
        REAL v = st[lo + i];
        if (op == VM_MIN) r = (v < r) ? v : r;
        else if (op == VM_MAX) r = (r < v) ? v : r;
        else r = r + v;
      }
      if (op == VM_AVG) r = r / REAL(n);
      sp = lo;
      st[sp] = r;
    }
  }
  return REAL(0);
}

#include "gradient.glsl"

// A value not finite: the host stops the run (its evaluator names the rule);
// the cell's actions are dropped.
void numeric(uint c, uint base) {
  atomicOr(event[SDS_EV_FLAGS], 2u);
  atomicMin(event[SDS_EV_BAD], c);
  pend[base] = REAL(0);
  pflag[2u * c] = 0u;
  pflag[2u * c + 1u] = 0u;
}

// What evaluate gathers over a cell's rules, in the host's order.
struct cell_acc {
  uint base, fl0, fl1;
  REAL grow;
  bool divided;
};

cell_acc acc_begin(uint c) {
  uint nm = pc.nmorph;
  for (uint k = 0u; k < nm; k++) src[c * nm + k] = REAL(0);
  return cell_acc(c * (1u + nm + pc.nstate), 0u, 0u, REAL(0), false);
}

// Rule r's action (kind word kw) with its value val (finite; 0 for divide
// and reset, which have none).
void act(uint c, uint r, uint kw, REAL val, inout cell_acc e) {
  uint nm = pc.nmorph, kind = kw & 255u, t = (kw >> 8) & 255u;
  if (kind == A_SET_MORPH || kind == A_SET_STATE || kind == A_RESET) {
    uint slot = kind == A_SET_STATE ? nm + t : t;
    pend[e.base + 1u + slot] = kind == A_RESET ? mcoef[2u * t + 1u] : val;
    if (slot < 32u) e.fl0 |= 1u << slot;
    else e.fl1 |= 1u << (slot - 32u);
  } else if (kind == A_PRODUCE) {
    precise REAL s = src[c * nm + t] + val;
    src[c * nm + t] = s;
  } else if (kind == A_GROW) {
    e.grow += val;
  } else if (kind == A_DIVIDE && !e.divided) {
    e.divided = true;
    REAL g0, g1, g2, d0 = REAL(0), d1 = REAL(0), d2 = REAL(0);
    if (gradient(c, t, g0, g1, g2)) {
      precise REAL l = sqrt(g0 * g0 + g1 * g1 + g2 * g2);
      REAL sg = ((kw >> 16) & 1u) != 0u ? REAL(-1) : REAL(1);
      precise REAL e0 = sg * g0 / l, e1 = sg * g1 / l, e2 = sg * g2 / l;
      d0 = e0, d1 = e1, d2 = e2;
    }
    uint q = atomicAdd(event[SDS_EV_NREQ], 1u);
    atomicOr(event[SDS_EV_FLAGS], 1u);
    if (q < pc.ncells) {
      uint o = uint(SDS_REQ) * q;
      divreq[o] = REAL(c), divreq[o + 1u] = REAL(r);
      divreq[o + 2u] = d0, divreq[o + 3u] = d1, divreq[o + 4u] = d2;
    }
  }
}

void acc_end(uint c, cell_acc e) {
  pend[e.base] = e.grow;
  pflag[2u * c] = e.fl0;
  pflag[2u * c + 1u] = e.fl1;
}

// The rules by the bytecode interpreter (the generated kernel's evaluate_gen,
// host/sds/rules_glsl.c, does the same with each expression's code written
// out).
void evaluate(uint c) {
  cell_acc e = acc_begin(c);
  uint nrules = prog[0];
  for (uint r = 0u; r < nrules; r++) {
    uint rec = prog[1u + r];
    REAL v = vm_run(c, prog[rec]);
    if (isnan(v)) {
      numeric(c, e.base);
      return;
    }
    if (v == REAL(0)) continue;
    uint nact = prog[rec + 1u];
    for (uint i = 0u; i < nact; i++) {
      uint kw = prog[rec + 2u + 2u * i], kind = kw & 255u;
      REAL val = REAL(0);
      if (kind != A_DIVIDE && kind != A_RESET) {
        val = vm_run(c, prog[rec + 3u + 2u * i]);
        if (!is_finite(val)) {
          numeric(c, e.base);
          return;
        }
      }
      act(c, r, kw, val, e);
    }
  }
  acc_end(c, e);
}

// r^3 rounded once (Dekker's exact products, no fma): pow(r, 3) on the host.
void two_prod(REAL a, REAL b, out REAL p, out REAL e) {
#if SESSILE_F64
  const REAL split = REAL(134217729.0);
#else
  const REAL split = REAL(4097.0);
#endif
  precise REAL ca = split * a, ah = ca - (ca - a), al = a - ah;
  precise REAL cb = split * b, bh = cb - (cb - b), bl = b - bh;
  precise REAL pp = a * b;
  precise REAL ee = ((ah * bh - pp) + ah * bl + al * bh) + al * bl;
  p = pp, e = ee;
}

REAL cube(REAL r) {
  REAL p, e, q, f;
  two_prod(r, r, p, e);
  two_prod(p, r, q, f);
  precise REAL g = e * r;
  precise REAL s = f + g;
  precise REAL v = q + s;
  return v;
}

// Mode 1: the pending actions applied.  Where its radius comes from and
// where r, m and the set amounts go: rm and phi in place, or (rules_morph
// mode 2) rm_next and the sub-step's output.
#ifndef AP_RM_OUT
#define AP_R_IN(c) rm[2u * (c)]
#define AP_RM_OUT rm
#define AP_PHI_OUT phi
#endif
void apply(uint c) {
  uint nm = pc.nmorph, ns = pc.nstate, base = c * (1u + nm + ns);
  precise REAL r = AP_R_IN(c) + step_dt() * pend[base];
  REAL vol = vol_of(r);
  uint fl0 = pflag[2u * c], fl1 = pflag[2u * c + 1u];
  for (uint t = 0u; t < nm + ns; t++) {
    bool set = t < 32u ? (fl0 & (1u << t)) != 0u : (fl1 & (1u << (t - 32u))) != 0u;
    if (!set) continue;
    REAL v = pend[base + 1u + t];
    if (t < nm) {
      v = (v >= REAL(0)) ? v : REAL(0);                                // glibc's fmax(v, 0)
      if (mcoef[2u * t] != REAL(0)) v = (v <= vol) ? v : vol;          // fmin(v, vol)
      AP_PHI_OUT[c * nm + t] = v;
    } else {
      state[c * ns + t - nm] = v;
    }
  }
  precise REAL mass = pc.density * REAL(4.0) / REAL(3.0) * REAL(3.14159265358979311600lf) * cube(r);
  AP_RM_OUT[2u * c] = r;
  AP_RM_OUT[2u * c + 1u] = mass;
}


#ifdef SDS_RULES_GEN
void evaluate_gen(uint c); // written after this file by host/sds/rules_glsl.c
#endif

#ifndef RULES_NO_MAIN
void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  if (pc.mode == 0u) {
    if (event[SDS_EV_STOP] != 0u) { // a topology event earlier in the batch
      event[SDS_EV_SKIP] = 1u;
      return;
    }
    if (pc.batch != 0u && event[SDS_EV_SKIP] != 0u) return; // morph_bound: the host's step
#ifdef SDS_RULES_GEN
    evaluate_gen(c);
#else
    evaluate(c);
#endif
  } else {
    if (event[SDS_EV_SKIP] != 0u) return;
    apply(c);
    if (event[SDS_EV_FLAGS] != 0u) event[SDS_EV_STOP] = 1u;
    if (pc.batch != 0u && c == 0u) event[SDS_EV_LAST] = pc.batch;
  }
}
#endif
