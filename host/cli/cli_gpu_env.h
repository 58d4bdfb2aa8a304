/* The environment's say in the GPU context's options.  Only the CLI (and the
 * test programs, which compile this file too) read environment variables: the
 * library takes every choice as an argument (docs/design.md, "Environment"). */
#ifndef SESSILE_CLI_GPU_ENV_H
#define SESSILE_CLI_GPU_ENV_H
#include <stddef.h>
#include "sessile/gpu/gpu.h"

/* Room for the default pipeline cache folder that cli_gpu_env writes. */
typedef struct { char cache_default[4096]; } cli_gpu_env_store;

/* Fills what o leaves unchosen from the environment: device (NULL) from
 * SESSILE_DEVICE, validation (-1) from SESSILE_VALIDATION, precision (0) from
 * SESSILE_PRECISION (SESSILE_ERR_USAGE unless 32, 64, fp32 or fp64), staged
 * from SESSILE_STAGED, and the default cache folder from XDG_CACHE_HOME
 * (absolute only) or HOME, written into *st (which must outlive o's use). */
sessile_status cli_gpu_env(sessile_gpu_options *o, cli_gpu_env_store *st);

/* device, or SESSILE_DEVICE when device is NULL or "". */
const char *cli_env_device(const char *device);

#endif
