/* `sessile devices`: every Vulkan device with what matters for sessile. */
#include <stdlib.h>
#include "device_info.h"

static void print_one(FILE *out, VkPhysicalDevice p, uint32_t i, int chosen) {
  sessile_gpu_info info;
  VkPhysicalDeviceMemoryProperties mem;
  sessile_describe_device_(p, i, &info, &mem);
  fprintf(out, "%s[%u] %s\n", chosen ? "* " : "  ", i, info.name);
  fprintf(out, "      type: %s   vendor 0x%04x device 0x%04x   Vulkan %u.%u.%u\n", info.type,
          info.vendor_id, info.device_id, VK_API_VERSION_MAJOR(info.api_version),
          VK_API_VERSION_MINOR(info.api_version), VK_API_VERSION_PATCH(info.api_version));
  fprintf(out, "      driver: %s\n", info.driver);
  for (uint32_t h = 0; h < mem.memoryHeapCount; h++)
    fprintf(out, "      heap %u: %.2f GiB%s\n", h, (double)mem.memoryHeaps[h].size / 1073741824.0,
            (mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) ? " device-local" : "");
  fprintf(out, "      subgroup size: %u (arithmetic: %s)   fp64 (shaderFloat64): %s   unified memory: %s\n",
          info.subgroup_size, info.subgroup_arithmetic ? "yes" : "no", info.float64 ? "yes" : "no",
          info.unified_memory ? "yes" : "no");
  fprintf(out, "      maxStorageBufferRange: %llu bytes (%.0f MiB)   "
               "maxComputeWorkGroupInvocations: %u   maxComputeWorkGroupCount[0]: %u\n",
          (unsigned long long)info.max_storage_buffer_range,
          (double)info.max_storage_buffer_range / 1048576.0, info.max_workgroup_invocations,
          info.max_workgroup_count_x);
  uint32_t ts = 0;
  sessile_compute_queue_family_(p, &ts);
  fprintf(out, "      timestamps: %s (period %.3g ns)\n", ts ? "yes" : "no", info.timestamp_period_ns);
}

sessile_status sessile_gpu_print_devices(FILE *out, const char *device_choice) {
  VkInstance inst;
  VkDebugUtilsMessengerEXT m;
  sessile_validation_sink_ sink = {0, NULL, NULL}; /* validation off: unused */
  SESSILE_CALL(sessile_instance_create_(0, &sink, &inst, &m));
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  uint32_t chosen_index = 0;
  sessile_status s = sessile_choose_device_(inst, device_choice, &chosen, &chosen_index);
  if (s == SESSILE_ERR_USAGE) { /* a --device that names nothing: say only that */
    sessile_instance_destroy_(inst, m);
    return s;
  }
  uint32_t n = 0;
  VkResult r = vkEnumeratePhysicalDevices(inst, &n, NULL);
  if (r >= 0 && n > 0) {
    VkPhysicalDevice devs[16];
    if (n > 16) n = 16;
    r = vkEnumeratePhysicalDevices(inst, &n, devs);
    if (r >= 0) {
      fprintf(out, "%u Vulkan device%s (* = chosen: discrete > integrated > virtual > cpu, "
                   "override with --device or SESSILE_DEVICE)\n", n, n == 1 ? "" : "s");
      for (uint32_t i = 0; i < n; i++) print_one(out, devs[i], i, s == SESSILE_OK && i == chosen_index);
    }
  }
  sessile_instance_destroy_(inst, m);
  if (r < 0) return sessile_vk_fail_(r, "vkEnumeratePhysicalDevices", __func__);
  return s;
}

sessile_status sessile_gpu_check_device(const char *device_choice) {
  /* no choice names nothing: no instance to make (a process's Vulkan start,
   * about 0.1 s on lavapipe, for a check that cannot fail) */
  if (!device_choice || !*device_choice) return SESSILE_OK;
  VkInstance inst;
  VkDebugUtilsMessengerEXT m;
  sessile_validation_sink_ sink = {0, NULL, NULL}; /* validation off: unused */
  if (sessile_instance_create_(0, &sink, &inst, &m) != SESSILE_OK) return SESSILE_OK; /* said at use */
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  uint32_t index = 0;
  sessile_status s = sessile_choose_device_(inst, device_choice, &chosen, &index);
  sessile_instance_destroy_(inst, m);
  /* only a choice that names no device is refused here; no Vulkan device at
   * all is the caller's to report when it needs one */
  return s == SESSILE_ERR_USAGE ? s : SESSILE_OK;
}
