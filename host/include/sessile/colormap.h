/* sessile — colour maps for pictures (host/render/colormap.c).
 *
 * viridis and magma (perceptually uniform, for one-signed fields) and
 * coolwarm (diverging, for signed fields centred at 0), 256 entries each as
 * matplotlib ships them. */
#ifndef SESSILE_COLORMAP_H
#define SESSILE_COLORMAP_H

#ifdef __cplusplus
extern "C" {
#endif

/* The colour of t in [0, 1] (clamped) on map `name`, as 8-bit sRGB.  An
 * unknown name or a NaN t gives mid grey (128, 128, 128). */
void sessile_colormap(const char *name, double t, unsigned char rgb[3]);

/* 1 when `name` is a map sessile_colormap knows, else 0. */
int sessile_colormap_known(const char *name);

/* The known names, for messages: "viridis, magma, coolwarm". */
const char *sessile_colormap_names(void);

#ifdef __cplusplus
}
#endif
#endif
