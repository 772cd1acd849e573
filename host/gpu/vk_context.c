#define _POSIX_C_SOURCE 200809L
#include "vk_context.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_hooks.h"
#include "lexer.h"
#include "vk_check.h"

#define TP2_VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"

static const char no_vulkan_hint[] =
    "tp2: no Vulkan device found; install a Vulkan driver (on Debian: "
    "apt-get install mesa-vulkan-drivers libvulkan1 for the lavapipe CPU "
    "driver, or your GPU vendor's driver)\n";

/* Environment variables that replace the installed drivers (the loader
 * reads VK_DRIVER_FILES first, then the older VK_ICD_FILENAMES). */
static const char *const driver_variables[] = {"VK_DRIVER_FILES", "VK_ICD_FILENAMES"};

/* Says where the drivers came from when the user chose them: a wrong path
 * there explains most driver failures. */
static void print_driver_source(void)
{
    for (size_t i = 0; i < sizeof driver_variables / sizeof *driver_variables; i++) {
        const char *v = getenv(driver_variables[i]);
        if (!v || !*v)
            continue;
        char *shown = lexer_escape(v);
        fprintf(stderr, "tp2: %s is set to '%s': only the driver files it names "
                        "are tried; check them, or unset it to use the installed "
                        "drivers\n", driver_variables[i], shown ? shown : "?");
        free(shown);
        return;
    }
}

static void print_no_vulkan(void)
{
    fputs(no_vulkan_hint, stderr);
    print_driver_source();
}

static unsigned validation_messages;

unsigned vkc_validation_message_count(void)
{
    return validation_messages;
}

/* Counts every message (any fails a --validate run) and says who speaks:
 * the loader's messages during vkCreateInstance (a driver file it could
 * not read, say) are "general", the layer's findings "validation". */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT type,
    const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)severity;
    (void)user;
    validation_messages++;
    const char *who = type & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT ? "validation"
                      : type & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT
                          ? "validation (performance)"
                          : "Vulkan loader";
    fprintf(stderr, "tp2: %s: %s\n", who, data->pMessage);
    return VK_FALSE;
}

/* Drivers print warnings straight to stderr (Mesa: "Failed to create ...
 * for shader cache ...---disabling."), which reads as if tp2 said it
 * without context. While Vulkan starts, stderr goes to a temporary file;
 * afterwards each line is replayed, prefixed "tp2: Vulkan driver: " unless
 * tp2 wrote it. */
struct stderr_capture {
    int saved; /* the real stderr, or -1 when not capturing */
    FILE *file;
};

static void capture_begin(struct stderr_capture *cap)
{
    cap->saved = -1;
    cap->file = tmpfile();
    if (!cap->file)
        return;
    fflush(stderr);
    cap->saved = dup(STDERR_FILENO);
    if (cap->saved >= 0 && dup2(fileno(cap->file), STDERR_FILENO) < 0) {
        close(cap->saved);
        cap->saved = -1;
    }
    if (cap->saved < 0) {
        fclose(cap->file);
        cap->file = NULL;
    }
}

static void capture_end(struct stderr_capture *cap)
{
    if (cap->saved < 0)
        return;
    fflush(stderr);
    dup2(cap->saved, STDERR_FILENO);
    close(cap->saved);
    cap->saved = -1;
    rewind(cap->file);
    char line[1024];
    bool line_start = true;
    while (fgets(line, sizeof line, cap->file)) {
        if (line_start && strncmp(line, "tp2: ", 5) != 0)
            fputs("tp2: Vulkan driver: ", stderr);
        fputs(line, stderr);
        line_start = strchr(line, '\n') != NULL;
    }
    if (!line_start) /* Mesa ends some warnings without a newline */
        fputc('\n', stderr);
    fclose(cap->file);
    cap->file = NULL;
}

static bool has_layer(const char *name)
{
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, NULL) != VK_SUCCESS)
        return false;
    VkLayerProperties *layers = calloc(n ? n : 1, sizeof *layers);
    if (!layers)
        return false;
    bool found = false;
    if (vkEnumerateInstanceLayerProperties(&n, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < n && !found; i++)
            found = strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static const VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
    .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
    .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
    .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
    .pfnUserCallback = on_validation_message,
};

/* True if the validation layer offers instance extension name. */
static bool layer_has_extension(const char *name)
{
    uint32_t n = 0;
    if (vkEnumerateInstanceExtensionProperties(TP2_VALIDATION_LAYER, &n, NULL) != VK_SUCCESS)
        return false;
    VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
    if (!ext)
        return false;
    bool found = false;
    if (vkEnumerateInstanceExtensionProperties(TP2_VALIDATION_LAYER, &n, ext) == VK_SUCCESS)
        for (uint32_t i = 0; i < n && !found; i++)
            found = strcmp(ext[i].extensionName, name) == 0;
    free(ext);
    return found;
}

/* Validation also checks synchronization (hazards between dispatches,
 * and between the device's writes and the host's reads of a band). */
static const VkValidationFeatureEnableEXT validation_features[] = {
    VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
};

static int create_instance(VkInstance *instance, bool validate)
{
    if (validate && !has_layer(TP2_VALIDATION_LAYER)) {
        fprintf(stderr, "tp2: validation requested but %s is not installed "
                        "(Debian: vulkan-validationlayers)\n",
                TP2_VALIDATION_LAYER);
        return -1;
    }
    const char *layers[] = {TP2_VALIDATION_LAYER};
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME,
                                VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    bool sync = validate && layer_has_extension(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger_info,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = validation_features,
    };
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "tp2",
        .apiVersion = VK_API_VERSION_1_1,
    };
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = sync ? (const void *)&features : validate ? &messenger_info : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = validate ? 1 : 0,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = sync ? 2 : validate ? 1 : 0,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult r = vkCreateInstance(&info, NULL, instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) {
        print_no_vulkan();
        return -1;
    }
    if (r != VK_SUCCESS) {
        /* The loader (1.3.239) answers a driver file it cannot parse with
         * VK_ERROR_OUT_OF_HOST_MEMORY, as if memory were short. */
        fprintf(stderr, "tp2: cannot start Vulkan (vkCreateInstance: %s): most "
                        "likely a Vulkan driver file (an ICD .json manifest) is "
                        "malformed or unreadable; the installed ones are in "
                        "/usr/share/vulkan/icd.d and /etc/vulkan/icd.d\n",
                vk_result_name(r));
        print_driver_source();
        return -1;
    }
    return 0;
}

/* Higher is better: discrete, integrated, virtual, then CPU (lavapipe). */
static int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

static const char *type_name(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

/* Enumerates devices into a new array; -1 after a message if none. */
static int get_devices(VkInstance instance, VkPhysicalDevice **out,
                       uint32_t *count)
{
    *out = NULL;
    *count = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, count, NULL);
    if (r != VK_SUCCESS) {
        fprintf(stderr, "tp2: a Vulkan driver failed to start "
                        "(vkEnumeratePhysicalDevices: %s)\n", vk_result_name(r));
        print_driver_source();
        return -1;
    }
    if (*count == 0) {
        print_no_vulkan();
        return -1;
    }
    *out = calloc(*count, sizeof **out);
    if (!*out) {
        fputs("tp2: out of memory\n", stderr);
        return -1;
    }
    r = vkEnumeratePhysicalDevices(instance, count, *out);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) {
        vk_report("vkEnumeratePhysicalDevices", r, __FILE__, __LINE__);
        free(*out);
        *out = NULL;
        return -1;
    }
    return 0;
}

static int best_device(const VkPhysicalDevice *devices, uint32_t count)
{
    int best = 0, best_rank = -1;
    for (uint32_t i = 0; i < count; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        if (type_rank(p.deviceType) > best_rank) {
            best_rank = type_rank(p.deviceType);
            best = (int)i;
        }
    }
    return best;
}

int vkc_list_devices(FILE *out)
{
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice *devices = NULL;
    uint32_t count = 0;
    int rc = -1;
    struct stderr_capture cap;
    capture_begin(&cap);
    bool ok = create_instance(&instance, false) == 0 &&
              get_devices(instance, &devices, &count) == 0;
    capture_end(&cap);
    if (ok) {
        int best = best_device(devices, count);
        for (uint32_t i = 0; i < count; i++) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            fprintf(out, "%u: %s (%s)%s\n", i, p.deviceName,
                    type_name(p.deviceType),
                    (int)i == best ? " [default]" : "");
        }
        rc = 0;
    }
    free(devices);
    if (instance)
        vkDestroyInstance(instance, NULL);
    return rc;
}

static int find_compute_queue(VkPhysicalDevice dev, uint32_t *family)
{
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(dev, &n, NULL);
    VkQueueFamilyProperties *q = calloc(n ? n : 1, sizeof *q);
    if (!q)
        return -1;
    vkGetPhysicalDeviceQueueFamilyProperties(dev, &n, q);
    int rc = -1;
    for (uint32_t i = 0; i < n && rc != 0; i++)
        if (q[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            *family = i;
            rc = 0;
        }
    free(q);
    return rc;
}

static int pick_device(struct vkc *c, const struct vkc_options *opt)
{
    VkPhysicalDevice *devices = NULL;
    uint32_t count = 0;
    if (get_devices(c->instance, &devices, &count) != 0)
        return -1;
    int index = opt->device_index;
    if (index >= (int)count) {
        fprintf(stderr, "tp2: no device %d: %u device%s found "
                        "(see tp2 --list-devices)\n",
                index, count, count == 1 ? "" : "s");
        free(devices);
        return -1;
    }
    if (index < 0)
        index = best_device(devices, count);
    c->physical = devices[index];
    free(devices);
    vkGetPhysicalDeviceProperties(c->physical, &c->props);
    vkGetPhysicalDeviceMemoryProperties(c->physical, &c->memory);
    if (find_compute_queue(c->physical, &c->queue_family) != 0) {
        fprintf(stderr, "tp2: device '%s' has no compute queue\n",
                c->props.deviceName);
        return -1;
    }
    return 0;
}

/* True if the device offers extension `name`. */
static bool device_has_extension(VkPhysicalDevice physical, const char *name)
{
    uint32_t n = 0;
    if (vkEnumerateDeviceExtensionProperties(physical, NULL, &n, NULL) != VK_SUCCESS)
        return false;
    VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
    bool found = false;
    if (ext && vkEnumerateDeviceExtensionProperties(physical, NULL, &n, ext) == VK_SUCCESS)
        for (uint32_t i = 0; i < n && !found; i++)
            found = strcmp(ext[i].extensionName, name) == 0;
    free(ext);
    return found;
}

/* A CPU device's memory is the host's: reading the packed scene where it
 * lies saves copying it (and its page faults) into memory of the same
 * kind. A GPU would read it across the bus on every ray, so there the
 * scene is copied. The test hook TP2_HOST_IMPORT=0 turns this off. */
static bool wants_host_import(const struct vkc *c)
{
    return c->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU &&
           !test_hooks()->no_host_import &&
           device_has_extension(c->physical, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
}

static int create_device(struct vkc *c, const struct vkc_options *opt)
{
    VkPhysicalDeviceFeatures have;
    vkGetPhysicalDeviceFeatures(c->physical, &have);
    if (opt->need_float64 && !have.shaderFloat64) {
        fprintf(stderr, "tp2: device '%s' has no shaderFloat64, so it "
                        "cannot render --precision double; choose another "
                        "with --device (lavapipe has it)\n",
                c->props.deviceName);
        return -1;
    }
    c->float64 = have.shaderFloat64 && (opt->need_float64 || opt->want_float64);
    if (opt->chosen)
        opt->chosen(c, opt->chosen_user);
    VkPhysicalDeviceFeatures want = {.shaderFloat64 = c->float64};
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = c->queue_family,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    bool import = wants_host_import(c);
    const char *extensions[] = {VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME};
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = import ? 1 : 0,
        .ppEnabledExtensionNames = extensions,
        .pEnabledFeatures = &want,
    };
    TP2_VK_TRY(vkCreateDevice(c->physical, &info, NULL, &c->device));
    vkGetDeviceQueue(c->device, c->queue_family, 0, &c->queue);
    if (import) {
        VkPhysicalDeviceExternalMemoryHostPropertiesEXT host = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT,
        };
        VkPhysicalDeviceProperties2 props = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
            .pNext = &host,
        };
        vkGetPhysicalDeviceProperties2(c->physical, &props);
        c->host_pointer_properties = (PFN_vkGetMemoryHostPointerPropertiesEXT)
            vkGetDeviceProcAddr(c->device, "vkGetMemoryHostPointerPropertiesEXT");
        if (c->host_pointer_properties)
            c->host_import = host.minImportedHostPointerAlignment;
    }
    return 0;
}

static int create_messenger(struct vkc *c)
{
    PFN_vkCreateDebugUtilsMessengerEXT create =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            c->instance, "vkCreateDebugUtilsMessengerEXT");
    if (!create) {
        fputs("tp2: vkCreateDebugUtilsMessengerEXT is missing\n", stderr);
        return -1;
    }
    TP2_VK_TRY(create(c->instance, &messenger_info, NULL, &c->messenger));
    return 0;
}

static int create_all(struct vkc *c, const struct vkc_options *opt)
{
    if (create_instance(&c->instance, opt->validate) != 0)
        return -1;
    if (opt->validate && create_messenger(c) != 0)
        return -1;
    if (pick_device(c, opt) != 0)
        return -1;
    return create_device(c, opt);
}

int vkc_create(struct vkc *c, const struct vkc_options *opt)
{
    memset(c, 0, sizeof *c);
    struct stderr_capture cap;
    capture_begin(&cap);
    int rc = create_all(c, opt);
    capture_end(&cap);
    return rc;
}

void vkc_destroy(struct vkc *c)
{
    if (c->device) {
        vkDeviceWaitIdle(c->device);
        vkDestroyDevice(c->device, NULL);
    }
    if (c->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                c->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy)
            destroy(c->instance, c->messenger, NULL);
    }
    if (c->instance)
        vkDestroyInstance(c->instance, NULL);
    memset(c, 0, sizeof *c);
}

int vkc_memory_type(const struct vkc *c, uint32_t allowed,
                    VkMemoryPropertyFlags want, VkMemoryPropertyFlags prefer)
{
    int fallback = -1;
    for (uint32_t i = 0; i < c->memory.memoryTypeCount; i++) {
        VkMemoryPropertyFlags f = c->memory.memoryTypes[i].propertyFlags;
        if (!(allowed & (1u << i)) || (f & want) != want)
            continue;
        if ((f & prefer) == prefer)
            return (int)i;
        if (fallback < 0)
            fallback = (int)i;
    }
    return fallback;
}
