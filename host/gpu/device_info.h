/* Device description and choice (internal to host/gpu). */
#ifndef SESSILE_DEVICE_INFO_H
#define SESSILE_DEVICE_INFO_H
#include "gpu_internal.h"

int sessile_compute_queue_family_(VkPhysicalDevice p, uint32_t *timestamp_bits);
void sessile_describe_device_(VkPhysicalDevice p, uint32_t index, sessile_gpu_info *info,
                              VkPhysicalDeviceMemoryProperties *mem);
sessile_status sessile_choose_device_(VkInstance inst, const char *choice, VkPhysicalDevice *out,
                                      uint32_t *index);
/* Creates an instance (validation: enable the Khronos layer and a messenger
 * reporting to *sink, which must outlive the instance). */
sessile_status sessile_instance_create_(int validation, sessile_validation_sink_ *sink, VkInstance *inst,
                                        VkDebugUtilsMessengerEXT *messenger);
void sessile_instance_destroy_(VkInstance inst, VkDebugUtilsMessengerEXT messenger);
#endif
