/* PLACEHOLDER until the welded surface lands (replaced by its owner). */
#include "sessile/skeleton.h"
sessile_status sessile_skeleton_weld(sessile_gpu *g, const sessile_skeleton *s, const sessile_weld_params *p,
                                     sessile_surface *out, double **vertex_value) {
  (void)g, (void)s, (void)p, (void)out, (void)vertex_value;
  return sessile_error_set(SESSILE_ERR_USAGE, "the welded surface is not built yet");
}
sessile_status sessile_skeleton_weld_ref(const sessile_skeleton *s, const sessile_weld_params *p,
                                         sessile_surface *out, double **vertex_value) {
  (void)s, (void)p, (void)out, (void)vertex_value;
  return sessile_error_set(SESSILE_ERR_USAGE, "the welded surface is not built yet");
}
