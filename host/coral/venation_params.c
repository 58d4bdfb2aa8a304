/* The venation generator's parameter table (sessile/coral/venation.h): every
 * parameter with its unit, range, the paper's name for it (Coralize §3.2, or
 * Runions et al. 2005) or "ours", and its meaning (docs/venation.md). */
#include <math.h>
#include <stddef.h>
#include "venation_internal.h"

#define P(f) offsetof(sessile_venation_params, f)
#define LO SESSILE_PARAM_LO_OPEN

static const char *const geometry_names[] = {"tubes", "weld", NULL};
static const char *const search_names[] = {"gpu", "host", NULL};

static const sessile_param_desc descs[] = {
    {"open", SESSILE_PT_BOOL, P(open), 1, 0, 1, 0, "", "Open Ended",
     "true: open venation (each auxin attracts its nearest vein node, a tree); false: closed "
     "(each auxin attracts its relative neighbourhood, veins rejoin)", NULL},
    {"planar", SESSILE_PT_BOOL, P(planar), 1, 0, 1, 0, "", "2D",
     "true: auxins in a leaf blade in the x-z plane (a sea fan); false: in a 3-D box", NULL},
    {"auxins_per_iteration", SESSILE_PT_INT, P(auxins_per_iteration), 30, 1, 100000, 0, "", "Auxins per iteration",
     "candidate auxins thrown per iteration (dart throwing: those too close to a vein or an auxin are dropped)", NULL},
    {"initial_width", SESSILE_PT_REAL, P(initial_width), 2, 0, 1e4, LO, "cm", "Initial width",
     "blade (box) width before the first iteration", NULL},
    {"width_increment", SESSILE_PT_REAL, P(width_increment), 0.25, 0, 1e3, 0, "cm", "Width increment",
     "marginal growth: width added per iteration", NULL},
    {"aspect", SESSILE_PT_REAL, P(aspect), 1, 0, 100, LO, "", "ours",
     "blade (box) height / width", NULL},
    {"depth_ratio", SESSILE_PT_REAL, P(depth_ratio), 1, 0, 100, LO, "", "ours",
     "3-D box (planar = false): depth / width", NULL},
    {"left_1x", SESSILE_PT_REAL, P(left_1x), -0.7, -10, 10, 0, "width", "Shape",
     "left Bezier curve (base to tip): first inner control point, x in widths", NULL},
    {"left_1z", SESSILE_PT_REAL, P(left_1z), 0.15, 0, 1, 0, "height", "Shape",
     "left curve: first inner control point, z in heights (0 <= 1z <= 2z <= 1)", NULL},
    {"left_2x", SESSILE_PT_REAL, P(left_2x), -0.75, -10, 10, 0, "width", "Shape",
     "left curve: second inner control point, x", NULL},
    {"left_2z", SESSILE_PT_REAL, P(left_2z), 0.95, 0, 1, 0, "height", "Shape",
     "left curve: second inner control point, z", NULL},
    {"right_1x", SESSILE_PT_REAL, P(right_1x), 0.7, -10, 10, 0, "width", "Shape",
     "right Bezier curve: first inner control point, x in widths", NULL},
    {"right_1z", SESSILE_PT_REAL, P(right_1z), 0.15, 0, 1, 0, "height", "Shape",
     "right curve: first inner control point, z in heights", NULL},
    {"right_2x", SESSILE_PT_REAL, P(right_2x), 0.75, -10, 10, 0, "width", "Shape",
     "right curve: second inner control point, x", NULL},
    {"right_2z", SESSILE_PT_REAL, P(right_2z), 0.95, 0, 1, 0, "height", "Shape",
     "right curve: second inner control point, z", NULL},
    {"kill_radius", SESSILE_PT_REAL, P(kill_radius), 0.25, 0, 1e3, LO, "cm", "Auxin Kill Radius",
     "an auxin is consumed when a vein node comes within this distance", NULL},
    {"birth_distance", SESSILE_PT_REAL, P(birth_distance), 0.6, 0, 1e3, LO, "cm", "Runions: birth distance",
     "a candidate auxin closer than this to a vein node or an auxin is dropped (>= kill_radius)", NULL},
    {"vein_step", SESSILE_PT_REAL, P(vein_step), 0.2, 0, 1e3, LO, "cm", "Vein Radius",
     "the vein's growth in length per iteration (<= kill_radius, so a vein cannot step over an auxin forever)", NULL},
    {"influence_radius", SESSILE_PT_REAL, P(influence_radius), 2, 0, 1e4, LO, "cm", "ours",
     "closed venation: vein nodes farther than this from an auxin are not candidates of its relative neighbourhood "
     "(the nearest node always is)", NULL},
    {"merge_distance", SESSILE_PT_REAL, P(merge_distance), 0.08, 0, 1e3, 0, "cm", "ours",
     "closed venation: a new node this close to an existing one joins it instead (a cycle); < vein_step", NULL},
    {"thickness_0", SESSILE_PT_REAL, P(thickness[0]), 0.04, 0, 100, LO, "cm", "Thickness",
     "thickness curve (piecewise linear): radius at normalised thickness index 0 (the tips)", NULL},
    {"thickness_1", SESSILE_PT_REAL, P(thickness[1]), 0.2, 0, 100, LO, "cm", "Thickness",
     "radius at normalised thickness index 1/3", NULL},
    {"thickness_2", SESSILE_PT_REAL, P(thickness[2]), 0.3, 0, 100, LO, "cm", "Thickness",
     "radius at normalised thickness index 2/3", NULL},
    {"thickness_3", SESSILE_PT_REAL, P(thickness[3]), 0.4, 0, 100, LO, "cm", "Thickness",
     "radius at normalised thickness index 1 (the root)", NULL},
    {"mesh_detail", SESSILE_PT_INT, P(mesh_detail), 8, 3, 64, 0, "", "Mesh detail",
     "sides of each vein's tube", NULL},
    {"geometry", SESSILE_PT_ENUM, P(geometry), 0, 0, 1, 0, "", "ours",
     "tubes: one closed tube per vein segment (Coralize's way); weld: one welded surface (GPU)", geometry_names},
    {"weld_cell", SESSILE_PT_REAL, P(weld_cell), 0.05, 0, 100, LO, "cm", "ours",
     "geometry = weld: grid spacing", NULL},
    {"weld_blend", SESSILE_PT_REAL, P(weld_blend), 0.05, 0, 100, 0, "cm", "ours",
     "geometry = weld: smooth-union radius at junctions", NULL},
    {"search", SESSILE_PT_ENUM, P(search), 0, 0, 1, 0, "", "ours",
     "who finds each auxin's nearest vein node: gpu (the kernel) or host (the same grid search in C; "
     "same answer in fp64)", search_names},
};

/* Bernstein coefficients of z must not decrease, so z(t) is monotone and a
 * height crosses each curve once. */
static sessile_status validate(const void *values) {
  const sessile_venation_params *p = values;
  SESSILE_CHECK(p->birth_distance >= p->kill_radius, SESSILE_ERR_USAGE,
                "birth_distance (%g cm) must be at least kill_radius (%g cm): new auxins would be consumed at once",
                p->birth_distance, p->kill_radius);
  SESSILE_CHECK(p->vein_step <= p->kill_radius, SESSILE_ERR_USAGE,
                "vein_step (%g cm) must be at most kill_radius (%g cm): a vein could step over an auxin forever",
                p->vein_step, p->kill_radius);
  SESSILE_CHECK(p->merge_distance < p->vein_step, SESSILE_ERR_USAGE,
                "merge_distance (%g cm) must be less than vein_step (%g cm)", p->merge_distance, p->vein_step);
  SESSILE_CHECK(p->left_1z <= p->left_2z && p->right_1z <= p->right_2z, SESSILE_ERR_USAGE,
                "the blade's curves must rise from base to tip: left_1z <= left_2z and right_1z <= right_2z");
  /* an empty blade: the curves enclose (almost) nothing */
  if (p->planar) {
    double area = 0;
    for (int k = 0; k < 256; k++) {
      double xl, xr;
      venation_blade_span(p, (k + 0.5) / 256, &xl, &xr);
      area += xr > xl ? (xr - xl) / 256 : 0;
    }
    SESSILE_CHECK(area > 1e-3, SESSILE_ERR_USAGE,
                  "the leaf blade is empty: its Bezier curves enclose %.2g of width x height (the right curve "
                  "must lie right of the left one)", area);
  }
  return SESSILE_OK;
}

const sessile_param_table sessile_venation_param_table = {
    "coral venation", sizeof(sessile_venation_params), (int)(sizeof descs / sizeof descs[0]), descs, validate, NULL, NULL};
