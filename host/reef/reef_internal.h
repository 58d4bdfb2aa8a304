/* The reef's private parts: the spatial grid of footprints (place_grid.c)
 * and the placement helpers shared by the brushes and growth. */
#ifndef SESSILE_REEF_INTERNAL_H
#define SESSILE_REEF_INTERNAL_H
#include "sessile/reef/reef.h"

/* Footprints (disc centre x, y and radius) in a uniform grid over the
 * seabed: a cell per `cell` metres, chained lists (head per cell, next per
 * placement). */
typedef struct reef_grid {
  double cell, rmax;
  uint32_t gx, gy;
  uint32_t *head, *next;
  uint32_t cap;
} reef_grid;

sessile_status reef_grid_init(reef_grid *g, const sessile_reef_scene *s);
/* Adds placement k of pl (its footprint). */
sessile_status reef_grid_add(reef_grid *g, const sessile_reef_placements *pl, uint32_t k);
/* Whether a disc (x, y, r) overlaps a footprint of pl in the grid. */
int reef_grid_overlaps(const reef_grid *g, const sessile_reef_placements *pl, double x, double y, double r);
void reef_grid_free(reef_grid *g);

/* Fills p's position, up axis and depth at (x, y) for entry e; 0 when off
 * the seabed or outside e's depth band. */
int reef_site(const sessile_reef_scene *s, const sessile_reef_seabed *b, const sessile_reef_entry *e, double x,
              double y, sessile_reef_placement *p);
/* Random rotations from one stream (three draws whichever axes rotate). */
void reef_angles(const sessile_reef_entry *e, uint64_t *rng, double angle[3]);
/* seabed.mesh of the scene (seabed_mesh.c): s->heights, res and extent. */
struct rj_obj;
sessile_status reef_seabed_mesh(const struct rj_obj *o, sessile_reef_scene *s);
/* seabed.image (seabed_image.c): s->heights, res, extent, base, height_scale. */
sessile_status reef_seabed_image(const struct rj_obj *o, sessile_reef_scene *s);
sessile_status reef_push(sessile_reef_placements *pl, const sessile_reef_placement *p);
#endif
