/* On-disk VkPipelineCache: lavapipe compiles every pipeline through LLVM
 * (tens of ms each), so reusing compiled pipelines across runs matters.  The
 * file is keyed by vendor, device and pipelineCacheUUID, and written
 * atomically (temp file + rename).  A cache that cannot be read or written is
 * not an error: we only lose speed, and say nothing. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "gpu_internal.h"

static int mkdirs(const char *path) {
  char tmp[1024];
  snprintf(tmp, sizeof tmp, "%s", path);
  for (char *p = tmp + 1; *p; p++) {
    if (*p != '/') continue;
    *p = 0;
    if (mkdir(tmp, 0755) != 0 && errno != EEXIST) return -1;
    *p = '/';
  }
  return (mkdir(tmp, 0755) == 0 || errno == EEXIST) ? 0 : -1;
}

static void cache_path(sessile_gpu *g, const char *dir) {
  char base[768] = "";
  g->cache_path[0] = 0;
  if (dir && !*dir) return; /* disabled */
  if (dir) snprintf(base, sizeof base, "%s", dir);
  else if (getenv("XDG_CACHE_HOME") && *getenv("XDG_CACHE_HOME"))
    snprintf(base, sizeof base, "%s/sessile", getenv("XDG_CACHE_HOME"));
  else if (getenv("HOME") && *getenv("HOME"))
    snprintf(base, sizeof base, "%s/.cache/sessile", getenv("HOME"));
  else return;
  if (mkdirs(base) != 0) return;
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(g->phys, &p);
  char uuid[2 * VK_UUID_SIZE + 1];
  for (unsigned i = 0; i < VK_UUID_SIZE; i++) snprintf(uuid + 2 * i, 3, "%02x", p.pipelineCacheUUID[i]);
  snprintf(g->cache_path, sizeof g->cache_path, "%s/pipelines-%04x-%04x-%s.bin", base,
           p.vendorID, p.deviceID, uuid);
}

sessile_status sessile_pipeline_cache_open_(sessile_gpu *g, const char *dir) {
  cache_path(g, dir);
  void *data = NULL;
  size_t size = 0;
  FILE *f = g->cache_path[0] ? fopen(g->cache_path, "rb") : NULL;
  if (f) {
    if (fseek(f, 0, SEEK_END) == 0) {
      long n = ftell(f);
      if (n > 0 && fseek(f, 0, SEEK_SET) == 0 && (data = malloc((size_t)n)) != NULL) {
        size = fread(data, 1, (size_t)n, f);
        if (size != (size_t)n) size = 0;
      }
    }
    fclose(f);
  }
  VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
                                  .initialDataSize = size,
                                  .pInitialData = size ? data : NULL};
  VkResult r = vkCreatePipelineCache(g->device, &ci, NULL, &g->pipeline_cache);
  if (r < 0 && size) { /* the driver rejected stale data: start empty */
    ci.initialDataSize = 0;
    ci.pInitialData = NULL;
    r = vkCreatePipelineCache(g->device, &ci, NULL, &g->pipeline_cache);
  }
  free(data);
  if (r < 0) return sessile_vk_fail_(r, "vkCreatePipelineCache", __func__);
  return SESSILE_OK;
}

void sessile_pipeline_cache_close_(sessile_gpu *g) {
  if (!g->pipeline_cache) return;
  size_t size = 0;
  void *data = NULL;
  if (g->cache_path[0] &&
      vkGetPipelineCacheData(g->device, g->pipeline_cache, &size, NULL) == VK_SUCCESS && size &&
      (data = malloc(size)) != NULL &&
      vkGetPipelineCacheData(g->device, g->pipeline_cache, &size, data) == VK_SUCCESS) {
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", g->cache_path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    int ok = f && fwrite(data, 1, size, f) == size;
    if (f) ok = (fclose(f) == 0) && ok;
    if (ok) ok = rename(tmp, g->cache_path) == 0;
    if (!ok) remove(tmp);
  }
  free(data);
  vkDestroyPipelineCache(g->device, g->pipeline_cache, NULL);
  g->pipeline_cache = VK_NULL_HANDLE;
}
