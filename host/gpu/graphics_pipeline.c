/* Graphics pipelines (from embedded vertex and fragment SPIR-V) and the
 * vertex and index buffers they draw.  See graphics.h. */
#include <stdlib.h>
#include <string.h>
#include "sessile/gpu/graphics.h"
#include "graphics_internal.h"

static sessile_status module_create(sessile_gpu *g, const char *name, VkShaderModule *m) {
  const sessile_spirv *sp = sessile_spirv_find(name);
  SESSILE_CHECK(sp, SESSILE_ERR_INTERNAL, "shader '%s' is not embedded in this build", name);
  VkShaderModuleCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                 .codeSize = sp->bytes,
                                 .pCode = sp->code};
  SESSILE_VK(vkCreateShaderModule(g->device, &ci, NULL, m));
  return SESSILE_OK;
}

static sessile_status pipeline_init(sessile_gfx_target *t, const sessile_gfx_pipeline_desc *d,
                                    sessile_gfx_pipeline *p, VkShaderModule mod[2]) {
  sessile_gpu *g = t->gpu;
  VkPushConstantRange pr = {.stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                            .offset = 0,
                            .size = d->push_bytes};
  VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                   .pushConstantRangeCount = d->push_bytes ? 1u : 0u,
                                   .pPushConstantRanges = &pr};
  SESSILE_VK(vkCreatePipelineLayout(g->device, &li, NULL, &p->layout));
  SESSILE_CALL(module_create(g, d->vert, &mod[0]));
  SESSILE_CALL(module_create(g, d->frag, &mod[1]));
  VkPipelineShaderStageCreateInfo st[2] = {
      {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
       .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = mod[0], .pName = "main"},
      {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
       .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = mod[1], .pName = "main"}};
  VkVertexInputBindingDescription bind[2] = {{0, d->stride, VK_VERTEX_INPUT_RATE_VERTEX},
                                             {1, d->instance_stride, VK_VERTEX_INPUT_RATE_INSTANCE}};
  VkVertexInputAttributeDescription attr[8];
  for (uint32_t i = 0; i < d->nattr; i++) {
    attr[i].location = i;
    attr[i].binding = d->attr[i].binding;
    attr[i].format = d->attr[i].format == SESSILE_GFX_FLOAT3   ? VK_FORMAT_R32G32B32_SFLOAT
                     : d->attr[i].format == SESSILE_GFX_FLOAT4 ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                               : VK_FORMAT_R8G8B8A8_UNORM;
    attr[i].offset = d->attr[i].offset;
  }
  VkPipelineVertexInputStateCreateInfo vi = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
      .vertexBindingDescriptionCount = d->instance_stride ? 2u : 1u,
      .pVertexBindingDescriptions = bind,
      .vertexAttributeDescriptionCount = d->nattr,
      .pVertexAttributeDescriptions = attr};
  VkPipelineInputAssemblyStateCreateInfo ia = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
      .topology = d->topology == SESSILE_GFX_LINES ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
                                                   : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  VkViewport vp = {0, 0, (float)t->width, (float)t->height, 0, 1};
  VkRect2D sc = {{0, 0}, {t->width, t->height}};
  VkPipelineViewportStateCreateInfo vps = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                           .viewportCount = 1, .pViewports = &vp,
                                           .scissorCount = 1, .pScissors = &sc};
  VkPipelineRasterizationStateCreateInfo rs = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
      .polygonMode = VK_POLYGON_MODE_FILL,
      .cullMode = VK_CULL_MODE_NONE, /* user meshes need not be consistently wound */
      .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
      .lineWidth = 1.0f};
  VkPipelineMultisampleStateCreateInfo ms = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
      .rasterizationSamples = (VkSampleCountFlagBits)t->samples};
  VkPipelineDepthStencilStateCreateInfo ds = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
      .depthTestEnable = VK_TRUE,
      .depthWriteEnable = VK_TRUE,
      .depthCompareOp = VK_COMPARE_OP_LESS};
  VkPipelineColorBlendAttachmentState cba = {.colorWriteMask = 0xf};
  VkPipelineColorBlendStateCreateInfo cb = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                            .attachmentCount = 1, .pAttachments = &cba};
  VkGraphicsPipelineCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                     .stageCount = 2,
                                     .pStages = st,
                                     .pVertexInputState = &vi,
                                     .pInputAssemblyState = &ia,
                                     .pViewportState = &vps,
                                     .pRasterizationState = &rs,
                                     .pMultisampleState = &ms,
                                     .pDepthStencilState = &ds,
                                     .pColorBlendState = &cb,
                                     .layout = p->layout,
                                     .renderPass = t->pass,
                                     .subpass = 0};
  SESSILE_VK(vkCreateGraphicsPipelines(g->device, g->pipeline_cache, 1, &ci, NULL, &p->pipeline));
  return SESSILE_OK;
}

sessile_status sessile_gfx_pipeline_create(sessile_gfx_target *t, const sessile_gfx_pipeline_desc *d,
                                           sessile_gfx_pipeline **out) {
  *out = NULL;
  SESSILE_CHECK(d->nattr <= 8 && d->push_bytes <= 128 && d->push_bytes % 4 == 0, SESSILE_ERR_INTERNAL,
                "graphics pipeline %s: %u attributes, %u push bytes (at most 8 and 128)", d->vert,
                d->nattr, d->push_bytes);
  for (uint32_t i = 0; i < d->nattr; i++)
    SESSILE_CHECK(d->attr[i].binding == 0 || (d->attr[i].binding == 1 && d->instance_stride), SESSILE_ERR_INTERNAL,
                  "graphics pipeline %s: attribute %u is per instance but the pipeline has no instance stride",
                  d->vert, i);
  sessile_gfx_pipeline *p = calloc(1, sizeof *p);
  SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory");
  p->gpu = t->gpu;
  p->push_bytes = d->push_bytes;
  VkShaderModule mod[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  sessile_status s = pipeline_init(t, d, p, mod);
  /* The modules are not needed once the pipeline exists. */
  for (int i = 0; i < 2; i++)
    if (mod[i]) vkDestroyShaderModule(t->gpu->device, mod[i], NULL);
  if (s != SESSILE_OK) {
    sessile_gfx_pipeline_destroy(p);
    return s;
  }
  *out = p;
  return SESSILE_OK;
}

void sessile_gfx_pipeline_destroy(sessile_gfx_pipeline *p) {
  if (!p) return;
  if (p->pipeline) vkDestroyPipeline(p->gpu->device, p->pipeline, NULL);
  if (p->layout) vkDestroyPipelineLayout(p->gpu->device, p->layout, NULL);
  free(p);
}

static sessile_status raw_buffer(sessile_gpu *g, size_t bytes, VkBufferUsageFlags usage,
                                 VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback,
                                 VkBuffer *buf, VkDeviceMemory *mem, void **mapped) {
  VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = bytes,
                           .usage = usage,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  SESSILE_VK(vkCreateBuffer(g->device, &ci, NULL, buf));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g->device, *buf, &req);
  uint32_t type = sessile_gpu_memory_type_(g, req.memoryTypeBits, want);
  if (type == UINT32_MAX) type = sessile_gpu_memory_type_(g, req.memoryTypeBits, fallback);
  SESSILE_CHECK(type != UINT32_MAX, SESSILE_ERR_UNSUPPORTED,
                "no memory type for a %zu-byte vertex buffer on %s", bytes, g->info.name);
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                             .allocationSize = req.size,
                             .memoryTypeIndex = type};
  VkResult r = vkAllocateMemory(g->device, &ai, NULL, mem);
  if (r < 0)
    return sessile_error_set(r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY
                                 ? SESSILE_ERR_NO_MEMORY : SESSILE_ERR_VULKAN,
                             "vkAllocateMemory of %zu bytes for a mesh failed with %s: render a "
                             "smaller mesh or use a device with more memory", bytes,
                             sessile_vk_result_name(r));
  SESSILE_VK(vkBindBufferMemory(g->device, *buf, *mem, 0));
  *mapped = NULL;
  if (g->mem.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
    SESSILE_VK(vkMapMemory(g->device, *mem, 0, VK_WHOLE_SIZE, 0, mapped));
  return SESSILE_OK;
}

/* A one-shot copy on the graphics queue (its own pool: the context's pool
 * belongs to the compute family). */
static sessile_status copy_on_gfx(sessile_gpu *g, VkBuffer src, VkBuffer dst, size_t bytes) {
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
                                .queueFamilyIndex = g->gfx_family};
  VkResult r = vkCreateCommandPool(g->device, &pi, NULL, &pool);
  const char *what = "vkCreateCommandPool";
  if (r >= 0) {
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = 1};
    r = vkAllocateCommandBuffers(g->device, &ai, &cb);
    what = "vkAllocateCommandBuffers";
  }
  if (r >= 0) {
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    r = vkBeginCommandBuffer(cb, &bi);
    what = "vkBeginCommandBuffer";
  }
  if (r >= 0) {
    VkBufferCopy region = {0, 0, bytes};
    vkCmdCopyBuffer(cb, src, dst, 1, &region);
    r = vkEndCommandBuffer(cb);
    what = "vkEndCommandBuffer";
  }
  if (r >= 0) r = sessile_gpu_submit_wait_(g, g->gfx_queue, cb, &what);
  if (pool) vkDestroyCommandPool(g->device, pool, NULL);
  if (r < 0) return sessile_vk_fail_(r, what, __func__);
  return SESSILE_OK;
}

static sessile_status buffer_init(sessile_gpu *g, VkBufferUsageFlags usage, const void *data,
                                  size_t bytes, sessile_gfx_buffer *b) {
  VkMemoryPropertyFlags hv = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  void *mapped = NULL;
  /* Unified memory (CPU, integrated): write the device memory directly. */
  VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | (g->info.unified_memory ? hv : 0);
  SESSILE_CALL(raw_buffer(g, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, want,
                          VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &b->buffer, &b->memory, &mapped));
  if (mapped && g->info.unified_memory) {
    memcpy(mapped, data, bytes);
    vkUnmapMemory(g->device, b->memory);
    return SESSILE_OK;
  }
  if (mapped) vkUnmapMemory(g->device, b->memory);
  VkBuffer st = VK_NULL_HANDLE;
  VkDeviceMemory sm = VK_NULL_HANDLE;
  sessile_status s = raw_buffer(g, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, hv, hv, &st, &sm, &mapped);
  if (s == SESSILE_OK && !mapped)
    s = sessile_error_set(SESSILE_ERR_UNSUPPORTED, "the staging memory of %s is not mappable",
                          g->info.name);
  if (s == SESSILE_OK) {
    memcpy(mapped, data, bytes);
    s = copy_on_gfx(g, st, b->buffer, bytes);
  }
  if (mapped) vkUnmapMemory(g->device, sm);
  if (st) vkDestroyBuffer(g->device, st, NULL);
  if (sm) vkFreeMemory(g->device, sm, NULL);
  return s;
}

sessile_status sessile_gfx_buffer_create(sessile_gpu *g, sessile_gfx_usage usage, const void *data,
                                         size_t bytes, sessile_gfx_buffer **out) {
  *out = NULL;
  SESSILE_CHECK(g->gfx_queue, SESSILE_ERR_UNSUPPORTED, "device '%s' has no graphics queue",
                g->info.name);
  SESSILE_CHECK(bytes > 0, SESSILE_ERR_INTERNAL, "an empty vertex or index buffer was asked for");
  sessile_gfx_buffer *b = calloc(1, sizeof *b);
  SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "out of host memory");
  b->gpu = g;
  b->bytes = bytes;
  VkBufferUsageFlags u = usage == SESSILE_GFX_INDEX ? VK_BUFFER_USAGE_INDEX_BUFFER_BIT
                                                    : VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  sessile_status s = buffer_init(g, u, data, bytes, b);
  if (s != SESSILE_OK) {
    sessile_gfx_buffer_destroy(b);
    return s;
  }
  *out = b;
  return SESSILE_OK;
}

void sessile_gfx_buffer_destroy(sessile_gfx_buffer *b) {
  if (!b) return;
  if (b->buffer) vkDestroyBuffer(b->gpu->device, b->buffer, NULL);
  if (b->memory) vkFreeMemory(b->gpu->device, b->memory, NULL);
  free(b);
}
