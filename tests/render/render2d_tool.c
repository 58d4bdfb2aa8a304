/* A small driver of the 2-D pictures (sessile/render/render2d.h) by hand; `sessile
 * render` draws slices and runs, and this also makes contact sheets of any PNGs:
 *   render2d_tool slice EXR CHANNEL OUT.png [PLY]
 *   render2d_tool plot RECORDS.jsonl WHAT OUT.png
 *   render2d_tool steps STEPS.csv OUT.png      (sds/steps.csv: ms per step and cells against time)
 *   render2d_tool sheet OUT.png COLS PNG CAPTION [PNG CAPTION ...]
 * Exit 2 with one line on bad input, like the CLI. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/render/render2d.h"

int main(int argc, char **argv) {
  sessile_status st = SESSILE_ERR_USAGE;
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  if (argc >= 5 && !strcmp(argv[1], "slice")) {
    if (argc >= 6) o.outline_ply = argv[5];
    st = sessile_render_slice(argv[2], argv[3], &o, argv[4]);
  } else if (argc == 5 && !strcmp(argv[1], "plot")) {
    st = sessile_render_plot_records(argv[2], argv[3], &o, argv[4]);
  } else if (argc == 4 && !strcmp(argv[1], "steps")) {
    st = sessile_render_plot_sds_steps(argv[2], &o, argv[3]);
  } else if (argc >= 6 && !strcmp(argv[1], "sheet") && argc % 2 == 0) {
    int n = (argc - 4) / 2;
    const char *paths[64], *caps[64];
    for (int k = 0; k < n && k < 64; k++) paths[k] = argv[4 + 2 * k], caps[k] = argv[5 + 2 * k];
    st = sessile_render_contact_sheet(paths, caps, n > 64 ? 64 : n, atoi(argv[3]), argv[2]);
  } else {
    fprintf(stderr, "usage: render2d_tool slice EXR CHANNEL OUT [PLY] | plot RECORDS WHAT OUT | steps CSV OUT | sheet OUT COLS PNG CAPTION...\n");
    return 2;
  }
  if (st != SESSILE_OK) {
    fprintf(stderr, "render2d_tool: error: %s\n", sessile_error_message());
    return st == SESSILE_ERR_USAGE ? 2 : 1;
  }
  return 0;
}
