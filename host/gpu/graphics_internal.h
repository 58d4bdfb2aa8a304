/* The structs behind graphics.h (host/gpu/graphics*.c only). */
#ifndef SESSILE_GPU_GRAPHICS_INTERNAL_H
#define SESSILE_GPU_GRAPHICS_INTERNAL_H
#include "gpu_internal.h"

typedef struct sessile_gfx_image {
  VkImage image;
  VkDeviceMemory memory;
  VkImageView view;
} sessile_gfx_image;

struct sessile_gfx_target {
  sessile_gpu *gpu;
  uint32_t width, height, samples;
  sessile_gfx_image color, depth, resolve; /* resolve only when samples > 1 */
  VkRenderPass pass;
  VkFramebuffer framebuffer;
  VkBuffer readback;
  VkDeviceMemory readback_mem;
  void *readback_ptr;
  int readback_coherent;
  VkCommandPool pool; /* on the graphics family */
  VkCommandBuffer cb[2]; /* draw, copy */
  VkFence fence;
};

struct sessile_gfx_pipeline {
  sessile_gpu *gpu;
  VkPipelineLayout layout;
  VkPipeline pipeline;
  uint32_t push_bytes;
};

struct sessile_gfx_buffer {
  sessile_gpu *gpu;
  VkBuffer buffer;
  VkDeviceMemory memory;
  size_t bytes;
};

#endif
