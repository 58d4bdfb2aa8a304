/* preview.png at the end of every generator's run (cli_run.h,
 * docs/render.md "Preview"): a convenience, so a device that cannot draw or
 * a picture that fails costs one warning, never the run. */
#include <stdio.h>
#include "cli_run.h"
#include "sessile/render/render_run.h"

void cli_run_preview(const char *cmd, const cli_run_args *a, sessile_run *run, const char *mesh_rel,
                     sessile_gpu *g, const cli_gpu_opts *go) {
  static int warned; /* once per process */
  if (a->no_preview || !run) return;
  char mesh[4096], png[4096];
  sessile_status s = sessile_run_file(run, mesh_rel, mesh, sizeof mesh);
  if (s == SESSILE_OK) s = sessile_run_file(run, "preview.png", png, sizeof png);
  sessile_gpu *own = NULL;
  if (s == SESSILE_OK && !g) {
    cli_gpu_opts def = {0};
    s = cli_gpu_create(go ? go : &def, &own);
    g = own;
  }
  if (s == SESSILE_OK) s = sessile_render_preview(g, mesh, png);
  sessile_gpu_destroy(own);
  if (s == SESSILE_OK) return;
  if (!warned)
    fprintf(stderr, "sessile %s: warning: no preview.png (the run is complete): %s\n", cmd, sessile_error_message());
  warned = 1;
  sessile_run_remove_file(run, "preview.png");
}
