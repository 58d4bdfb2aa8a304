/* Command recording: many dispatches per submit, a barrier between dependent
 * dispatches, timestamps, and re-submission of the same recording (Krylov
 * solvers record k iterations once and submit them until converged). */
#include <stdlib.h>
#include <string.h>
#include "gpu_internal.h"

/* PROF_MAX: dispatches timed per recording under sessile_gpu_profile. */
enum { SETS_PER_POOL = 512, MAX_POOLS = 256, TIMESTAMPS = 64, PROF_MAX = SESSILE_PROFILE_MAX };

struct sessile_cmd {
  sessile_gpu *gpu;
  VkCommandPool pool;
  VkCommandBuffer cb;
  VkFence fence;
  VkQueryPool queries;
  VkDescriptorPool dpools[MAX_POOLS];
  uint32_t ndpools, cur_pool;
  uint32_t ndispatch;
  /* sessile_cmd_indirect: dispatches of these group counts read theirs
   * from ind_args (word 4 + 3 i for ind_groups[i]) */
  sessile_buffer *ind_args;
  uint32_t ind_groups[SESSILE_INDIRECT_MAX], nind;
  int recording, recorded;
  uint64_t ts_written; /* bitmask of slots written in this recording */
  uint64_t ts[TIMESTAMPS];
  int ts_valid;
  /* sessile_gpu_profile: a pool of its own (2 per dispatch), whether this
   * recording is timed, and the kernels of its timed dispatches */
  VkQueryPool prof_q;
  int prof_rec;
  uint32_t nprof, nuntimed;
  const char *prof_name[PROF_MAX];
  /* transfers of this recording (sessile_cmd_upload/download): its own
   * host-visible staging buffer, replaced when it runs out mid-recording
   * (the old ones are kept in `retired` until the next begin, when nothing
   * can still read them); uploads done, and reads to finish after the wait */
  sessile_buffer *stage;
  size_t stage_used;
  sessile_buffer **retired;
  size_t nretired;
  uint32_t ncopies_up, nuploads; /* recorded copies to the device; uploads of any kind */
  int submits;                    /* of this recording */
  int down_barrier; /* the barrier before the download copies is recorded */
  int copied;       /* a sessile_cmd_copy since the last dispatch: the next waits for it */
  struct cmd_read {
    void *dst;
    sessile_buffer *src; /* the stage, or a mapped buffer */
    size_t offset, bytes;
    int f32; /* floats to widen into doubles */
  } *reads;
  size_t nreads, cap_reads;
};

static sessile_status add_pool(sessile_cmd *c) {
  SESSILE_CHECK(c->ndpools < MAX_POOLS, SESSILE_ERR_TOO_LARGE,
                "more than %d dispatches in one recording: submit in smaller pieces",
                SETS_PER_POOL * MAX_POOLS);
  VkDescriptorPoolSize size[2] = {
      {.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = SETS_PER_POOL * 16},
      {.type = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, .descriptorCount = SETS_PER_POOL * 8}};
  VkDescriptorPoolCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                   .maxSets = SETS_PER_POOL, .poolSizeCount = 2,
                                   .pPoolSizes = size};
  SESSILE_VK(vkCreateDescriptorPool(c->gpu->device, &ci, NULL, &c->dpools[c->ndpools]));
  c->ndpools++;
  return SESSILE_OK;
}

static sessile_status cmd_init(sessile_cmd *c) {
  sessile_gpu *g = c->gpu;
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = g->queue_family};
  SESSILE_VK(vkCreateCommandPool(g->device, &pi, NULL, &c->pool));
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = c->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  SESSILE_VK(vkAllocateCommandBuffers(g->device, &ai, &c->cb));
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  SESSILE_VK(vkCreateFence(g->device, &fi, NULL, &c->fence));
  if (g->info.timestamp_period_ns > 0) {
    VkQueryPoolCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = TIMESTAMPS};
    SESSILE_VK(vkCreateQueryPool(g->device, &qi, NULL, &c->queries));
  }
  return add_pool(c);
}

sessile_status sessile_cmd_create(sessile_gpu *g, sessile_cmd **out) {
  *out = NULL;
  sessile_cmd *c = calloc(1, sizeof *c);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory");
  c->gpu = g;
  sessile_status s = cmd_init(c);
  if (s != SESSILE_OK) {
    sessile_cmd_destroy(c);
    return s;
  }
  *out = c;
  return SESSILE_OK;
}

static void free_retired(sessile_cmd *c) {
  for (size_t i = 0; i < c->nretired; i++) sessile_buffer_destroy(c->retired[i]);
  free(c->retired);
  c->retired = NULL, c->nretired = 0;
}

void sessile_cmd_destroy(sessile_cmd *c) {
  if (!c) return;
  free_retired(c);
  sessile_buffer_destroy(c->stage);
  free(c->reads);
  VkDevice d = c->gpu->device;
  /* Nothing can be pending: submit_wait always waits for its fence. */
  if (c->fence) vkDestroyFence(d, c->fence, NULL);
  for (uint32_t i = 0; i < c->ndpools; i++) vkDestroyDescriptorPool(d, c->dpools[i], NULL);
  if (c->queries) vkDestroyQueryPool(d, c->queries, NULL);
  if (c->prof_q) vkDestroyQueryPool(d, c->prof_q, NULL);
  if (c->pool) vkDestroyCommandPool(d, c->pool, NULL); /* frees the command buffer */
  free(c);
}

sessile_status sessile_cmd_begin(sessile_cmd *c) {
  VkDevice d = c->gpu->device;
  SESSILE_VK(vkResetCommandBuffer(c->cb, 0));
  for (uint32_t i = 0; i < c->ndpools; i++) SESSILE_VK(vkResetDescriptorPool(d, c->dpools[i], 0));
  c->cur_pool = 0;
  c->ndispatch = 0;
  c->ind_args = NULL, c->nind = 0;
  free_retired(c); /* the last submission has been waited for */
  c->stage_used = 0, c->ncopies_up = c->nuploads = 0, c->nreads = 0, c->down_barrier = 0, c->submits = 0;
  c->copied = 0;
  c->ts_written = 0;
  c->ts_valid = 0;
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  SESSILE_VK(vkBeginCommandBuffer(c->cb, &bi));
  if (c->queries) vkCmdResetQueryPool(c->cb, c->queries, 0, TIMESTAMPS);
  c->nprof = c->nuntimed = 0;
  c->prof_rec = c->gpu->prof_on && c->queries; /* c->queries: the queue has timestamps */
  if (c->prof_rec && !c->prof_q) {
    VkQueryPoolCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 2 * PROF_MAX};
    SESSILE_VK(vkCreateQueryPool(d, &qi, NULL, &c->prof_q));
  }
  if (c->prof_rec) vkCmdResetQueryPool(c->cb, c->prof_q, 0, 2 * PROF_MAX);
  c->recording = 1;
  c->recorded = 0;
  return SESSILE_OK;
}

static sessile_status alloc_set(sessile_cmd *c, VkDescriptorSetLayout layout, VkDescriptorSet *set) {
  for (;;) {
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = c->dpools[c->cur_pool],
                                      .descriptorSetCount = 1, .pSetLayouts = &layout};
    VkResult r = vkAllocateDescriptorSets(c->gpu->device, &ai, set);
    if (r == VK_SUCCESS) return SESSILE_OK;
    if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL)
      return sessile_vk_fail_(r, "vkAllocateDescriptorSets", __func__);
    c->cur_pool++;
    if (c->cur_pool == c->ndpools) SESSILE_CALL(add_pool(c));
  }
}

static void barrier(VkCommandBuffer cb, VkPipelineStageFlags dst_stage, VkAccessFlags dst) {
  VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                        .dstAccessMask = dst};
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dst_stage, 0, 1, &mb, 0, NULL, 0,
                       NULL);
}

/* The whole-buffer texel view of `b` in format `kind`, made on first use. */
static sessile_status texel_view(sessile_gpu *g, sessile_buffer *b, uint32_t kind, const char *kname,
                                 VkBufferView *out) {
  static const VkFormat fmt[4] = {VK_FORMAT_UNDEFINED, VK_FORMAT_R32_UINT, VK_FORMAT_R32G32_UINT,
                                  VK_FORMAT_R32G32B32A32_UINT};
  static const size_t texel_bytes[4] = {1, 4, 8, 16};
  if (!b->view[kind]) {
    size_t texels = b->bytes / texel_bytes[kind];
    SESSILE_CHECK(texels <= g->info.max_texel_buffer_elements, SESSILE_ERR_TOO_LARGE,
                  "kernel %s: a buffer of %zu texels exceeds maxTexelBufferElements (%u) of %s",
                  kname, texels, g->info.max_texel_buffer_elements, g->info.name);
    VkBufferViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
                                 .buffer = b->buffer, .format = fmt[kind], .offset = 0,
                                 .range = texels * texel_bytes[kind]};
    SESSILE_VK(vkCreateBufferView(g->device, &vi, NULL, &b->view[kind]));
  }
  *out = b->view[kind];
  return SESSILE_OK;
}

/* Above maxComputeWorkGroupCount[0], `groups` spread over y (kernels use
 * sessile_gid()). */
static sessile_status split_groups(const sessile_cmd *c, uint32_t groups, const char *kname, uint32_t *gx,
                                   uint32_t *gy) {
  uint32_t maxx = c->gpu->info.max_workgroup_count_x;
  *gx = groups, *gy = 1;
  if (groups > maxx) {
    *gy = (groups + maxx - 1) / maxx;
    *gx = (groups + *gy - 1) / *gy;
    SESSILE_CHECK(*gy <= c->gpu->limits.maxComputeWorkGroupCount[1], SESSILE_ERR_TOO_LARGE,
                  "kernel %s needs %u workgroups, more than the device allows", kname, groups);
  }
  return SESSILE_OK;
}

sessile_status sessile_cmd_copy(sessile_cmd *c, sessile_buffer *src, sessile_buffer *dst, size_t bytes) {
  SESSILE_CHECK(c->recording, SESSILE_ERR_INTERNAL, "a buffer copy outside a recording");
  SESSILE_CHECK(c->nreads == 0, SESSILE_ERR_INTERNAL, "a buffer copy after a download in the same recording");
  SESSILE_CHECK(src && dst && src != dst && bytes <= src->bytes && bytes <= dst->bytes, SESSILE_ERR_INTERNAL,
                "a buffer copy of %zu bytes between buffers of %zu and %zu", bytes, src ? src->bytes : 0,
                dst ? dst->bytes : 0);
  if (bytes == 0) return SESSILE_OK;
  /* the dispatches' and uploads' writes (and the reads of dst) before it */
  VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                        .srcAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                         VK_ACCESS_TRANSFER_WRITE_BIT,
                        .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
  vkCmdPipelineBarrier(c->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, NULL, 0, NULL);
  VkBufferCopy r = {.srcOffset = 0, .dstOffset = 0, .size = bytes};
  vkCmdCopyBuffer(c->cb, src->buffer, dst->buffer, 1, &r);
  c->copied = 1;
  return SESSILE_OK;
}

sessile_status sessile_cmd_dispatch(sessile_cmd *c, const sessile_kernel *k, uint32_t groups,
                                    sessile_buffer *const *buffers, const void *push) {
  SESSILE_CHECK(c->recording, SESSILE_ERR_INTERNAL, "dispatch of %s outside a recording", k->name);
  if (groups == 0) return SESSILE_OK;
  /* the kernel object is the caller's const handle; its pipeline is a cache */
  SESSILE_CALL(sessile_kernel_pipeline((sessile_kernel *)k));
  VkDescriptorSet set;
  SESSILE_CALL(alloc_set(c, k->set_layout, &set));
  VkDescriptorBufferInfo bi[SESSILE_MAX_BINDINGS];
  VkWriteDescriptorSet w[SESSILE_MAX_BINDINGS];
  VkBufferView views[SESSILE_MAX_BINDINGS];
  for (uint32_t i = 0; i < k->nbuffers; i++) {
    SESSILE_CHECK(buffers[i], SESSILE_ERR_INTERNAL, "kernel %s: binding %u is NULL", k->name, i);
    bi[i] = (VkDescriptorBufferInfo){.buffer = buffers[i]->buffer, .offset = 0,
                                     .range = VK_WHOLE_SIZE};
    w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set,
                                  .dstBinding = i, .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  .pBufferInfo = &bi[i]};
    if (k->texel[i]) {
      SESSILE_CALL(texel_view(c->gpu, buffers[i], k->texel[i], k->name, &views[i]));
      w[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
      w[i].pBufferInfo = NULL;
      w[i].pTexelBufferView = &views[i];
    }
  }
  SESSILE_CHECK(c->nreads == 0, SESSILE_ERR_INTERNAL,
                "dispatch of %s after a download in the same recording (downloads come last)", k->name);
  vkUpdateDescriptorSets(c->gpu->device, k->nbuffers, w, 0, NULL);
  /* an indirect dispatch reads its counts, which a kernel before it may have zeroed */
  int slot = -1;
  for (uint32_t i = 0; c->ind_args && i < c->nind && slot < 0; i++)
    if (c->ind_groups[i] == groups) slot = (int)i;
  VkPipelineStageFlags ind_stage = c->ind_args ? VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT : 0;
  VkAccessFlags ind_access = c->ind_args ? VK_ACCESS_INDIRECT_COMMAND_READ_BIT : 0;
  if (c->ndispatch == 0 && c->ncopies_up > 0) { /* the recorded uploads, before the first dispatch */
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                          .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | ind_access};
    vkCmdPipelineBarrier(c->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | ind_stage, 0, 1,
                         &mb, 0, NULL, 0, NULL);
  }
  if (c->ndispatch > 0)
    barrier(c->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | ind_stage,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | ind_access);
  if (c->copied) { /* sessile_cmd_copy's writes, before this dispatch reads them */
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                          .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | ind_access};
    vkCmdPipelineBarrier(c->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | ind_stage, 0, 1,
                         &mb, 0, NULL, 0, NULL);
    c->copied = 0;
  }
  vkCmdBindPipeline(c->cb, VK_PIPELINE_BIND_POINT_COMPUTE, k->pipeline);
  vkCmdBindDescriptorSets(c->cb, VK_PIPELINE_BIND_POINT_COMPUTE, k->layout, 0, 1, &set, 0, NULL);
  if (k->push_bytes)
    vkCmdPushConstants(c->cb, k->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, k->push_bytes, push);
  uint32_t gx, gy;
  SESSILE_CALL(split_groups(c, groups, k->name, &gx, &gy));
  int timed = c->prof_rec && c->nprof < PROF_MAX;
  if (timed) vkCmdWriteTimestamp(c->cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, c->prof_q, 2 * c->nprof);
  if (slot >= 0) vkCmdDispatchIndirect(c->cb, c->ind_args->buffer, (VkDeviceSize)(4 + 3 * slot) * 4);
  else vkCmdDispatch(c->cb, gx, gy, 1);
  if (timed) {
    vkCmdWriteTimestamp(c->cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, c->prof_q, 2 * c->nprof + 1);
    c->prof_name[c->nprof++] = k->name;
  } else if (c->prof_rec)
    c->nuntimed++;
  c->ndispatch++;
  return SESSILE_OK;
}

sessile_status sessile_cmd_indirect(sessile_cmd *c, sessile_buffer *args, const uint32_t *groups, uint32_t n) {
  SESSILE_CHECK(c->recording && c->ndispatch == 0, SESSILE_ERR_INTERNAL,
                "sessile_cmd_indirect after a dispatch or outside a recording");
  uint32_t w[4 + 3 * SESSILE_INDIRECT_MAX] = {0}, m = 0;
  for (uint32_t i = 0; i < n; i++) {
    int seen = groups[i] == 0;
    for (uint32_t j = 0; j < m; j++) seen |= c->ind_groups[j] == groups[i];
    if (seen) continue;
    SESSILE_CHECK(m < SESSILE_INDIRECT_MAX, SESSILE_ERR_INTERNAL, "more than %d indirect group counts",
                  SESSILE_INDIRECT_MAX);
    uint32_t gx, gy;
    SESSILE_CALL(split_groups(c, groups[i], "an indirect dispatch", &gx, &gy));
    c->ind_groups[m] = groups[i];
    w[4 + 3 * m] = gx, w[5 + 3 * m] = gy, w[6 + 3 * m] = 1;
    m++;
  }
  w[0] = m;
  SESSILE_CHECK(args->bytes >= sizeof w, SESSILE_ERR_INTERNAL, "the indirect arguments need %zu bytes", sizeof w);
  SESSILE_CALL(sessile_cmd_upload(c, args, 0, w, (4 + 3 * (size_t)m) * 4));
  c->ind_args = args, c->nind = m;
  return SESSILE_OK;
}

sessile_status sessile_cmd_timestamp(sessile_cmd *c, uint32_t slot) {
  SESSILE_CHECK(slot < TIMESTAMPS, SESSILE_ERR_INTERNAL, "timestamp slot %u >= %d", slot, TIMESTAMPS);
  SESSILE_CHECK(c->recording, SESSILE_ERR_INTERNAL, "timestamp outside a recording");
  if (!c->queries) return SESSILE_OK;
  vkCmdWriteTimestamp(c->cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, c->queries, slot);
  c->ts_written |= 1ull << slot;
  return SESSILE_OK;
}

sessile_status sessile_cmd_end(sessile_cmd *c) {
  SESSILE_CHECK(c->recording, SESSILE_ERR_INTERNAL, "end without begin");
  /* the shaders' and the recorded copies' writes, visible to the host */
  VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                        .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(c->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, NULL, 0, NULL);
  SESSILE_VK(vkEndCommandBuffer(c->cb));
  c->recording = 0;
  c->recorded = 1;
  return SESSILE_OK;
}

/* --- transfers inside a recording -------------------------------------- */
int sessile_cmd_recording(const sessile_cmd *c) { return c->recording; }

static sessile_status sync_mapped(sessile_buffer *b, int flush) {
  if (b->coherent) return SESSILE_OK;
  VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = b->memory, .size = VK_WHOLE_SIZE};
  if (flush) SESSILE_VK(vkFlushMappedMemoryRanges(b->gpu->device, 1, &r));
  else SESSILE_VK(vkInvalidateMappedMemoryRanges(b->gpu->device, 1, &r));
  return SESSILE_OK;
}

/* `bytes` of this recording's stage, at *off (16-byte aligned). */
static sessile_status stage_take(sessile_cmd *c, size_t bytes, size_t *off) {
  size_t at = (c->stage_used + 15) & ~(size_t)15;
  if (!c->stage || sessile_buffer_size(c->stage) < at + bytes) {
    size_t want = (size_t)64 << 10;
    while (want < 2 * (at + bytes)) want *= 2;
    if (c->stage) { /* recorded copies may still name it: kept until the next begin */
      sessile_buffer **r = realloc(c->retired, (c->nretired + 1) * sizeof *r);
      SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory for a recording's transfers");
      c->retired = r;
      c->retired[c->nretired++] = c->stage;
      c->stage = NULL;
    }
    SESSILE_CALL(sessile_buffer_create(c->gpu, want, SESSILE_BUFFER_MAPPED, &c->stage));
    SESSILE_CHECK(c->stage->mapped, SESSILE_ERR_INTERNAL, "a recording's staging buffer is not mapped");
    at = 0;
  }
  *off = at;
  c->stage_used = at + bytes;
  return SESSILE_OK;
}

static sessile_status check_transfer(const sessile_cmd *c, const sessile_buffer *b, size_t offset, size_t bytes,
                                     const char *what) {
  SESSILE_CHECK(c->recording, SESSILE_ERR_INTERNAL, "%s outside a recording", what);
  SESSILE_CHECK(b && offset <= b->bytes && bytes <= b->bytes - offset, SESSILE_ERR_USAGE,
                "%s of %zu bytes at offset %zu exceeds the %zu-byte buffer", what, bytes, offset, b ? b->bytes : 0);
  return SESSILE_OK;
}

/* Where an upload of `bytes` goes on the host: the mapped buffer itself, or
 * the stage (and the copy to the device recorded). */
static sessile_status upload_dst(sessile_cmd *c, sessile_buffer *b, size_t offset, size_t bytes, void **dst) {
  SESSILE_CHECK(c->ndispatch == 0 && c->nreads == 0, SESSILE_ERR_INTERNAL,
                "an upload after a dispatch or a download in the same recording (uploads come first)");
  c->nuploads++;
  if (b->mapped) {
    *dst = (char *)b->mapped + offset;
    return SESSILE_OK;
  }
  size_t at;
  SESSILE_CALL(stage_take(c, bytes, &at));
  VkBufferCopy region = {.srcOffset = at, .dstOffset = offset, .size = bytes};
  vkCmdCopyBuffer(c->cb, c->stage->buffer, b->buffer, 1, &region);
  c->ncopies_up++;
  *dst = (char *)c->stage->mapped + at;
  return SESSILE_OK;
}

sessile_status sessile_cmd_upload(sessile_cmd *c, sessile_buffer *b, size_t offset, const void *src, size_t bytes) {
  SESSILE_CALL(check_transfer(c, b, offset, bytes, "a recorded upload"));
  if (bytes == 0) return SESSILE_OK;
  void *dst = NULL;
  SESSILE_CALL(upload_dst(c, b, offset, bytes, &dst));
  memcpy(dst, src, bytes);
  return b->mapped ? sync_mapped(b, 1) : SESSILE_OK;
}

sessile_status sessile_cmd_upload_reals(sessile_cmd *c, sessile_buffer *b, size_t offset_reals, const double *src,
                                        size_t n) {
  if (c->gpu->info.precision == 64) return sessile_cmd_upload(c, b, offset_reals * 8, src, n * 8);
  SESSILE_CALL(check_transfer(c, b, offset_reals * 4, n * 4, "a recorded upload"));
  if (n == 0) return SESSILE_OK;
  void *dst = NULL;
  SESSILE_CALL(upload_dst(c, b, offset_reals * 4, n * 4, &dst));
  float *t = dst;
  for (size_t i = 0; i < n; i++) t[i] = (float)src[i];
  return b->mapped ? sync_mapped(b, 1) : SESSILE_OK;
}

static sessile_status download_rec(sessile_cmd *c, sessile_buffer *b, size_t offset, void *dst, size_t bytes,
                                   int f32) {
  SESSILE_CALL(check_transfer(c, b, offset, bytes, "a recorded download"));
  if (bytes == 0) return SESSILE_OK;
  if (c->nreads == c->cap_reads) {
    size_t cap = c->cap_reads ? 2 * c->cap_reads : 8;
    struct cmd_read *r = realloc(c->reads, cap * sizeof *r);
    SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory for a recording's transfers");
    c->reads = r, c->cap_reads = cap;
  }
  struct cmd_read rd = {.dst = dst, .src = b, .offset = offset, .bytes = bytes, .f32 = f32};
  if (!b->mapped) {
    if (!c->down_barrier) { /* the dispatches' and uploads' writes, before the copies read them */
      c->down_barrier = 1;
      VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                            .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                            .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT};
      vkCmdPipelineBarrier(c->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, NULL, 0, NULL);
    }
    size_t at;
    SESSILE_CALL(stage_take(c, bytes, &at));
    VkBufferCopy region = {.srcOffset = offset, .dstOffset = at, .size = bytes};
    vkCmdCopyBuffer(c->cb, b->buffer, c->stage->buffer, 1, &region);
    rd.src = c->stage, rd.offset = at;
  }
  c->reads[c->nreads++] = rd;
  return SESSILE_OK;
}

sessile_status sessile_cmd_download(sessile_cmd *c, sessile_buffer *b, size_t offset, void *dst, size_t bytes) {
  return download_rec(c, b, offset, dst, bytes, 0);
}

sessile_status sessile_cmd_download_reals(sessile_cmd *c, sessile_buffer *b, size_t offset_reals, double *dst,
                                          size_t n) {
  if (c->gpu->info.precision == 64) return download_rec(c, b, offset_reals * 8, dst, n * 8, 0);
  return download_rec(c, b, offset_reals * 4, dst, n * 4, 1);
}

/* After the wait: the recorded downloads into their host arrays. */
static sessile_status finish_reads(sessile_cmd *c) {
  for (size_t i = 0; i < c->nreads; i++) {
    const struct cmd_read *r = &c->reads[i];
    SESSILE_CALL(sync_mapped(r->src, 0));
    const char *p = (const char *)r->src->mapped + r->offset;
    if (!r->f32) memcpy(r->dst, p, r->bytes);
    else {
      const float *f = (const float *)(const void *)p;
      double *d = r->dst;
      for (size_t k = 0; k < r->bytes / 4; k++) d[k] = f[k];
    }
  }
  return SESSILE_OK;
}

sessile_status sessile_cmd_submit_wait(sessile_cmd *c) {
  SESSILE_CHECK(c->recorded, SESSILE_ERR_INTERNAL, "submit of an unfinished recording");
  /* a mapped buffer's upload was written when recorded, once: no replay */
  SESSILE_CHECK(c->nuploads == 0 || c->submits == 0, SESSILE_ERR_INTERNAL,
                "a recording with uploads runs once (record it again to run it again)");
  c->submits++;
  VkDevice d = c->gpu->device;
  SESSILE_VK(vkResetFences(d, 1, &c->fence));
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                     .pCommandBuffers = &c->cb};
  SESSILE_VK(vkQueueSubmit(c->gpu->queue, 1, &si, c->fence));
  c->gpu->submissions++;
  SESSILE_VK(vkWaitForFences(d, 1, &c->fence, VK_TRUE, UINT64_MAX));
  SESSILE_CALL(finish_reads(c));
  c->ts_valid = 0;
  if (c->queries && c->ts_written) {
    /* Read the slots that were written (contiguous runs of the mask). */
    for (uint32_t s = 0; s < TIMESTAMPS; s++) {
      if (!(c->ts_written >> s & 1)) continue;
      SESSILE_VK(vkGetQueryPoolResults(d, c->queries, s, 1, sizeof(uint64_t), &c->ts[s],
                                       sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    }
    c->ts_valid = 1;
  }
  if (c->prof_rec) c->gpu->prof_untimed += c->nuntimed;
  if (c->prof_rec && c->nprof) {
    uint64_t *t = malloc(2 * (size_t)c->nprof * sizeof *t);
    SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory for the profile's timestamps");
    VkResult vr = vkGetQueryPoolResults(d, c->prof_q, 0, 2 * c->nprof, 2 * (size_t)c->nprof * sizeof *t, t,
                                        sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    sessile_status ps = vr == VK_SUCCESS ? SESSILE_OK
                                         : sessile_error_set(SESSILE_ERR_VULKAN, "vkGetQueryPoolResults failed (%d)", (int)vr);
    for (uint32_t i = 0; ps == SESSILE_OK && i < c->nprof; i++)
      ps = sessile_gpu_profile_add_(c->gpu, c->prof_name[i],
                                    1e-6 * (double)(t[2 * i + 1] - t[2 * i]) * c->gpu->info.timestamp_period_ns);
    free(t);
    SESSILE_CALL(ps);
  }
  return SESSILE_OK;
}

sessile_status sessile_cmd_elapsed_ns(sessile_cmd *c, uint32_t s0, uint32_t s1, double *ns) {
  *ns = 0;
  SESSILE_CHECK(c->queries, SESSILE_ERR_UNSUPPORTED, "this device has no compute timestamps");
  SESSILE_CHECK(c->ts_valid && s0 < TIMESTAMPS && s1 < TIMESTAMPS &&
                    (c->ts_written >> s0 & 1) && (c->ts_written >> s1 & 1),
                SESSILE_ERR_INTERNAL, "timestamp slots %u/%u were not recorded", s0, s1);
  *ns = (double)(c->ts[s1] - c->ts[s0]) * c->gpu->info.timestamp_period_ns;
  return SESSILE_OK;
}
