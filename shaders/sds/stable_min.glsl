// One workgroup: the stable bound, min(dt_max, min_c h_c) (a NaN h_c is
// skipped, as sessile_sds_stable_dt does; a min is exact in any order, so
// the bits do not depend on the schedule), the cap hmax = dt_max lowered to
// stable_safety x the bound, and the step h = min(asked, hmax) that the
// gather takes in mode 2: stab[n] = h, stab[n + 1] = hmax, stab[n + 2] = the
// bound, copied to step for the host.  The cap is the one
// sessile_sds_gpu_advance applied on the host before this kernel existed.
// In a batch (pc.batch > 0; docs/sds.md, "The loop on the device"), where
// tet_force flags the inverted tets of its input (the step before's result)
// into ev[2], it first
// checks the batch's previous step as sessile_sds_gpu_advance does on the
// host, operation by operation (the same bits in fp64): its largest move
// against max_move (else the step is rejected and the batch stops: the host
// halves dt), the next step aimed at SDS_MOVE_AIM x max_move, the time, and
// the events that stop the batch after the step (inverted tets, stale
// contact lists, the stop time, dt_min).  With SDS_BATCH_SPLIT each step is
// checked by a dispatch of its own in mode 3, after the step's inverted
// flags and before anything of the next step (the rules must see a step
// only once it is accepted).  Once ev[0] is set it writes
// stab[n] = -1, which the gather honours, and does nothing more.
// step_check.comp includes the check alone (STABLE_MIN_CHECK_ONLY: no
// growth check, no main).
#include "sds_common.glsl"
#include "group.glsl"
// SDS_SLIVERS 0 (stable_all.comp, step_check_nosl.comp): no quiet slivers,
// for a batch without a table, where any inverted tet stops the batch
// anyway.  llvmpipe runs a fused kernel's tail, masked, in every subgroup of
// its dispatch, so the cubic's code would cost every subgroup of every step
// (docs/sds.md, "Tails that every subgroup runs").
#ifndef SDS_SLIVERS
#define SDS_SLIVERS 1
#endif
#if SDS_SLIVERS
#include "sliver.glsl"
#endif

#ifndef SDS_PART_SHARED
#define SDS_PART_SHARED 1 // also morph_bound.glsl's
shared REAL part[SDS_SCAN_MAX];
#endif
shared uint bad, evs, loud;

// The largest of v over the workgroup's lanes (exact in any order).
REAL group_max(uint l, uint L, REAL v) {
  part[l] = v;
  GRP_BARRIER();
  for (uint w = L / 2u; w > 0u; w /= 2u) {
    if (l < w && part[l + w] > part[l]) part[l] = part[l + w];
    GRP_BARRIER();
  }
  REAL r = part[0];
  GRP_BARRIER();
  return r;
}

// The batch stopped: every later dispatch of its recording launches no
// workgroup (sessile_cmd_indirect's counts; disp[0] of them, none outside a
// batch).  Those dispatches would return at once anyway (they honour ev[0]);
// not launching them saves lavapipe a thread-pool round trip each.
void stop_dispatches() {
  uint n = disp[0];
  for (uint i = 0u; i < n; i++) disp[4u + 3u * i] = 0u;
}

// The check of the batch's step j (its gather wrote move; inverted counted
// its inverted tets in ev[2] and listed them in sl): the events into ev[0]
// and evs, the step's dt and end time logged.  Inverted tets stop the batch
// unless they are exactly the slivers' table, each quiet (sliver.glsl).
void check_step(uint l, uint L, uint n, uint j) {
  if (l == 0u) bad = 0u, loud = 0u;
  GRP_BARRIER();
  uint ninv = ev[2];
  if (ninv != 0u) { // any lane: the same value
#if SDS_SLIVERS
    if (ninv != sl[SL_COUNT]) loud = 1u;
    else
      for (uint i = l; i < ninv; i += L)
        if (!sl_quiet(sl[uint(SL_LIST) + i], j)) loud = 1u;
#else
    loud = 1u; // no table: every inverted tet stops the batch
#endif
  }
  REAL mv = REAL(0), far = REAL(0), far_surf = REAL(0);
  bool lists = pc.lcap > 0u;
  for (uint c = l; c < n; c += L) {
    REAL m = move[c];
    if (!is_finite(m)) bad = 1u; // any lane: the same value
    else if (m > mv) mv = m;
    if (lists) {
      REAL d = move[n + c];
      if (d > far) far = d;
      if (topo[o_csurf() + c] != 0u && d > far_surf) far_surf = d;
    }
  }
  mv = group_max(l, L, mv);
  far = group_max(l, L, far);
  far_surf = group_max(l, L, far_surf);
  if (l == 0u) {
    uint e = 0u;
    precise REAL h = step[0], g = step[6];
    // the lists' staleness (sds_gpu_lists_stale), also after a rejected step
    if (lists && ((pc.nobs != 0u && !(far + g <= sp[SP_SKIN])) || (pc.tsize != 0u && !(REAL(2) * far_surf + g <= sp[SP_SKIN]))))
      e |= SDS_EV_LISTS;
    if (bad != 0u) e |= SDS_EV_NONFINITE;
    else if (mv > sp[SP_MAX_MOVE]) e |= SDS_EV_REJECT;
    else {
      precise REAL t = step[4] + h;
      precise REAL f = mv > REAL(0) ? sp[SP_AIM] * sp[SP_MAX_MOVE] / mv : sp[SP_GROW];
      precise REAL hn = h * (f < sp[SP_GROW] ? f : sp[SP_GROW]);
      if (hn > sp[SP_DT_MAX]) hn = sp[SP_DT_MAX];
      ev[1] = ev[1] + 1u;
      step[4] = t, step[3] = hn, step[7] = mv;
      step[SDS_STEP_LOG + 2u * j] = h, step[SDS_STEP_LOG + 2u * j + 1u] = t;
      if (!(hn >= sp[SP_DT_MIN])) e |= SDS_EV_DTMIN;
      uint q = 0u; // the step's quiet slivers, counted as the host's loop counts them
      if (ninv != 0u && loud != 0u) e |= SDS_EV_INVERTED;
      else q = ninv;
      sl[SL_QUIET] += q, sl[SL_QLAST] = q;
      if (t >= step[5]) e |= SDS_EV_TIME;
    }
    ev[2] = 0u;
    ev[0] = e;
    evs = e;
    // split: step j's rules still run after this check (stable_min mode 4 stops the dispatches)
    if (e != 0u && (pc.batch & SDS_BATCH_SPLIT) == 0u) stop_dispatches();
  }
  GRP_BARRIER();
}

#if !STABLE_MIN_CHECK_ONLY
// Mode 4, in a batch after step j's rules (host/sds/sds_gpu_batch_rules.c):
// the batch stops when the host must complete the step's rules (SKIP) or a
// cell asked to divide (STOP); else the lists' staleness with the radii the
// rules grew, as the host's loop checks it when it uploads them
// (sds_gpu_lists_check_moves: the largest r - rb, then
// sds_gpu_lists_stale; pc.dt carries contact_scale), and the growth term the
// next steps' checks use.
// True (on every lane) when the batch stopped, here or before.  Folded into
// the next step's stable_min (SDS_BATCH_RULES), or a dispatch of its own
// after the batch's last step: on lavapipe each dispatch is a thread-pool
// round trip whatever it does.
shared uint gstop;
bool growth_check(uint l, uint L, uint n) {
  if (ev[0] != 0u) { // stopped by the step's check (stab[n] is -1 already), after which its rules ran
    if (l == 0u) stop_dispatches();
    return true;
  }
  uint e = rev[SDS_EV_SKIP] != 0u ? SDS_EV_HOST : rev[SDS_EV_STOP] != 0u ? SDS_EV_DIVIDE : 0u;
  if (e != 0u || pc.lcap == 0u) {
    if (l == 0u && e != 0u) ev[0] = e, stab[n] = REAL(-1), stop_dispatches();
    return e != 0u;
  }
  REAL far = REAL(0), far_surf = REAL(0), grown = REAL(0);
  for (uint c = l; c < n; c += L) {
    REAL d = move[n + c];
    if (d > far) far = d;
    if (topo[o_csurf() + c] != 0u && d > far_surf) far_surf = d;
    precise REAL g = rm[2u * c] - rb[c];
    if (!(g <= grown)) grown = g;
  }
  far = group_max(l, L, far);
  far_surf = group_max(l, L, far_surf);
  grown = group_max(l, L, grown);
  if (l == 0u) {
    precise REAL g = pc.dt * grown;
    gstop = 0u;
    if ((pc.nobs != 0u && !(far + g <= sp[SP_SKIN])) || (pc.tsize != 0u && !(REAL(2) * far_surf + g <= sp[SP_SKIN])))
      ev[0] = SDS_EV_LISTS, stab[n] = REAL(-1), stop_dispatches(), gstop = 1u;
    else
      step[6] = g;
  }
  GRP_BARRIER();
  return gstop != 0u;
}

// One workgroup's lanes, every one (main, or stable_all.comp's last workgroup).
void stable_min_run() {
  uint l = GRP_LANE, L = GRP_SIZE, n = pc.ncells;
  if (pc.mode == 4u) {
    growth_check(l, L, n);
    return;
  }
  uint bk = pc.batch & ~(SDS_BATCH_SPLIT | SDS_BATCH_RULES);
  bool split = (pc.batch & SDS_BATCH_SPLIT) != 0u; // steps checked by their own dispatches (mode 3)
  if (bk != 0u) {
    // the step before's rules ran after its check: their growth check first
    if ((pc.batch & SDS_BATCH_RULES) != 0u && growth_check(l, L, n)) return;
    if (ev[0] != 0u) return; // stopped: stab[n] is -1 already
    if (bk == 1u && !split && l == 0u) ev[2] = 0u; // tet_force flagged the batch's start state: not a step's
    if (bk > 1u && (pc.mode == 3u || !split)) {
      check_step(l, L, n, bk - 2u);
      if (evs != 0u) {
        if (l == 0u) stab[n] = REAL(-1);
        return;
      }
    }
    if (pc.mode == 3u) return; // a check alone
  }
  REAL best = sp[SP_DT_MAX];
  for (uint c = l; c < n; c += L)
    if (stab[c] < best) best = stab[c];
  part[l] = best;
  GRP_BARRIER();
  for (uint w = L / 2u; w > 0u; w /= 2u) {
    if (l < w && part[l + w] < part[l]) part[l] = part[l + w];
    GRP_BARRIER();
  }
  if (l == 0u) {
    REAL bound = part[0], hmax = sp[SP_DT_MAX], asked = bk != 0u ? step[3] : pc.dt;
    if (sp[SP_SAFETY] > REAL(0) && sp[SP_SAFETY] * bound < hmax) hmax = sp[SP_SAFETY] * bound;
    REAL h = asked > hmax ? hmax : asked;
    stab[n] = h, stab[n + 1u] = hmax, stab[n + 2u] = bound;
    step[0] = h, step[1] = hmax, step[2] = bound;
  }
}

#ifndef STABLE_MIN_NO_MAIN
void main() { stable_min_run(); }
#endif
#endif
