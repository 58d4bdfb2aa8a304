/* sessile io — the colour view of an EXR slice (exr_view.c; not public). */
#ifndef SESSILE_EXR_VIEW_H
#define SESSILE_EXR_VIEW_H
#include <stddef.h>

/* The map and value range the view uses. */
typedef struct exr_view {
  const char *map; /* "viridis" or "coolwarm" */
  double lo, hi;   /* lo == hi: a constant (or no finite) value */
} exr_view;

/* The map and range for the values v[0..n), as `render --color-by` picks them. */
void exr_view_pick(const float *v, size_t n, exr_view *out);
/* Linear-light r, g, b of each value (NaN and infinities grey). */
void exr_view_fill(const exr_view *view, const float *v, size_t n, float *r, float *g, float *b);

#endif
