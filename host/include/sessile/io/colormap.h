/* sessile — colour maps (256-entry tables from matplotlib's published data:
 * viridis and magma, perceptually uniform; coolwarm, diverging, for signed
 * ranges).  Shared by the mesh renderer and the 2-D pictures. */
#ifndef SESSILE_COLORMAP_H
#define SESSILE_COLORMAP_H

#ifdef __cplusplus
extern "C" {
#endif

/* The colour of t in [0, 1] (clamped; NaN reads as 0) in map `name` as 8-bit
 * sRGB: entry floor(256 t) of 256, as matplotlib looks it up.  Returns 0, or
 * -1 for an unknown name (rgb untouched). */
int sessile_colormap(const char *name, double t, unsigned char rgb[3]);
/* 1 when `name` is a known map. */
int sessile_colormap_known(const char *name);
/* 1 for a diverging map (meant for ranges symmetric about 0). */
int sessile_colormap_diverging(const char *name);
/* "viridis, magma, coolwarm": for messages. */
const char *sessile_colormap_names(void);

#ifdef __cplusplus
}
#endif
#endif
