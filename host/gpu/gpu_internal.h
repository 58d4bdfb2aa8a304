/* Internal definitions shared by the files of host/gpu (not public API). */
#ifndef SESSILE_GPU_INTERNAL_H
#define SESSILE_GPU_INTERNAL_H

#include <vulkan/vulkan.h>
#include "sessile/gpu/gpu.h"

/* Where the validation messenger reports (instance.c): every warning and
 * error is counted, then handed to fn (NULL: printed to stderr). */
typedef struct sessile_validation_sink_ {
  uint64_t count;
  sessile_validation_fn fn;
  void *user;
} sessile_validation_sink_;

struct sessile_gpu {
  VkInstance instance;
  VkDebugUtilsMessengerEXT messenger;
  VkPhysicalDevice phys;
  VkDevice device;
  VkQueue queue;
  uint32_t queue_family;
  /* A queue with graphics for the renderer (graphics*.c): the compute queue
   * when its family has graphics, else one of the first graphics family;
   * gfx_queue is VK_NULL_HANDLE on a compute-only device. */
  VkQueue gfx_queue;
  uint32_t gfx_family;
  VkCommandPool pool; /* for internal one-shot transfers */
  /* Kept between blocking transfers (buffer.c, context.c): on a discrete GPU
   * each vkAllocateMemory and vkCreateFence is a driver call of 0.1-1 ms, and
   * a loop that moves a few small arrays per step paid it every transfer.
   * staging is the buffer of staged transfers up to SESSILE_STAGING_KEEP_
   * bytes (larger ones use a temporary); fence, that of sessile_gpu_submit_wait_.
   * A context is used by one host thread at a time, so one of each serves. */
  struct sessile_buffer *staging;
  VkFence fence;
  int staged_only; /* options.staged (the CLI's $SESSILE_STAGED): device buffers are never mapped (context.c) */
  VkPipelineCache pipeline_cache;
  char cache_path[1024]; /* "" when the on-disk cache is off */
  VkPhysicalDeviceMemoryProperties mem;
  VkPhysicalDeviceLimits limits;
  sessile_gpu_info info;
  sessile_validation_sink_ validation;
  /* sessile_gpu_profile: on, the per-kernel table, untimed dispatches */
  int prof_on;
  sessile_kernel_time *prof;
  size_t nprof, cap_prof;
  uint64_t prof_untimed;
  uint64_t submissions; /* vkQueueSubmit calls so far (sessile_gpu_submissions) */
};
/* The staged-transfer buffer kept by a context (buffer.c), freed with it. */
#define SESSILE_STAGING_KEEP_ ((size_t)64 << 20)
void sessile_gpu_staging_free_(sessile_gpu *g);
/* Adds one timed call of kernel `name` (cmd.c, after a profiled submission). */
sessile_status sessile_gpu_profile_add_(sessile_gpu *g, const char *name, double ms);

struct sessile_buffer {
  sessile_gpu *gpu;
  VkBuffer buffer;
  VkDeviceMemory memory;
  size_t bytes;
  void *mapped; /* non-NULL when host-visible */
  int coherent;
  VkBufferView view[4]; /* whole-buffer texel views by sessile_binding_kind, made on first use */
};

struct sessile_kernel {
  sessile_gpu *gpu;
  VkShaderModule module;
  VkDescriptorSetLayout set_layout;
  VkPipelineLayout layout;
  VkPipeline pipeline;
  uint32_t nbuffers, push_bytes, local_size;
  uint8_t texel[SESSILE_MAX_BINDINGS]; /* sessile_binding_kind of each binding */
  char name[64];
};

/* Makes kernel k's pipeline if it has none yet (kernel.c: at its first
 * dispatch, not at its creation). */
sessile_status sessile_kernel_pipeline(sessile_kernel *k);

/* Name of a VkResult ("VK_ERROR_DEVICE_LOST"). */
const char *sessile_vk_result_name(VkResult r);

/* Checks a Vulkan call: on failure records "CALL failed: VK_...; HINT" and
 * returns SESSILE_ERR_VULKAN (or SESSILE_ERR_NO_MEMORY for out-of-memory). */
sessile_status sessile_vk_fail_(VkResult r, const char *call, const char *func);
#define SESSILE_VK(call)                                                       \
  do {                                                                         \
    VkResult sessile_vk_r_ = (call);                                           \
    if (sessile_vk_r_ < 0) return sessile_vk_fail_(sessile_vk_r_, #call, __func__); \
  } while (0)

/* Memory type with all of `want` among `bits`, or UINT32_MAX. */
uint32_t sessile_gpu_memory_type_(const sessile_gpu *g, uint32_t bits, VkMemoryPropertyFlags want);

/* One-shot command buffer for transfers. */
sessile_status sessile_gpu_oneshot_begin_(sessile_gpu *g, VkCommandBuffer *cb);
sessile_status sessile_gpu_oneshot_end_(sessile_gpu *g, VkCommandBuffer cb);
/* Submits cb to queue q and waits on a fence; *what names the call that
 * failed (the caller frees cb and reports). */
VkResult sessile_gpu_submit_wait_(sessile_gpu *g, VkQueue q, VkCommandBuffer cb, const char **what);

/* Pipeline cache persistence (pipeline_cache.c). */
sessile_status sessile_pipeline_cache_open_(sessile_gpu *g, const char *dir, const char *default_dir);
void sessile_pipeline_cache_close_(sessile_gpu *g);

#endif
