#!/usr/bin/python3
# Writes host/io/colormap.c: 256-entry tables of matplotlib's viridis,
# magma and coolwarm (published data), rounded to 8 bits.  Not part of the
# build; run from the repository root with Debian's python3-matplotlib when
# a map is added.
import matplotlib
from matplotlib import colormaps
out=[]
out.append('''/* Colour maps for sessile's pictures: 256 entries each, 8-bit sRGB.
 *
 * Tabulated from matplotlib %s (colormaps["viridis"|"magma"|"coolwarm"]
 * sampled at entry i of 256 and rounded to 8 bits): viridis and magma by
 * Stefan van der Walt and Nathaniel Smith (perceptually uniform, CC0);
 * coolwarm by Kenneth Moreland, "Diverging Color Maps for Scientific
 * Visualization" (ISVC 2009).  Tables of published data, not code. */
#include <math.h>
#include <string.h>
#include "sessile/io/colormap.h"
''' % matplotlib.__version__)
for name in ["viridis","magma","coolwarm"]:
    cm=colormaps[name]
    assert cm.N==256
    out.append("static const unsigned char %s_table[256][3] = {" % name)
    rows=[]
    for i in range(256):
        r,g,b,a=cm(i)
        rows.append("{%d, %d, %d}" % (round(r*255),round(g*255),round(b*255)))
    for k in range(0,256,6):
        out.append("    "+", ".join(rows[k:k+6])+",")
    out.append("};\n")
out.append('''static const struct {
  const char *name;
  const unsigned char (*table)[3];
  int diverging;
} maps[] = {
    {"viridis", viridis_table, 0},
    {"magma", magma_table, 0},
    {"coolwarm", coolwarm_table, 1},
};

static int find(const char *name) {
  if (!name) return -1;
  for (int i = 0; i < (int)(sizeof maps / sizeof maps[0]); i++)
    if (strcmp(maps[i].name, name) == 0) return i;
  return -1;
}

int sessile_colormap_known(const char *name) { return find(name) >= 0; }
const char *sessile_colormap_names(void) { return "viridis, magma, coolwarm"; }
int sessile_colormap_diverging(const char *name) {
  int i = find(name);
  return i >= 0 && maps[i].diverging;
}

/* Entry floor(256 t), clamped: matplotlib's own lookup for N = 256. */
int sessile_colormap(const char *name, double t, unsigned char rgb[3]) {
  int m = find(name);
  if (m < 0) return -1;
  if (!(t == t)) t = 0; /* NaN: the low end */
  if (t < 0) t = 0;
  if (t > 1) t = 1;
  int i = (int)floor(t * 256.0);
  if (i > 255) i = 255;
  memcpy(rgb, maps[m].table[i], 3);
  return 0;
}
''')
open("host/io/colormap.c","w").write("\n".join(out))
