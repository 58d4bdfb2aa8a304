/* Compute kernels: one pipeline per embedded SPIR-V module, made from the
 * kernel's declaration (shaders/<layer>/kernels.def).  Bindings 0..n-1 are
 * storage buffers or uniform texel buffers as declared, scalars come as push
 * constants, and the workgroup size is specialisation constant 0, so one
 * SPIR-V serves every device. */
#include <stdlib.h>
#include <string.h>
#include "gpu_internal.h"

/* The shader module and the layouts now (cheap; the validation layer checks
 * the SPIR-V here), the pipeline at the kernel's first dispatch: a driver
 * compiles a pipeline when it is made (lavapipe: LLVM, about 25 ms a kernel
 * here even from the pipeline cache), and a run dispatches only some of the
 * kernels its layer makes (docs/performance.md, "Pipelines made on first
 * use"). */
static sessile_status build(sessile_kernel *k, const sessile_spirv *sp) {
  sessile_gpu *g = k->gpu;
  VkShaderModuleCreateInfo mi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                 .codeSize = sp->bytes, .pCode = sp->code};
  SESSILE_VK(vkCreateShaderModule(g->device, &mi, NULL, &k->module));
  VkDescriptorSetLayoutBinding b[SESSILE_MAX_BINDINGS];
  for (uint32_t i = 0; i < k->nbuffers; i++)
    b[i] = (VkDescriptorSetLayoutBinding){.binding = i,
                                          .descriptorType = k->texel[i]
                                                                ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER
                                                                : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                          .descriptorCount = 1,
                                          .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
  VkDescriptorSetLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                        .bindingCount = k->nbuffers, .pBindings = b};
  SESSILE_VK(vkCreateDescriptorSetLayout(g->device, &li, NULL, &k->set_layout));
  VkPushConstantRange pr = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0,
                            .size = k->push_bytes};
  VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                    .setLayoutCount = 1, .pSetLayouts = &k->set_layout,
                                    .pushConstantRangeCount = k->push_bytes ? 1 : 0,
                                    .pPushConstantRanges = k->push_bytes ? &pr : NULL};
  SESSILE_VK(vkCreatePipelineLayout(g->device, &pli, NULL, &k->layout));
  return SESSILE_OK;
}

sessile_status sessile_kernel_pipeline(sessile_kernel *k) {
  if (k->pipeline) return SESSILE_OK;
  VkSpecializationMapEntry me = {.constantID = 0, .offset = 0, .size = sizeof(uint32_t)};
  VkSpecializationInfo si = {.mapEntryCount = 1, .pMapEntries = &me,
                             .dataSize = sizeof(uint32_t), .pData = &k->local_size};
  VkComputePipelineCreateInfo ci = {
      .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
      .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = k->module, .pName = "main",
                .pSpecializationInfo = &si},
      .layout = k->layout};
  SESSILE_VK(vkCreateComputePipelines(k->gpu->device, k->gpu->pipeline_cache, 1, &ci, NULL, &k->pipeline));
  return SESSILE_OK;
}

/* The binding kind on this precision: a "real" texel is one real wide. */
static uint8_t resolve_kind(sessile_binding_kind kind, uint32_t real_bytes) {
  if (kind != SESSILE_TEXEL_REAL) return (uint8_t)kind;
  return real_bytes == 8 ? SESSILE_TEXEL_RG32UI : SESSILE_TEXEL_R32UI;
}

/* The kernel of declaration d from SPIR-V sp, named `name`. */
static sessile_status create_from(sessile_gpu *g, const sessile_kernel_decl *d, uint32_t real_bytes,
                                  uint32_t local_size, const sessile_spirv *sp, const char *name,
                                  sessile_kernel **out) {
  SESSILE_CHECK(d->nbindings <= SESSILE_MAX_BINDINGS, SESSILE_ERR_INTERNAL, "kernel %s: %u bindings > %d", name,
                d->nbindings, SESSILE_MAX_BINDINGS);
  SESSILE_CHECK(d->push_bytes <= 128 && d->push_bytes % 4 == 0, SESSILE_ERR_INTERNAL,
                "kernel %s: %u push-constant bytes (at most 128, multiple of 4)", name, d->push_bytes);
  if (local_size == 0) local_size = d->local_size ? d->local_size : 256;
  /* Halving keeps a power of two, which the reductions' trees need. */
  while (local_size > 1 && (local_size > g->info.max_workgroup_invocations ||
                            local_size > g->limits.maxComputeWorkGroupSize[0]))
    local_size /= 2;
  sessile_kernel *k = calloc(1, sizeof *k);
  SESSILE_CHECK(k, SESSILE_ERR_NO_MEMORY, "out of host memory");
  k->gpu = g;
  k->nbuffers = d->nbindings;
  k->push_bytes = d->push_bytes;
  k->local_size = local_size;
  for (uint32_t i = 0; i < d->nbindings; i++) {
    if ((unsigned)d->bindings[i].kind > SESSILE_TEXEL_REAL) {
      free(k);
      return sessile_error_set(SESSILE_ERR_INTERNAL, "kernel %s: binding %u has an unknown kind %d",
                               name, i, (int)d->bindings[i].kind);
    }
    k->texel[i] = resolve_kind(d->bindings[i].kind, real_bytes);
  }
  snprintf(k->name, sizeof k->name, "%s", name);
  sessile_status s = build(k, sp);
  if (s != SESSILE_OK) {
    sessile_kernel_destroy(k);
    return s;
  }
  *out = k;
  return SESSILE_OK;
}

sessile_status sessile_kernel_create_decl(sessile_gpu *g, const sessile_kernel_decl *d,
                                          uint32_t real_bytes, uint32_t local_size,
                                          sessile_kernel **out) {
  *out = NULL;
  if (real_bytes == 0) real_bytes = g->info.precision == 64 ? 8 : 4;
  char name[64];
  if (d->per_precision) snprintf(name, sizeof name, "%s.%s", d->name, real_bytes == 8 ? "f64" : "f32");
  else snprintf(name, sizeof name, "%s", d->name);
  const sessile_spirv *sp = sessile_spirv_find(name);
  SESSILE_CHECK(sp, SESSILE_ERR_INTERNAL, "no embedded kernel named \"%s\"", name);
  return create_from(g, d, real_bytes, local_size, sp, name, out);
}

sessile_status sessile_kernel_create_glsl(sessile_gpu *g, const sessile_kernel_decl *d, uint32_t real_bytes,
                                          uint32_t local_size, const char *body, sessile_kernel **out) {
  *out = NULL;
  if (real_bytes == 0) real_bytes = g->info.precision == 64 ? 8 : 4;
  uint32_t *words = NULL;
  size_t n = 0;
  char log[2048];
  sessile_status st = sessile_glsl_to_spirv(d->name, real_bytes == 8, body, &words, &n, log, sizeof log);
  if (st != SESSILE_OK) return sessile_error_set(st, "kernel %s compiled at run time: %s", d->name, log);
  char name[64];
  /* "+": its timings (--kernels) apart from the embedded kernel's */
  snprintf(name, sizeof name, "%s+.%s", d->name, real_bytes == 8 ? "f64" : "f32");
  const sessile_spirv sp = {name, words, n * 4};
  st = create_from(g, d, real_bytes, local_size, &sp, name, out);
  free(words);
  return st;
}

void sessile_kernel_destroy(sessile_kernel *k) {
  if (!k) return;
  VkDevice d = k->gpu->device;
  if (k->pipeline) vkDestroyPipeline(d, k->pipeline, NULL);
  if (k->layout) vkDestroyPipelineLayout(d, k->layout, NULL);
  if (k->set_layout) vkDestroyDescriptorSetLayout(d, k->set_layout, NULL);
  if (k->module) vkDestroyShaderModule(d, k->module, NULL);
  free(k);
}

uint32_t sessile_kernel_local_size(const sessile_kernel *k) { return k->local_size; }
