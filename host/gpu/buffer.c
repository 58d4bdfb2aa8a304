/* Storage buffers.  DEVICE buffers live in device-local memory and are filled
 * through a staging buffer, except on unified memory (CPU and integrated
 * devices) where the device-local memory is host-visible and mapped directly.
 * MAPPED buffers are host-visible and coherent (small readback buffers). */
#include <stdlib.h>
#include <string.h>
#include "gpu_internal.h"

static sessile_status alloc_buffer(sessile_gpu *g, size_t bytes, VkBufferUsageFlags usage,
                                   VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback,
                                   sessile_buffer *b) {
  b->gpu = g;
  b->bytes = bytes;
  VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = bytes,
                           .usage = usage,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  SESSILE_VK(vkCreateBuffer(g->device, &ci, NULL, &b->buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g->device, b->buffer, &req);
  uint32_t type = sessile_gpu_memory_type_(g, req.memoryTypeBits, want);
  if (type == UINT32_MAX) type = sessile_gpu_memory_type_(g, req.memoryTypeBits, fallback);
  SESSILE_CHECK(type != UINT32_MAX, SESSILE_ERR_UNSUPPORTED,
                "no suitable memory type for a %zu-byte buffer on %s", bytes, g->info.name);
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                             .allocationSize = req.size,
                             .memoryTypeIndex = type};
  VkResult r = vkAllocateMemory(g->device, &ai, NULL, &b->memory);
  if (r < 0)
    return sessile_error_set(r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY
                                 ? SESSILE_ERR_NO_MEMORY : SESSILE_ERR_VULKAN,
                             "vkAllocateMemory of %zu bytes failed with %s: use a smaller "
                             "problem or a device with more memory", bytes,
                             sessile_vk_result_name(r));
  SESSILE_VK(vkBindBufferMemory(g->device, b->buffer, b->memory, 0));
  VkMemoryPropertyFlags flags = g->mem.memoryTypes[type].propertyFlags;
  if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    SESSILE_VK(vkMapMemory(g->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    b->coherent = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  }
  return SESSILE_OK;
}

static void release(sessile_buffer *b) {
  if (!b || !b->gpu) return;
  VkDevice d = b->gpu->device;
  if (b->mapped) vkUnmapMemory(d, b->memory);
  for (int i = 0; i < 4; i++)
    if (b->view[i]) vkDestroyBufferView(d, b->view[i], NULL);
  if (b->buffer) vkDestroyBuffer(d, b->buffer, NULL);
  if (b->memory) vkFreeMemory(d, b->memory, NULL);
  memset(b, 0, sizeof *b);
}

static sessile_status copy_buffer(sessile_gpu *g, VkBuffer src, size_t so, VkBuffer dst, size_t dof,
                                  size_t bytes) {
  VkCommandBuffer cb;
  SESSILE_CALL(sessile_gpu_oneshot_begin_(g, &cb));
  VkBufferCopy region = {.srcOffset = so, .dstOffset = dof, .size = bytes};
  vkCmdCopyBuffer(cb, src, dst, 1, &region);
  return sessile_gpu_oneshot_end_(g, cb);
}

static sessile_status fill_zero(sessile_buffer *b) {
  if (b->mapped) {
    memset(b->mapped, 0, b->bytes);
    if (!b->coherent) {
      VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                               .memory = b->memory, .offset = 0, .size = VK_WHOLE_SIZE};
      SESSILE_VK(vkFlushMappedMemoryRanges(b->gpu->device, 1, &r));
    }
    return SESSILE_OK;
  }
  VkCommandBuffer cb;
  SESSILE_CALL(sessile_gpu_oneshot_begin_(b->gpu, &cb));
  vkCmdFillBuffer(cb, b->buffer, 0, VK_WHOLE_SIZE, 0);
  return sessile_gpu_oneshot_end_(b->gpu, cb);
}

sessile_status sessile_buffer_create(sessile_gpu *g, size_t bytes, sessile_buffer_kind kind,
                                     sessile_buffer **out) {
  *out = NULL;
  SESSILE_CHECK(bytes > 0, SESSILE_ERR_USAGE, "a buffer of 0 bytes was asked for");
  SESSILE_CHECK(bytes <= g->info.max_storage_buffer_range, SESSILE_ERR_TOO_LARGE,
                "a storage buffer of %zu bytes (%.1f MiB) was asked for, but %s allows at most "
                "%llu bytes (maxStorageBufferRange, %.1f MiB): use a smaller problem or a "
                "device with a larger limit", bytes, (double)bytes / 1048576.0, g->info.name,
                (unsigned long long)g->info.max_storage_buffer_range,
                (double)g->info.max_storage_buffer_range / 1048576.0);
  sessile_buffer *b = calloc(1, sizeof *b);
  SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "out of host memory");
  VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                             VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                             VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkMemoryPropertyFlags hv = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                             VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VkMemoryPropertyFlags want, fallback;
  if (kind == SESSILE_BUFFER_MAPPED) {
    want = hv | VK_MEMORY_PROPERTY_HOST_CACHED_BIT; /* fast host reads */
    fallback = hv;
  } else if (g->info.unified_memory) {
    want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | hv;
    fallback = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  } else {
    want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    fallback = 0;
  }
  sessile_status s = alloc_buffer(g, bytes, usage, want, fallback, b);
  /* A discrete GPU may hand us host-visible device memory (BAR): kept mapped,
   * unless the context takes the staged paths on purpose (options.staged). */
  if (s == SESSILE_OK && kind == SESSILE_BUFFER_DEVICE && g->staged_only && b->mapped) {
    vkUnmapMemory(g->device, b->memory);
    b->mapped = NULL;
  }
  if (s == SESSILE_OK) s = fill_zero(b);
  if (s != SESSILE_OK) {
    release(b);
    free(b);
    return s;
  }
  *out = b;
  return SESSILE_OK;
}

void sessile_buffer_destroy(sessile_buffer *b) {
  if (!b) return;
  release(b);
  free(b);
}

sessile_status sessile_buffer_reserve(sessile_gpu *g, sessile_buffer **b, size_t bytes, sessile_buffer_kind kind) {
  if (*b && (*b)->bytes >= bytes) return SESSILE_OK;
  sessile_buffer_destroy(*b);
  *b = NULL;
  size_t room = bytes + bytes / 4, max = g->info.max_storage_buffer_range;
  if (room > max) room = bytes > max ? bytes : max; /* bytes > max: create() says so */
  return sessile_buffer_create(g, room, kind, b);
}

size_t sessile_buffer_size(const sessile_buffer *b) { return b ? b->bytes : 0; }
int sessile_buffer_texels_fit(const sessile_buffer *b, size_t texel_bytes) {
  return !b || b->bytes / texel_bytes <= b->gpu->info.max_texel_buffer_elements;
}
void *sessile_buffer_host_ptr(sessile_buffer *b) { return b->mapped; }

static sessile_status check_range(const sessile_buffer *b, size_t offset, size_t bytes) {
  SESSILE_CHECK(offset <= b->bytes && bytes <= b->bytes - offset, SESSILE_ERR_USAGE,
                "transfer of %zu bytes at offset %zu exceeds the %zu-byte buffer", bytes, offset,
                b->bytes);
  return SESSILE_OK;
}

/* A host-visible buffer of at least `bytes` for a staged transfer: the
 * context's kept one (grown to a power of two, at most
 * SESSILE_STAGING_KEEP_), or for a larger transfer a temporary in *tmp. */
static sessile_status staging_for(sessile_gpu *g, size_t bytes, sessile_buffer *tmp, sessile_buffer **out) {
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const VkMemoryPropertyFlags hv = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (bytes > SESSILE_STAGING_KEEP_) {
    *out = tmp;
    return alloc_buffer(g, bytes, usage, hv, hv, tmp);
  }
  if (!g->staging || g->staging->bytes < bytes) {
    size_t want = (size_t)64 << 10;
    while (want < bytes) want *= 2;
    sessile_gpu_staging_free_(g);
    sessile_buffer *b = calloc(1, sizeof *b);
    SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "out of host memory for a staging buffer");
    sessile_status s = alloc_buffer(g, want, usage, hv, hv, b);
    if (s != SESSILE_OK) {
      release(b);
      free(b);
      return s;
    }
    g->staging = b;
  }
  *out = g->staging;
  return SESSILE_OK;
}

void sessile_gpu_staging_free_(sessile_gpu *g) {
  if (!g->staging) return;
  release(g->staging);
  free(g->staging);
  g->staging = NULL;
}

/* Transfers through a staging buffer when the memory is not mapped. */
static sessile_status staged(sessile_buffer *b, size_t offset, void *host, size_t bytes, int up) {
  sessile_buffer tmp = {0}, *st = NULL;
  sessile_gpu *g = b->gpu;
  sessile_status s = staging_for(g, bytes, &tmp, &st);
  if (s == SESSILE_OK && up) {
    memcpy(st->mapped, host, bytes);
    s = copy_buffer(g, st->buffer, 0, b->buffer, offset, bytes);
  } else if (s == SESSILE_OK) {
    s = copy_buffer(g, b->buffer, offset, st->buffer, 0, bytes);
    if (s == SESSILE_OK) memcpy(host, st->mapped, bytes);
  }
  release(&tmp);
  return s;
}

sessile_status sessile_buffer_upload(sessile_buffer *b, size_t offset, const void *src, size_t bytes) {
  SESSILE_CALL(check_range(b, offset, bytes));
  if (bytes == 0) return SESSILE_OK;
  if (!b->mapped) return staged(b, offset, (void *)src, bytes, 1);
  memcpy((char *)b->mapped + offset, src, bytes);
  if (!b->coherent) {
    VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                             .memory = b->memory, .offset = 0, .size = VK_WHOLE_SIZE};
    SESSILE_VK(vkFlushMappedMemoryRanges(b->gpu->device, 1, &r));
  }
  return SESSILE_OK;
}

sessile_status sessile_buffer_download(sessile_buffer *b, size_t offset, void *dst, size_t bytes) {
  SESSILE_CALL(check_range(b, offset, bytes));
  if (bytes == 0) return SESSILE_OK;
  if (!b->mapped) return staged(b, offset, dst, bytes, 0);
  if (!b->coherent) {
    VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                             .memory = b->memory, .offset = 0, .size = VK_WHOLE_SIZE};
    SESSILE_VK(vkInvalidateMappedMemoryRanges(b->gpu->device, 1, &r));
  }
  memcpy(dst, (const char *)b->mapped + offset, bytes);
  return SESSILE_OK;
}
