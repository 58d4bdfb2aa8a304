/* The environment variables that choose the GPU context (cli_gpu_env.h). */
#include "cli_gpu_env.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *cli_env_device(const char *device) {
  return device && *device ? device : getenv("SESSILE_DEVICE");
}

static int env_on(const char *name) {
  const char *e = getenv(name);
  return e && *e && strcmp(e, "0") != 0;
}

sessile_status cli_gpu_env(sessile_gpu_options *o, cli_gpu_env_store *st) {
  if (!o->device || !*o->device) o->device = getenv("SESSILE_DEVICE");
  if (o->validation < 0) o->validation = env_on("SESSILE_VALIDATION");
  const char *e = getenv("SESSILE_PRECISION");
  if (o->precision == 0 && e && *e) {
    SESSILE_CHECK(strcmp(e, "32") == 0 || strcmp(e, "64") == 0 || strcmp(e, "fp32") == 0 ||
                      strcmp(e, "fp64") == 0,
                  SESSILE_ERR_USAGE, "SESSILE_PRECISION=%s: use 32 or 64", e);
    o->precision = strstr(e, "32") ? 32 : 64;
  }
  /* SESSILE_STAGED=1 takes a discrete GPU's paths on unified memory too, so
   * that the tests on lavapipe cover them (tests/CMakeLists.txt, *_staged). */
  if (env_on("SESSILE_STAGED")) o->staged = 1;
  if (!o->cache_default) {
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n = -1;
    if (xdg && xdg[0] == '/') /* XDG: relative values are ignored */
      n = snprintf(st->cache_default, sizeof st->cache_default, "%s/sessile", xdg);
    else if (home && *home)
      n = snprintf(st->cache_default, sizeof st->cache_default, "%s/.cache/sessile", home);
    /* too long: no default cache rather than a cut path */
    if (n > 0 && (size_t)n < sizeof st->cache_default) o->cache_default = st->cache_default;
  }
  return SESSILE_OK;
}
