/* One error path for Vulkan: every failed call names itself, its VkResult and
 * what the user can do about it. */
#include "gpu_internal.h"

const char *sessile_vk_result_name(VkResult r) {
  switch (r) {
#define X(v) case v: return #v;
    X(VK_SUCCESS) X(VK_NOT_READY) X(VK_TIMEOUT) X(VK_EVENT_SET) X(VK_EVENT_RESET)
    X(VK_INCOMPLETE) X(VK_ERROR_OUT_OF_HOST_MEMORY) X(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    X(VK_ERROR_INITIALIZATION_FAILED) X(VK_ERROR_DEVICE_LOST) X(VK_ERROR_MEMORY_MAP_FAILED)
    X(VK_ERROR_LAYER_NOT_PRESENT) X(VK_ERROR_EXTENSION_NOT_PRESENT)
    X(VK_ERROR_FEATURE_NOT_PRESENT) X(VK_ERROR_INCOMPATIBLE_DRIVER)
    X(VK_ERROR_TOO_MANY_OBJECTS) X(VK_ERROR_FORMAT_NOT_SUPPORTED)
    X(VK_ERROR_FRAGMENTED_POOL) X(VK_ERROR_UNKNOWN) X(VK_ERROR_OUT_OF_POOL_MEMORY)
    X(VK_ERROR_INVALID_EXTERNAL_HANDLE) X(VK_ERROR_FRAGMENTATION)
    X(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS) X(VK_PIPELINE_COMPILE_REQUIRED)
#undef X
  default: return "VK_RESULT_UNKNOWN";
  }
}

static const char *hint(VkResult r) {
  switch (r) {
  case VK_ERROR_OUT_OF_HOST_MEMORY: return "the host ran out of memory: use a smaller problem";
  case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    return "the device ran out of memory: use a smaller problem or another device (--device)";
  case VK_ERROR_DEVICE_LOST:
    return "the device was lost (driver crash or timeout): rerun; if it repeats, try another device";
  case VK_ERROR_INCOMPATIBLE_DRIVER:
    return "no Vulkan 1.1 driver: install mesa-vulkan-drivers (CPU lavapipe) or your GPU's driver";
  case VK_ERROR_LAYER_NOT_PRESENT:
    return "a requested layer is missing: install vulkan-validationlayers or unset SESSILE_VALIDATION";
  case VK_ERROR_EXTENSION_NOT_PRESENT:
  case VK_ERROR_FEATURE_NOT_PRESENT:
    return "the device lacks a required feature: choose another device with --device";
  case VK_ERROR_INITIALIZATION_FAILED:
    return "Vulkan could not initialise: check the driver install (vulkaninfo --summary)";
  default: return "this is unexpected: please report it with the output of `sessile devices`";
  }
}

sessile_status sessile_vk_fail_(VkResult r, const char *call, const char *func) {
  sessile_status s = (r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY)
                         ? SESSILE_ERR_NO_MEMORY
                         : SESSILE_ERR_VULKAN;
  /* Keep only the function name of the call expression. */
  char name[96];
  size_t i = 0;
  while (call[i] && call[i] != '(' && i + 1 < sizeof name) { name[i] = call[i]; i++; }
  name[i] = 0;
  return sessile_error_set(s, "%s failed with %s (in %s): %s", name, sessile_vk_result_name(r),
                           func, hint(r));
}
