/* Device description and choice: discrete > integrated > virtual > CPU, with
 * the options' device as override (the CLI's --device INDEX|NAME-SUBSTRING
 * or $SESSILE_DEVICE). */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include "device_info.h"

static const char *type_name(VkPhysicalDeviceType t) {
  switch (t) {
  case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
  case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
  case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
  case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
  default: return "other";
  }
}

static int type_rank(VkPhysicalDeviceType t) {
  switch (t) {
  case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
  case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
  case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
  case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
  default: return 0;
  }
}

int sessile_compute_queue_family_(VkPhysicalDevice p, uint32_t *ts_bits) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(p, &n, NULL);
  VkQueueFamilyProperties q[32];
  if (n > 32) n = 32;
  vkGetPhysicalDeviceQueueFamilyProperties(p, &n, q);
  /* Prefer a compute queue without graphics (dedicated compute), else any. */
  int best = -1;
  for (uint32_t i = 0; i < n; i++) {
    if (!(q[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (best < 0 || !(q[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) best = (int)i;
  }
  if (best >= 0 && ts_bits) *ts_bits = q[best].timestampValidBits;
  return best;
}

void sessile_describe_device_(VkPhysicalDevice p, uint32_t index, sessile_gpu_info *info,
                              VkPhysicalDeviceMemoryProperties *mem_out) {
  memset(info, 0, sizeof *info);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(p, &props);
  VkPhysicalDeviceSubgroupProperties sub = {.sType =
                                                VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceDriverProperties drv = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                    .pNext = &sub};
  int has_driver = VK_API_VERSION_MINOR(props.apiVersion) >= 2 ||
                   VK_API_VERSION_MAJOR(props.apiVersion) > 1;
  if (has_driver) sub.pNext = &drv;
  vkGetPhysicalDeviceProperties2(p, &p2);
  VkPhysicalDeviceFeatures feat;
  vkGetPhysicalDeviceFeatures(p, &feat);
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(p, &mem);

  snprintf(info->name, sizeof info->name, "%s", props.deviceName);
  snprintf(info->type, sizeof info->type, "%s", type_name(props.deviceType));
  if (has_driver)
    snprintf(info->driver, sizeof info->driver, "%s %s", drv.driverName, drv.driverInfo);
  else
    snprintf(info->driver, sizeof info->driver, "driver version 0x%x", props.driverVersion);
  info->api_version = props.apiVersion;
  info->vendor_id = props.vendorID;
  info->device_id = props.deviceID;
  info->index = index;
  info->subgroup_size = sub.subgroupSize;
  {
    VkSubgroupFeatureFlags need = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    info->subgroup_arithmetic = (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                                (sub.supportedOperations & need) == need;
  }
  info->float64 = feat.shaderFloat64 ? 1 : 0;
  info->max_storage_buffer_range = props.limits.maxStorageBufferRange;
  info->max_texel_buffer_elements = props.limits.maxTexelBufferElements;
  info->max_workgroup_invocations = props.limits.maxComputeWorkGroupInvocations;
  info->max_workgroup_count_x = props.limits.maxComputeWorkGroupCount[0];
  info->timestamp_period_ns = props.limits.timestampPeriod;
  /* Unified: an integrated/CPU device whose device-local memory is host-visible
   * and coherent, so buffers are mapped directly with no staging copies. */
  info->unified_memory = 0;
  if (props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ||
      props.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) {
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                 VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t i = 0; i < mem.memoryTypeCount; i++)
      if ((mem.memoryTypes[i].propertyFlags & want) == want) info->unified_memory = 1;
  }
  /* The largest device-local heap: what a run's estimate is checked against. */
  info->device_local_bytes = 0;
  for (uint32_t h = 0; h < mem.memoryHeapCount; h++)
    if ((mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
        mem.memoryHeaps[h].size > info->device_local_bytes)
      info->device_local_bytes = mem.memoryHeaps[h].size;
  if (mem_out) *mem_out = mem;
}

static int ieq_substr(const char *hay, const char *needle) {
  size_t n = strlen(needle);
  for (const char *h = hay; *h; h++) {
    size_t i = 0;
    while (i < n && h[i] && tolower((unsigned char)h[i]) == tolower((unsigned char)needle[i])) i++;
    if (i == n) return 1;
  }
  return n == 0;
}

sessile_status sessile_choose_device_(VkInstance inst, const char *choice, VkPhysicalDevice *out,
                                      uint32_t *out_index) {
  uint32_t n = 0;
  VkResult r = vkEnumeratePhysicalDevices(inst, &n, NULL);
  if (r < 0) return sessile_vk_fail_(r, "vkEnumeratePhysicalDevices", __func__);
  SESSILE_CHECK(n > 0, SESSILE_ERR_NO_DEVICE,
                "no Vulkan device found: install mesa-vulkan-drivers (the CPU driver lavapipe) "
                "or your GPU's Vulkan driver, then check with `vulkaninfo --summary`");
  VkPhysicalDevice devs[16];
  if (n > 16) n = 16;
  r = vkEnumeratePhysicalDevices(inst, &n, devs);
  if (r < 0) return sessile_vk_fail_(r, "vkEnumeratePhysicalDevices", __func__);

  int pick = -1;
  if (choice && *choice) {
    char *end = NULL;
    long idx = strtol(choice, &end, 10);
    if (end && *end == 0) {
      SESSILE_CHECK(idx >= 0 && idx < (long)n, SESSILE_ERR_USAGE,
                    "device index %ld does not exist: there are %u devices (0..%u); "
                    "list them with `sessile devices`", idx, n, n - 1);
      pick = (int)idx;
    } else {
      for (uint32_t i = 0; i < n && pick < 0; i++) {
        VkPhysicalDeviceProperties pr;
        vkGetPhysicalDeviceProperties(devs[i], &pr);
        if (ieq_substr(pr.deviceName, choice)) pick = (int)i;
      }
      SESSILE_CHECK(pick >= 0, SESSILE_ERR_USAGE,
                    "no device name contains \"%s\": list them with `sessile devices`", choice);
    }
    SESSILE_CHECK(sessile_compute_queue_family_(devs[pick], NULL) >= 0, SESSILE_ERR_NO_DEVICE,
                  "device %d has no compute queue: choose another with --device", pick);
  } else {
    int best_rank = -1;
    for (uint32_t i = 0; i < n; i++) {
      VkPhysicalDeviceProperties pr;
      vkGetPhysicalDeviceProperties(devs[i], &pr);
      if (sessile_compute_queue_family_(devs[i], NULL) < 0) continue;
      if (VK_API_VERSION_MINOR(pr.apiVersion) < 1 && VK_API_VERSION_MAJOR(pr.apiVersion) == 1)
        continue; /* need Vulkan 1.1 */
      int rank = type_rank(pr.deviceType);
      if (rank > best_rank) { best_rank = rank; pick = (int)i; }
    }
    SESSILE_CHECK(pick >= 0, SESSILE_ERR_NO_DEVICE,
                  "no Vulkan 1.1 device with a compute queue: install mesa-vulkan-drivers");
  }
  *out = devs[pick];
  *out_index = (uint32_t)pick;
  return SESSILE_OK;
}
