/* Offscreen render targets: colour (RGBA8 UNORM), depth (D32, else
 * D24), an optional multisampled colour resolved into a single-sample image,
 * a Vulkan 1.0 render pass and framebuffer, a host-visible readback buffer
 * and a command buffer per frame stage (draw, then copy), on the graphics
 * queue.  See graphics.h. */
#include <stdlib.h>
#include <string.h>
#include "gpu_internal.h"
#include "sessile/gpu/graphics.h"
#include "graphics_internal.h"

uint32_t sessile_gfx_sample_counts(const sessile_gpu *g) {
  if (!g->gfx_queue) return 0;
  return (uint32_t)(g->limits.framebufferColorSampleCounts & g->limits.framebufferDepthSampleCounts);
}

uint32_t sessile_gfx_max_side(const sessile_gpu *g) {
  uint32_t m = g->limits.maxImageDimension2D;
  if (g->limits.maxFramebufferWidth < m) m = g->limits.maxFramebufferWidth;
  if (g->limits.maxFramebufferHeight < m) m = g->limits.maxFramebufferHeight;
  return m;
}

uint64_t sessile_gfx_target_bytes(uint32_t width, uint32_t height, uint32_t samples) {
  uint64_t px = (uint64_t)width * height;
  /* colour and depth per sample, the resolve image, the readback buffer */
  return px * 4u * samples * 2u + (samples > 1 ? px * 4u : 0) + px * 4u;
}

static sessile_status image_create(sessile_gpu *g, uint32_t w, uint32_t h, VkFormat format,
                                   VkSampleCountFlagBits samples, VkImageUsageFlags usage,
                                   VkImageAspectFlags aspect, sessile_gfx_image *im) {
  VkImageCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                          .imageType = VK_IMAGE_TYPE_2D,
                          .format = format,
                          .extent = {w, h, 1},
                          .mipLevels = 1,
                          .arrayLayers = 1,
                          .samples = samples,
                          .tiling = VK_IMAGE_TILING_OPTIMAL,
                          .usage = usage,
                          .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
                          .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  SESSILE_VK(vkCreateImage(g->device, &ci, NULL, &im->image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(g->device, im->image, &req);
  uint32_t type = sessile_gpu_memory_type_(g, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type == UINT32_MAX) type = sessile_gpu_memory_type_(g, req.memoryTypeBits, 0);
  SESSILE_CHECK(type != UINT32_MAX, SESSILE_ERR_UNSUPPORTED,
                "no memory type for a %ux%u image on %s", w, h, g->info.name);
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                             .allocationSize = req.size,
                             .memoryTypeIndex = type};
  SESSILE_VK(vkAllocateMemory(g->device, &ai, NULL, &im->memory));
  SESSILE_VK(vkBindImageMemory(g->device, im->image, im->memory, 0));
  VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                              .image = im->image,
                              .viewType = VK_IMAGE_VIEW_TYPE_2D,
                              .format = format,
                              .subresourceRange = {aspect, 0, 1, 0, 1}};
  SESSILE_VK(vkCreateImageView(g->device, &vi, NULL, &im->view));
  return SESSILE_OK;
}

static void image_destroy(sessile_gpu *g, sessile_gfx_image *im) {
  if (im->view) vkDestroyImageView(g->device, im->view, NULL);
  if (im->image) vkDestroyImage(g->device, im->image, NULL);
  if (im->memory) vkFreeMemory(g->device, im->memory, NULL);
  memset(im, 0, sizeof *im);
}

static VkFormat depth_format(sessile_gpu *g) {
  const VkFormat cand[2] = {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32};
  for (int i = 0; i < 2; i++) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(g->phys, cand[i], &fp);
    if (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return cand[i];
  }
  return VK_FORMAT_UNDEFINED;
}

/* Attachments: 0 colour (multisampled when samples > 1), 1 depth, 2 the
 * single-sample resolve when samples > 1.  The image read back ends in
 * TRANSFER_SRC_OPTIMAL; the dependencies order the frame's copy after the
 * writes and the next frame's writes after the copy. */
static sessile_status render_pass_create(sessile_gfx_target *t, VkFormat dfmt) {
  int ms = t->samples > 1;
  VkAttachmentDescription a[3] = {
      {.format = VK_FORMAT_R8G8B8A8_UNORM,
       .samples = (VkSampleCountFlagBits)t->samples,
       .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
       .storeOp = ms ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
       .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
       .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
       .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
       .finalLayout = ms ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
                         : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
      {.format = dfmt,
       .samples = (VkSampleCountFlagBits)t->samples,
       .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
       .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
       .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
       .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
       .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
       .finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL},
      {.format = VK_FORMAT_R8G8B8A8_UNORM,
       .samples = VK_SAMPLE_COUNT_1_BIT,
       .loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
       .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
       .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
       .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
       .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
       .finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}};
  VkAttachmentReference color = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth = {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkAttachmentReference resolve = {2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                              .colorAttachmentCount = 1,
                              .pColorAttachments = &color,
                              .pResolveAttachments = ms ? &resolve : NULL,
                              .pDepthStencilAttachment = &depth};
  VkSubpassDependency dep[2] = {
      {.srcSubpass = VK_SUBPASS_EXTERNAL,
       .dstSubpass = 0,
       .srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
       .dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                       VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                       VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
       .srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT,
       .dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
      {.srcSubpass = 0,
       .dstSubpass = VK_SUBPASS_EXTERNAL,
       .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
       .dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
       .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
       .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT}};
  VkRenderPassCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                               .attachmentCount = ms ? 3u : 2u,
                               .pAttachments = a,
                               .subpassCount = 1,
                               .pSubpasses = &sub,
                               .dependencyCount = 2,
                               .pDependencies = dep};
  SESSILE_VK(vkCreateRenderPass(t->gpu->device, &ci, NULL, &t->pass));
  VkImageView views[3] = {t->color.view, t->depth.view, t->resolve.view};
  VkFramebufferCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                .renderPass = t->pass,
                                .attachmentCount = ms ? 3u : 2u,
                                .pAttachments = views,
                                .width = t->width,
                                .height = t->height,
                                .layers = 1};
  SESSILE_VK(vkCreateFramebuffer(t->gpu->device, &fi, NULL, &t->framebuffer));
  return SESSILE_OK;
}

static sessile_status readback_create(sessile_gfx_target *t) {
  sessile_gpu *g = t->gpu;
  VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = (VkDeviceSize)t->width * t->height * 4u,
                           .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  SESSILE_VK(vkCreateBuffer(g->device, &ci, NULL, &t->readback));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g->device, t->readback, &req);
  VkMemoryPropertyFlags hv = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  uint32_t type = sessile_gpu_memory_type_(g, req.memoryTypeBits, hv | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  if (type == UINT32_MAX) type = sessile_gpu_memory_type_(g, req.memoryTypeBits, hv);
  SESSILE_CHECK(type != UINT32_MAX, SESSILE_ERR_UNSUPPORTED, "no host-visible memory on %s",
                g->info.name);
  t->readback_coherent =
      (g->mem.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                             .allocationSize = req.size,
                             .memoryTypeIndex = type};
  SESSILE_VK(vkAllocateMemory(g->device, &ai, NULL, &t->readback_mem));
  SESSILE_VK(vkBindBufferMemory(g->device, t->readback, t->readback_mem, 0));
  SESSILE_VK(vkMapMemory(g->device, t->readback_mem, 0, VK_WHOLE_SIZE, 0, &t->readback_ptr));
  return SESSILE_OK;
}

static sessile_status commands_create(sessile_gfx_target *t) {
  sessile_gpu *g = t->gpu;
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = g->gfx_family};
  SESSILE_VK(vkCreateCommandPool(g->device, &pi, NULL, &t->pool));
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = t->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 2};
  SESSILE_VK(vkAllocateCommandBuffers(g->device, &ai, t->cb));
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  SESSILE_VK(vkCreateFence(g->device, &fi, NULL, &t->fence));
  return SESSILE_OK;
}

static sessile_status target_init(sessile_gfx_target *t) {
  sessile_gpu *g = t->gpu;
  VkFormat dfmt = depth_format(g);
  SESSILE_CHECK(dfmt != VK_FORMAT_UNDEFINED, SESSILE_ERR_UNSUPPORTED,
                "%s has no depth format for attachments (D32 or D24)", g->info.name);
  int ms = t->samples > 1;
  VkImageUsageFlags cu = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (ms) cu |= VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  else cu |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  VkImageUsageFlags du = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                         VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  SESSILE_CALL(image_create(g, t->width, t->height, VK_FORMAT_R8G8B8A8_UNORM,
                            (VkSampleCountFlagBits)t->samples, cu, VK_IMAGE_ASPECT_COLOR_BIT, &t->color));
  SESSILE_CALL(image_create(g, t->width, t->height, dfmt, (VkSampleCountFlagBits)t->samples, du,
                            VK_IMAGE_ASPECT_DEPTH_BIT, &t->depth));
  if (ms)
    SESSILE_CALL(image_create(g, t->width, t->height, VK_FORMAT_R8G8B8A8_UNORM, VK_SAMPLE_COUNT_1_BIT,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT, &t->resolve));
  SESSILE_CALL(render_pass_create(t, dfmt));
  SESSILE_CALL(readback_create(t));
  SESSILE_CALL(commands_create(t));
  return SESSILE_OK;
}

sessile_status sessile_gfx_target_create(sessile_gpu *g, uint32_t width, uint32_t height,
                                         uint32_t samples, sessile_gfx_target **out) {
  *out = NULL;
  SESSILE_CHECK(g->gfx_queue, SESSILE_ERR_UNSUPPORTED,
                "device '%s' has no graphics queue: rendering needs one (choose another "
                "device with --device; 'sessile devices' lists them)", g->info.name);
  uint32_t counts = sessile_gfx_sample_counts(g);
  SESSILE_CHECK(samples >= 1 && (samples & (samples - 1)) == 0 && (counts & samples), SESSILE_ERR_USAGE,
                "%u samples per pixel are not supported by '%s' (sample-count mask 0x%x: %s%s%s%s)",
                samples, g->info.name, counts, counts & 1 ? "1 " : "", counts & 2 ? "2 " : "",
                counts & 4 ? "4 " : "", counts & 8 ? "8" : "");
  uint32_t mx = sessile_gfx_max_side(g);
  SESSILE_CHECK(width >= 1 && height >= 1 && width <= mx && height <= mx, SESSILE_ERR_USAGE,
                "an image of %ux%u pixels exceeds what '%s' can render (1..%u per side)", width,
                height, g->info.name, mx);
  sessile_gfx_target *t = calloc(1, sizeof *t);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory");
  t->gpu = g;
  t->width = width;
  t->height = height;
  t->samples = samples;
  sessile_status s = target_init(t);
  if (s != SESSILE_OK) {
    sessile_gfx_target_destroy(t);
    return s;
  }
  *out = t;
  return SESSILE_OK;
}

void sessile_gfx_target_destroy(sessile_gfx_target *t) {
  if (!t) return;
  sessile_gpu *g = t->gpu;
  if (t->fence) vkDestroyFence(g->device, t->fence, NULL);
  if (t->pool) vkDestroyCommandPool(g->device, t->pool, NULL); /* frees cb[] */
  if (t->readback_ptr) vkUnmapMemory(g->device, t->readback_mem);
  if (t->readback) vkDestroyBuffer(g->device, t->readback, NULL);
  if (t->readback_mem) vkFreeMemory(g->device, t->readback_mem, NULL);
  if (t->framebuffer) vkDestroyFramebuffer(g->device, t->framebuffer, NULL);
  if (t->pass) vkDestroyRenderPass(g->device, t->pass, NULL);
  image_destroy(g, &t->resolve);
  image_destroy(g, &t->depth);
  image_destroy(g, &t->color);
  free(t);
}

static sessile_status submit_wait(sessile_gfx_target *t, VkCommandBuffer cb) {
  VkDevice d = t->gpu->device;
  SESSILE_VK(vkResetFences(d, 1, &t->fence));
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                     .pCommandBuffers = &cb};
  SESSILE_VK(vkQueueSubmit(t->gpu->gfx_queue, 1, &si, t->fence));
  t->gpu->submissions++;
  SESSILE_VK(vkWaitForFences(d, 1, &t->fence, VK_TRUE, UINT64_MAX));
  return SESSILE_OK;
}

static sessile_status record_draws(sessile_gfx_target *t, VkCommandBuffer cb, const float clear[4],
                                   const sessile_gfx_draw *draws, uint32_t ndraws) {
  SESSILE_VK(vkResetCommandBuffer(cb, 0));
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  SESSILE_VK(vkBeginCommandBuffer(cb, &bi));
  VkClearValue cv[3];
  memset(cv, 0, sizeof cv);
  memcpy(cv[0].color.float32, clear, 4 * sizeof(float));
  cv[1].depthStencil.depth = 1.0f;
  memcpy(cv[2].color.float32, clear, 4 * sizeof(float));
  VkRenderPassBeginInfo rb = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                              .renderPass = t->pass,
                              .framebuffer = t->framebuffer,
                              .renderArea = {{0, 0}, {t->width, t->height}},
                              .clearValueCount = t->samples > 1 ? 3u : 2u,
                              .pClearValues = cv};
  vkCmdBeginRenderPass(cb, &rb, VK_SUBPASS_CONTENTS_INLINE);
  for (uint32_t i = 0; i < ndraws; i++) {
    const sessile_gfx_draw *dr = &draws[i];
    if (dr->count == 0 || (dr->instances && dr->ninstances == 0)) continue;
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, dr->pipeline->pipeline);
    if (dr->pipeline->push_bytes)
      vkCmdPushConstants(cb, dr->pipeline->layout,
                         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                         dr->pipeline->push_bytes, dr->push);
    VkDeviceSize off[2] = {0, 0};
    VkBuffer bufs[2] = {dr->vertices->buffer, dr->instances ? dr->instances->buffer : VK_NULL_HANDLE};
    vkCmdBindVertexBuffers(cb, 0, dr->instances ? 2u : 1u, bufs, off);
    uint32_t n = dr->instances ? dr->ninstances : 1u, first = dr->instances ? dr->first_instance : 0u;
    if (dr->indices) {
      vkCmdBindIndexBuffer(cb, dr->indices->buffer, 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cb, dr->count, n, dr->first_index, 0, first);
    } else {
      vkCmdDraw(cb, dr->count, n, 0, first);
    }
  }
  vkCmdEndRenderPass(cb);
  SESSILE_VK(vkEndCommandBuffer(cb));
  return SESSILE_OK;
}

static sessile_status record_copy(sessile_gfx_target *t, VkCommandBuffer cb) {
  SESSILE_VK(vkResetCommandBuffer(cb, 0));
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  SESSILE_VK(vkBeginCommandBuffer(cb, &bi));
  VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                              .imageExtent = {t->width, t->height, 1}};
  VkImage src = t->samples > 1 ? t->resolve.image : t->color.image;
  vkCmdCopyImageToBuffer(cb, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t->readback, 1, &region);
  VkBufferMemoryBarrier host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .buffer = t->readback,
                                .size = VK_WHOLE_SIZE};
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1,
                       &host, 0, NULL);
  SESSILE_VK(vkEndCommandBuffer(cb));
  return SESSILE_OK;
}

sessile_status sessile_gfx_render(sessile_gfx_target *t, const float clear[4],
                                  const sessile_gfx_draw *draws, uint32_t ndraws, unsigned char *rgba,
                                  double *t_draw, double *t_read) {
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(record_draws(t, t->cb[0], clear, draws, ndraws));
  SESSILE_CALL(submit_wait(t, t->cb[0]));
  double t1 = sessile_wall_seconds();
  SESSILE_CALL(record_copy(t, t->cb[1]));
  SESSILE_CALL(submit_wait(t, t->cb[1]));
  if (!t->readback_coherent) {
    VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                             .memory = t->readback_mem, .offset = 0, .size = VK_WHOLE_SIZE};
    SESSILE_VK(vkInvalidateMappedMemoryRanges(t->gpu->device, 1, &r));
  }
  memcpy(rgba, t->readback_ptr, (size_t)t->width * t->height * 4u);
  double t2 = sessile_wall_seconds();
  if (t_draw) *t_draw = t1 - t0;
  if (t_read) *t_read = t2 - t1;
  return SESSILE_OK;
}
