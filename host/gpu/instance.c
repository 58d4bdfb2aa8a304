/* Vulkan instance, with the Khronos validation layer on request.  Validation
 * warnings and errors are counted (tests fail on any) and handed to the
 * context's validation_message callback, by default printed to stderr. */
#define _GNU_SOURCE /* dl_iterate_phdr, RTLD_NODELETE (sanitizer builds) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device_info.h"

#if defined(__SANITIZE_ADDRESS__)
#define SESSILE_PIN_LIBRARIES 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SESSILE_PIN_LIBRARIES 1
#endif
#endif

#ifdef SESSILE_PIN_LIBRARIES
#include <dlfcn.h>
#include <link.h>
/* Sanitizer builds only: before the instance goes, mark every loaded library
 * (the loader's driver and layers among them) never-unloaded.  The driver
 * keeps process-lifetime caches; once the loader dlcloses it, LeakSanitizer
 * reports them at exit as "<unknown module>", which no suppression can name.
 * Pinned, they are reported under libvulkan_lvp.so etc. and tests/lsan.supp
 * applies.  Names are collected first: dlopen is not called while
 * dl_iterate_phdr holds the loader's lock. */
typedef struct { char *name[256]; int n; } lib_list;
static int collect_library(struct dl_phdr_info *info, size_t size, void *data) {
  (void)size;
  lib_list *l = data;
  if (info->dlpi_name && info->dlpi_name[0] && l->n < 256) {
    char *c = malloc(strlen(info->dlpi_name) + 1);
    if (c) l->name[l->n++] = strcpy(c, info->dlpi_name);
  }
  return 0;
}
static void pin_loaded_libraries(void) {
  lib_list l = {.n = 0};
  dl_iterate_phdr(collect_library, &l);
  for (int i = 0; i < l.n; i++) {
    void *h = dlopen(l.name[i], RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
    if (h) dlclose(h); /* drops the reference NOLOAD took; NODELETE stays */
    free(l.name[i]);
  }
}
#else
static void pin_loaded_libraries(void) {}
#endif

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT sev,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *d,
                                                 void *user) {
  (void)type;
  if (sev >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    sessile_validation_sink_ *sink = user;
    int is_error = sev >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    const char *msg = d && d->pMessage ? d->pMessage : "(no message)";
    sink->count++;
    if (sink->fn) sink->fn(sink->user, is_error, msg);
    else /* the documented default (sessile_gpu_options.validation_message) */
      fprintf(stderr, "sessile: vulkan validation %s: %s\n", is_error ? "error" : "warning", msg);
  }
  return VK_FALSE;
}

static int has_layer(const char *name) {
  uint32_t n = 0;
  if (vkEnumerateInstanceLayerProperties(&n, NULL) < 0 || n == 0) return 0;
  VkLayerProperties *l = calloc(n, sizeof *l);
  if (!l) return 0;
  int found = 0;
  if (vkEnumerateInstanceLayerProperties(&n, l) >= 0)
    for (uint32_t i = 0; i < n; i++) found |= strcmp(l[i].layerName, name) == 0;
  free(l);
  return found;
}

sessile_status sessile_instance_create_(int validation, sessile_validation_sink_ *sink, VkInstance *inst,
                                        VkDebugUtilsMessengerEXT *messenger) {
  *inst = VK_NULL_HANDLE;
  *messenger = VK_NULL_HANDLE;
  validation = validation > 0; /* -1: unchosen, off (the CLI reads the environment) */
  static const char *layer = "VK_LAYER_KHRONOS_validation";
  static const char *ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  if (validation)
    SESSILE_CHECK(has_layer(layer), SESSILE_ERR_UNSUPPORTED,
                  "validation was requested but %s is not installed: "
                  "apt-get install vulkan-validationlayers (or unset SESSILE_VALIDATION)", layer);

  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                           .pApplicationName = "sessile",
                           .applicationVersion = 1,
                           .pEngineName = "sessile",
                           .apiVersion = VK_API_VERSION_1_2};
  VkDebugUtilsMessengerCreateInfoEXT mi = {
      .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
      .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
      .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
      .pfnUserCallback = on_message,
      .pUserData = sink};
  VkInstanceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                             .pNext = validation ? &mi : NULL, /* also catches create/destroy */
                             .pApplicationInfo = &app,
                             .enabledLayerCount = validation ? 1 : 0,
                             .ppEnabledLayerNames = validation ? &layer : NULL,
                             .enabledExtensionCount = validation ? 1 : 0,
                             .ppEnabledExtensionNames = validation ? &ext : NULL};
  VkResult r = vkCreateInstance(&ci, NULL, inst);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    return sessile_error_set(SESSILE_ERR_NO_DEVICE,
                             "vkCreateInstance failed with %s: no usable Vulkan driver; install "
                             "mesa-vulkan-drivers (CPU lavapipe) or your GPU's Vulkan driver",
                             sessile_vk_result_name(r));
  if (r < 0) return sessile_vk_fail_(r, "vkCreateInstance", __func__);
  if (validation) {
    PFN_vkCreateDebugUtilsMessengerEXT create =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(*inst,
                                                                   "vkCreateDebugUtilsMessengerEXT");
    if (!create) {
      vkDestroyInstance(*inst, NULL);
      *inst = VK_NULL_HANDLE;
      return sessile_error_set(SESSILE_ERR_UNSUPPORTED,
                               "vkCreateDebugUtilsMessengerEXT is missing although validation "
                               "was requested: reinstall vulkan-validationlayers");
    }
    r = create(*inst, &mi, NULL, messenger);
    if (r < 0) {
      vkDestroyInstance(*inst, NULL);
      *inst = VK_NULL_HANDLE;
      return sessile_vk_fail_(r, "vkCreateDebugUtilsMessengerEXT", __func__);
    }
  }
  return SESSILE_OK;
}

void sessile_instance_destroy_(VkInstance inst, VkDebugUtilsMessengerEXT messenger) {
  if (!inst) return;
  if (messenger) {
    PFN_vkDestroyDebugUtilsMessengerEXT destroy =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            inst, "vkDestroyDebugUtilsMessengerEXT");
    if (destroy) destroy(inst, messenger, NULL);
  }
  pin_loaded_libraries();
  vkDestroyInstance(inst, NULL);
}
