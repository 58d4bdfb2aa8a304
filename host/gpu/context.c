/* The compute context: instance, chosen device, one compute queue, a command
 * pool for transfers, and the pipeline cache. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "device_info.h"

void sessile_gpu_options_default(sessile_gpu_options *o) {
  memset(o, 0, sizeof *o);
  o->validation = -1;
}

double sessile_wall_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static sessile_status resolve_precision(int asked, int float64, const char *name, int *out) {
  if (asked == 0) asked = float64 ? 64 : 32;
  SESSILE_CHECK(asked == 32 || asked == 64, SESSILE_ERR_USAGE,
                "precision %d is not supported: use 32 or 64", asked);
  SESSILE_CHECK(asked == 32 || float64, SESSILE_ERR_UNSUPPORTED,
                "fp64 was asked for but %s has no shaderFloat64: use precision 32 "
                "(mixed-precision iterative refinement)", name);
  *out = asked;
  return SESSILE_OK;
}

/* The compute family when it has graphics, else the first graphics family, else -1. */
static int graphics_queue_family(VkPhysicalDevice p, uint32_t compute_family) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(p, &n, NULL);
  VkQueueFamilyProperties q[32];
  if (n > 32) n = 32;
  vkGetPhysicalDeviceQueueFamilyProperties(p, &n, q);
  if (compute_family < n && (q[compute_family].queueFlags & VK_QUEUE_GRAPHICS_BIT))
    return (int)compute_family;
  for (uint32_t i = 0; i < n; i++)
    if (q[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) return (int)i;
  return -1;
}

static sessile_status create_device(sessile_gpu *g) {
  uint32_t ts_bits = 0;
  int fam = sessile_compute_queue_family_(g->phys, &ts_bits);
  SESSILE_CHECK(fam >= 0, SESSILE_ERR_NO_DEVICE, "device has no compute queue");
  g->queue_family = (uint32_t)fam;
  if (ts_bits == 0) g->info.timestamp_period_ns = 0; /* no timestamps on this queue */
  float prio = 1.0f;
  VkDeviceQueueCreateInfo q[2] = {{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                   .queueFamilyIndex = g->queue_family,
                                   .queueCount = 1,
                                   .pQueuePriorities = &prio}};
  /* The renderer needs graphics; a dedicated compute family has none, so a
   * second queue of a graphics family is made beside it. */
  int gfam = graphics_queue_family(g->phys, g->queue_family);
  uint32_t nq = 1;
  if (gfam >= 0 && (uint32_t)gfam != g->queue_family) {
    q[1] = q[0];
    q[1].queueFamilyIndex = (uint32_t)gfam;
    nq = 2;
  }
  VkPhysicalDeviceFeatures feat = {0};
  feat.shaderFloat64 = g->info.precision == 64 ? VK_TRUE : VK_FALSE;
  feat.shaderInt64 = VK_FALSE;
  VkDeviceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                           .queueCreateInfoCount = nq,
                           .pQueueCreateInfos = q,
                           .pEnabledFeatures = &feat};
  SESSILE_VK(vkCreateDevice(g->phys, &ci, NULL, &g->device));
  vkGetDeviceQueue(g->device, g->queue_family, 0, &g->queue);
  if (gfam >= 0) {
    g->gfx_family = (uint32_t)gfam;
    vkGetDeviceQueue(g->device, g->gfx_family, 0, &g->gfx_queue);
  }
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = g->queue_family};
  SESSILE_VK(vkCreateCommandPool(g->device, &pi, NULL, &g->pool));
  return SESSILE_OK;
}

static sessile_status gpu_init(sessile_gpu *g, const sessile_gpu_options *o) {
  g->validation.fn = o->validation_message;
  g->validation.user = o->validation_user;
  SESSILE_CALL(sessile_instance_create_(o->validation, &g->validation, &g->instance,
                                        &g->messenger));
  uint32_t index = 0;
  SESSILE_CALL(sessile_choose_device_(g->instance, o->device, &g->phys, &index));
  sessile_describe_device_(g->phys, index, &g->info, &g->mem);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(g->phys, &props);
  g->limits = props.limits;
  /* staged: a discrete GPU's paths on unified memory too (device buffers
   * unmapped, transfers staged), so that the tests on lavapipe cover them
   * (tests/CMakeLists.txt, the *_staged tests). */
  if (o->staged) g->info.unified_memory = 0, g->staged_only = 1;
  SESSILE_CALL(resolve_precision(o->precision, g->info.float64, g->info.name, &g->info.precision));
  /* The reductions use subgroupAdd (fewer barriers on lavapipe); every
   * Vulkan 1.1 GPU driver we know of has it, but a device may not. */
  SESSILE_CHECK(g->info.subgroup_arithmetic, SESSILE_ERR_UNSUPPORTED,
                "device '%s' lacks subgroup arithmetic in compute shaders "
                "(VK_SUBGROUP_FEATURE_ARITHMETIC_BIT), which sessile's reductions need; "
                "choose another device with --device (see 'sessile devices')", g->info.name);
  SESSILE_CALL(create_device(g));
  SESSILE_CALL(sessile_pipeline_cache_open_(g, o->cache_dir, o->cache_default));
  return SESSILE_OK;
}

sessile_status sessile_gpu_create(const sessile_gpu_options *opt, sessile_gpu **out) {
  *out = NULL;
  sessile_gpu_options def;
  if (!opt) { sessile_gpu_options_default(&def); opt = &def; }
  sessile_gpu *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory creating the GPU context");
  sessile_status s = gpu_init(g, opt);
  if (s != SESSILE_OK) {
    sessile_gpu_destroy(g);
    return s;
  }
  *out = g;
  return SESSILE_OK;
}

void sessile_gpu_destroy(sessile_gpu *g) {
  if (!g) return;
  if (g->device) {
    vkDeviceWaitIdle(g->device); /* result irrelevant: we tear down either way */
    sessile_pipeline_cache_close_(g);
    sessile_gpu_staging_free_(g);
    if (g->fence) vkDestroyFence(g->device, g->fence, NULL);
    if (g->pool) vkDestroyCommandPool(g->device, g->pool, NULL);
    vkDestroyDevice(g->device, NULL);
  }
  sessile_instance_destroy_(g->instance, g->messenger);
  free(g->prof);
  free(g);
}

const sessile_gpu_info *sessile_gpu_info_of(const sessile_gpu *g) { return &g->info; }
uint64_t sessile_gpu_submissions(const sessile_gpu *g) { return g->submissions; }

sessile_status sessile_gpu_profile(sessile_gpu *g, int on) {
  SESSILE_CHECK(!on || g->info.timestamp_period_ns > 0, SESSILE_ERR_UNSUPPORTED,
                "%s has no timestamps on its compute queue: no kernel profile", g->info.name);
  if (on) g->nprof = 0, g->prof_untimed = 0;
  g->prof_on = on != 0;
  return SESSILE_OK;
}

size_t sessile_gpu_profile_read(const sessile_gpu *g, const sessile_kernel_time **out, uint64_t *untimed) {
  if (out) *out = g->prof;
  if (untimed) *untimed = g->prof_untimed;
  return g->nprof;
}

sessile_status sessile_gpu_profile_add_(sessile_gpu *g, const char *name, double ms) {
  size_t i = 0;
  while (i < g->nprof && strncmp(g->prof[i].name, name, sizeof g->prof[i].name - 1)) i++;
  if (i == g->nprof) {
    if (g->nprof == g->cap_prof) {
      size_t cap = g->cap_prof ? 2 * g->cap_prof : 32;
      sessile_kernel_time *p = realloc(g->prof, cap * sizeof *p);
      SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for the kernel profile");
      g->prof = p, g->cap_prof = cap;
    }
    memset(&g->prof[i], 0, sizeof g->prof[i]);
    snprintf(g->prof[i].name, sizeof g->prof[i].name, "%s", name);
    g->nprof++;
  }
  g->prof[i].calls++, g->prof[i].ms += ms;
  return SESSILE_OK;
}
uint64_t sessile_gpu_validation_count(const sessile_gpu *g) { return g->validation.count; }

uint32_t sessile_gpu_memory_type_(const sessile_gpu *g, uint32_t bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < g->mem.memoryTypeCount; i++)
    if ((bits & (1u << i)) && (g->mem.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

sessile_status sessile_gpu_oneshot_begin_(sessile_gpu *g, VkCommandBuffer *cb) {
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = g->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  SESSILE_VK(vkAllocateCommandBuffers(g->device, &ai, cb));
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  VkResult r = vkBeginCommandBuffer(*cb, &bi);
  if (r < 0) {
    vkFreeCommandBuffers(g->device, g->pool, 1, cb);
    return sessile_vk_fail_(r, "vkBeginCommandBuffer", __func__);
  }
  return SESSILE_OK;
}

VkResult sessile_gpu_submit_wait_(sessile_gpu *g, VkQueue q, VkCommandBuffer cb, const char **what) {
  VkResult r = VK_SUCCESS;
  *what = "vkCreateFence";
  if (!g->fence) {
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    r = vkCreateFence(g->device, &fi, NULL, &g->fence);
    if (r < 0) g->fence = VK_NULL_HANDLE;
  } else {
    r = vkResetFences(g->device, 1, &g->fence);
    *what = "vkResetFences";
  }
  if (r >= 0) {
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                       .pCommandBuffers = &cb};
    r = vkQueueSubmit(q, 1, &si, g->fence);
    *what = "vkQueueSubmit";
    g->submissions++;
  }
  if (r >= 0) {
    r = vkWaitForFences(g->device, 1, &g->fence, VK_TRUE, UINT64_MAX);
    *what = "vkWaitForFences";
  }
  return r;
}

sessile_status sessile_gpu_oneshot_end_(sessile_gpu *g, VkCommandBuffer cb) {
  VkResult r = vkEndCommandBuffer(cb);
  const char *what = "vkEndCommandBuffer";
  if (r >= 0) r = sessile_gpu_submit_wait_(g, g->queue, cb, &what);
  vkFreeCommandBuffers(g->device, g->pool, 1, &cb);
  if (r < 0) return sessile_vk_fail_(r, what, __func__);
  return SESSILE_OK;
}
