/* sessile_render_plot and sessile_render_plot_records: the 1-2-5 tick rule,
 * axis ranges extended to whole ticks, markers of a known series at the
 * pixels the axis transform puts them (checked by their colour), gaps at NaN,
 * interval bars, the records presets, same bytes on rerun, bad input refused. */
#include <math.h>
#include "render/draw2d.h"
#include "render2d_testutil.h"
#include "sessile/render/render2d.h"
#include "testutil.h"


static const unsigned char blue[3] = {0x1f, 0x77, 0xb4}, orange[3] = {0xff, 0x7f, 0x0e};

/* The pixel holding data point (x, y) by the plot's affine transform, computed
 * here from the plot area's corners and the axis ranges. */
static uint32_t px_at(const t_png *p, const sessile_plot_layout *L, double x, double y) {
  double fx = L->px0 + (x - L->x0) / (L->x1 - L->x0) * (L->px1 - L->px0);
  double fy = L->py0 - (y - L->y0) / (L->y1 - L->y0) * (L->py0 - L->py1);
  return t_px(p, (int)floor(fx), (int)floor(fy));
}

static void bad(const char *what, sessile_status s, const char *out, const char *must_contain) {
  char msg[400];
  const char *m = sessile_error_message();
  snprintf(msg, sizeof msg, "%s: SESSILE_ERR_USAGE, one line naming '%s', nothing written [%s]", what, must_contain, m);
  t_true(msg, s == SESSILE_ERR_USAGE && !strchr(m, '\n') && strstr(m, must_contain) && !t_exists(out));
}

int main(void) {
  dir = t_scratch("test_render_plot");
  /* the 1-2-5 rule */
  t_true("tick step over [0, 10], at most 8 ticks: 2", d2_tick_step(0, 10, 8) == 2);
  t_true("tick step over [0, 100], at most 6 ticks: 20", d2_tick_step(0, 100, 6) == 20);
  t_true("tick step over [0, 100], at most 11 ticks: 10", d2_tick_step(0, 100, 11) == 10);
  t_true("tick step over [0.013, 0.087], at most 5 ticks: 0.02", fabs(d2_tick_step(0.013, 0.087, 5) - 0.02) < 1e-15);
  t_true("tick step over [-3, 7e5], at most 8 ticks: 1e5", d2_tick_step(-3, 7e5, 8) == 1e5);
  char lab[32];
  d2_tick_label(lab, sizeof lab, 0.30000000000000004, 0.05);
  t_true("tick label of 0.3 on a 0.05 grid is \"0.30\"", !strcmp(lab, "0.30"));
  d2_tick_label(lab, sizeof lab, -1e-17, 0.1);
  t_true("tick label at zero is \"0.0\" (no -0)", !strcmp(lab, "0.0"));

  /* a known series: A = 10 x (blue), B = 100 - 10 x (orange) with a NaN at x = 3 */
  double x[11], ya[11], yb[11];
  for (int i = 0; i <= 10; i++) x[i] = i, ya[i] = 10 * i, yb[i] = i == 3 ? NAN : 100 - 10 * i;
  sessile_plot p = {"two lines", "x (cm)", "y (s)", 2, {{"A", x, ya, 11, 0, NULL, NULL}, {"B", x, yb, 11, 0, NULL, NULL}}, NULL};
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  sessile_plot_layout L;
  t_ok("plot two series", sessile_render_plot(&p, &o, P("two.png")));
  t_ok("plot layout", sessile_render_plot_layout(&p, &o, &L));
  t_true("axes: x [0, 10], y [0, 100] (data ranges on whole ticks)", L.x0 == 0 && L.x1 == 10 && L.y0 == 0 && L.y1 == 100);
  double kx = round((L.x1 - L.x0) / L.xstep), ky = round((L.y1 - L.y0) / L.ystep);
  t_true("the ranges hold whole numbers of ticks", fabs(kx * L.xstep - 10) < 1e-9 && fabs(ky * L.ystep - 100) < 1e-9);
  t_png img = t_png_read(P("two.png"));
  t_true("the plot PNG reads back at 800 x 600", img.px && img.w == 800 && img.h == 600);
  if (img.px) {
    int worst = 0;
    for (int i = 0; i <= 10; i++) {
      if (i == 5) continue; /* both series pass there; B is drawn last */
      worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, x[i], ya[i]), blue));
      if (i != 3) worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, x[i], yb[i]), orange));
    }
    worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, 5, 50), orange));
    t_check("21 markers have their series' colour at the transformed pixel (max level diff)", worst, 1);
    t_true("no marker and no line where B is NaN (x = 3, y = 70): not orange",
           t_rgb_diff(px_at(&img, &L, 3, 70), orange) > 40);
    free(img.px);
  }
  t_ok("plot again", sessile_render_plot(&p, &o, P("two2.png")));
  t_true("same input, identical PNG bytes", t_same_bytes(P("two.png"), P("two2.png")));

  /* records: the SDS preset (ms per step against cells), blank and partial lines skipped */
  FILE *f = fopen(P("records.jsonl"), "w");
  double cells[5] = {120, 480, 1000, 2400, 3900}, ms[5] = {0.6, 1.1, 2.3, 4.9, 8.2};
  for (int k = 0; f && k < 5; k++) {
    fprintf(f, "{\"frame\":%d,\"time\":%g,\"cells\":%g,\"tets\":%g,\"ms_per_step\":%g}\n", k, 0.5 * k, cells[k],
            3 * cells[k], ms[k]);
    if (k == 2) fprintf(f, "\n{\"frame\":99,\"note\":\"no timing\"}\n");
  }
  /* a frame written before any step (steps 0): no time per step, so no point */
  if (f) fprintf(f, "{\"frame\":5,\"cells\":2000,\"steps\":0,\"ms_per_step\":0}\n");
  if (f) fclose(f);
  t_ok("plot records preset steps", sessile_render_plot_records(P("records.jsonl"), "steps", &o, P("steps.png")));
  sessile_plot ps = {"", "", "", 1, {{"", cells, ms, 5, 0, NULL, NULL}}, NULL};
  t_ok("layout of the same points", sessile_render_plot_layout(&ps, &o, &L));
  t_true("steps axes: cells [0, 4000], ms [0, 9 or 10]", L.x0 == 0 && L.x1 == 4000 && L.y0 == 0 && L.y1 >= 8.2 && L.y1 <= 10);
  img = t_png_read(P("steps.png"));
  if (img.px) {
    int worst = 0;
    for (int k = 0; k < 5; k++) worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, cells[k], ms[k]), blue));
    t_check("steps: the 5 records' markers at their pixels (max level diff)", worst, 1);
    t_true("a record with steps 0 is no point: no line toward (2000, 0) (its midpoint is not blue)",
           t_rgb_diff(px_at(&img, &L, 2950, 4.1), blue) > 40);
    free(img.px);
  } else t_true("steps PNG reads back", 0);
  t_ok("plot records by keys", sessile_render_plot_records(P("records.jsonl"), "time:cells,tets", &o, P("keys.png")));
  t_true("plot by keys wrote a PNG", t_exists(P("keys.png")));

  /* interval bars: the y range covers them; the bar's pixels between the
   * marker and its ends have the series' colour, pixels beyond its ends not */
  double bx[3] = {1, 2, 3}, by[3] = {10, 20, 30}, blo[3] = {4, 18, NAN}, bhi[3] = {16, 42, NAN};
  sessile_plot pb = {"bars", "x", "y", 1, {{"mean", bx, by, 3, 0, blo, bhi}}, NULL};
  t_ok("plot with interval bars", sessile_render_plot(&pb, &o, P("bars.png")));
  t_ok("layout with interval bars", sessile_render_plot_layout(&pb, &o, &L));
  t_true("bars: the y range covers the intervals (4..42), not only the means (10..30)", L.y0 <= 4 && L.y1 >= 42 && L.y1 < 60);
  img = t_png_read(P("bars.png"));
  if (img.px) {
    int worst = 0;
    for (double y = 19; y <= 41; y += 2) worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, 2, y), blue));
    for (double y = 5; y <= 15; y += 2) worst = (int)fmax(worst, t_rgb_diff(px_at(&img, &L, 1, y), blue));
    t_check("bars: blue all along both intervals (max level diff)", worst, 1);
    t_true("bars: no bar past an interval's end (x = 2, y = 44) nor where the bounds are NaN (x = 3, y = 36)",
           t_rgb_diff(px_at(&img, &L, 2, 44), blue) > 40 && t_rgb_diff(px_at(&img, &L, 3, 36), blue) > 40);
    free(img.px);
  } else t_true("bars PNG reads back", 0);
  sessile_plot pnb = {"bars", "x", "y", 1, {{"mean", bx, by, 3, 0, NULL, NULL}}, NULL};
  t_ok("the same plot without bars", sessile_render_plot(&pnb, &o, P("nobars.png")));
  t_true("... differs from the plot with them", !t_same_bytes(P("bars.png"), P("nobars.png")));

  /* bad input */
  bad("missing records", sessile_render_plot_records(P("none.jsonl"), "steps", &o, P("b1.png")), P("b1.png"), "none.jsonl");
  bad("unknown plot", sessile_render_plot_records(P("records.jsonl"), "speed", &o, P("b2.png")), P("b2.png"), "unknown plot 'speed'");
  bad("keys in no record", sessile_render_plot_records(P("records.jsonl"), "iteration:seconds.total", &o, P("b3.png")),
      P("b3.png"), "no record");
  f = fopen(P("broken.jsonl"), "w");
  if (f) fputs("{\"cells\":1,\"ms_per_step\":2}\n{oops\n", f), fclose(f);
  bad("a line that is not JSON", sessile_render_plot_records(P("broken.jsonl"), "steps", &o, P("b4.png")), P("b4.png"), "line 2");
  o.height = 0;
  bad("size 0", sessile_render_plot(&p, &o, P("b5.png")), P("b5.png"), "800 x 0");
  o.height = 100000;
  bad("size 100000", sessile_render_plot(&p, &o, P("b6.png")), P("b6.png"), "100000");
  sessile_render2d_opts_default(&o);
  double nan1[1] = {NAN};
  sessile_plot pn = {"", "", "", 1, {{"", nan1, nan1, 1, 0, NULL, NULL}}, NULL};
  bad("only NaN points", sessile_render_plot(&pn, &o, P("b7.png")), P("b7.png"), "nothing to plot");
  return t_finish(NULL);
}
