/* The instance, the physical and logical device, the queue, the command
 * pool and the timestamp queries: the context of vkc_create, and what it
 * tells about its device. */
#include "vkc_internal.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static const char *device_type_name(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

/* Lower is preferred: real GPUs first, a CPU implementation only when it is
 * all there is (it is correct but orders of magnitude slower). */
static int device_rank(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 2;
    default: return 1;
    }
}

/* The first queue family with compute, or -1. Any such family will do: one
 * dispatch at a time gains nothing from a dedicated compute queue. */
/* The first queue family with compute, preferring one that also has
 * graphics (vkc_draw's raster pass runs on the same queue). */
static int compute_family(VkPhysicalDevice pd, uint32_t *family, uint32_t *timestamp_bits, int *graphics) {
    VkQueueFamilyProperties *props;
    uint32_t n = 0, i;
    int found = -1;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
    if (n == 0) return -1;
    props = (VkQueueFamilyProperties *)malloc(n * sizeof *props);
    if (props == NULL) return -1;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, props);
    for (i = 0; i < n; i++) {
        const VkQueueFlags flags = props[i].queueFlags;
        if (!(flags & VK_QUEUE_COMPUTE_BIT) || props[i].queueCount == 0) continue;
        if (found == 0 && (*graphics || !(flags & VK_QUEUE_GRAPHICS_BIT))) continue;
        *family = i;
        *timestamp_bits = props[i].timestampValidBits;
        *graphics = (flags & VK_QUEUE_GRAPHICS_BIT) != 0;
        found = 0;
    }
    free(props);
    return found;
}

/* The instance API version to ask for: vkEnumerateInstanceVersion exists only
 * in 1.1 loaders, so it is looked up rather than linked. */
static uint32_t instance_api_version(void) {
    PFN_vkEnumerateInstanceVersion enumerate =
        (PFN_vkEnumerateInstanceVersion)vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion");
    uint32_t v = VK_API_VERSION_1_0;
    if (enumerate == NULL || enumerate(&v) != VK_SUCCESS) return VK_API_VERSION_1_0;
    if (VK_API_VERSION_MAJOR(v) > 1 || (VK_API_VERSION_MAJOR(v) == 1 && VK_API_VERSION_MINOR(v) >= 1))
        return VK_API_VERSION_1_1;
    return VK_API_VERSION_1_0;
}

/* Chooses the device per vkc_create's rules and fills ctx's physical device,
 * properties and queue family. */
static int pick_device(VkcContext *ctx, char *err, size_t err_len) {
    VkPhysicalDevice *devices = NULL;
    uint32_t n = 0, i, family = 0, bits = 0;
    int best = -1, best_rank = 0, rc = 1, graphics = 0;
    const char *override = getenv("VKC_DEVICE");
    VkResult r = vkEnumeratePhysicalDevices(ctx->instance, &n, NULL);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkEnumeratePhysicalDevices", r);
        return 1;
    }
    if (n == 0) {
        vkci_fail(err, err_len, "vkEnumeratePhysicalDevices found no Vulkan device (is a driver such as lavapipe "
                  "installed?)");
        return 1;
    }
    devices = (VkPhysicalDevice *)malloc(n * sizeof *devices);
    if (devices == NULL) {
        vkci_fail(err, err_len, "out of host memory listing %u devices", (unsigned)n);
        return 1;
    }
    r = vkEnumeratePhysicalDevices(ctx->instance, &n, devices);
    /* VK_INCOMPLETE only means a device appeared between the two calls; the
     * n written are still valid. */
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) {
        vkci_fail_vk(err, err_len, "vkEnumeratePhysicalDevices", r);
        goto done;
    }

    if (override != NULL && override[0] != '\0') {
        char *end = NULL;
        unsigned long index;
        errno = 0;
        index = strtoul(override, &end, 10);
        if (errno != 0 || end == override || *end != '\0' || override[0] == '-' || index >= n) {
            vkci_fail(err, err_len, "VKC_DEVICE=%s is not a device index (0..%u)", override, (unsigned)(n - 1));
            goto done;
        }
        vkGetPhysicalDeviceProperties(devices[index], &ctx->properties);
        if (compute_family(devices[index], &family, &bits, &graphics) != 0) {
            vkci_fail(err, err_len, "VKC_DEVICE=%lu (%s, %s) has no compute queue", index, ctx->properties.deviceName,
                      device_type_name(ctx->properties.deviceType));
            goto done;
        }
        best = (int)index;
    } else {
        for (i = 0; i < n; i++) {
            VkPhysicalDeviceProperties p;
            uint32_t f, b;
            int rank, g = 0;
            if (compute_family(devices[i], &f, &b, &g) != 0) continue;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            rank = device_rank(p.deviceType);
            if (best < 0 || rank < best_rank) {
                best = (int)i;
                best_rank = rank;
                family = f;
                bits = b;
                graphics = g;
            }
        }
        if (best < 0) {
            vkci_fail(err, err_len, "none of the %u Vulkan devices has a compute queue", (unsigned)n);
            goto done;
        }
        vkGetPhysicalDeviceProperties(devices[best], &ctx->properties);
    }
    ctx->physical = devices[best];
    ctx->queue_family = family;
    ctx->graphics = graphics;
    ctx->timestamp_bits = bits;
    vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->memory);
    rc = 0;
done:
    free(devices);
    return rc;
}

int vkc_create(VkcContext **out, char *err, size_t err_len) {
    VkcContext *ctx;
    VkResult r;
    VkApplicationInfo app;
    VkInstanceCreateInfo ici;
    VkDeviceQueueCreateInfo qci;
    VkDeviceCreateInfo dci;
    VkCommandPoolCreateInfo pci;
    float priority = 1.0f;

    if (err != NULL && err_len > 0) err[0] = '\0';
    if (out == NULL) {
        vkci_fail(err, err_len, "vkc_create: out is NULL");
        return 1;
    }
    *out = NULL;
    ctx = (VkcContext *)calloc(1, sizeof *ctx);
    if (ctx == NULL) {
        vkci_fail(err, err_len, "vkc_create: out of host memory");
        return 1;
    }
    ctx->last_ms = -1.0;

    memset(&app, 0, sizeof app);
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "subcone vulkan-host";
    app.pEngineName = "subcone";
    app.apiVersion = instance_api_version();
    memset(&ici, 0, sizeof ici);
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pApplicationInfo = &app;
    r = vkCreateInstance(&ici, NULL, &ctx->instance);
    if (r != VK_SUCCESS) {
        /* A failed vkCreateInstance leaves the handle undefined. */
        ctx->instance = VK_NULL_HANDLE;
        /* The loader's answer when it finds no driver at all, which is what
         * a user needs to hear. */
        if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
            vkci_fail(err, err_len, "vkCreateInstance failed: %s (%d): no usable Vulkan driver (ICD) was found",
                      vkci_result_name(r), (int)r);
        else
            vkci_fail_vk(err, err_len, "vkCreateInstance", r);
        goto fail;
    }

    if (pick_device(ctx, err, err_len) != 0) goto fail;

    memset(&qci, 0, sizeof qci);
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = ctx->queue_family;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    memset(&dci, 0, sizeof dci);
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    r = vkCreateDevice(ctx->physical, &dci, NULL, &ctx->device);
    if (r != VK_SUCCESS) {
        ctx->device = VK_NULL_HANDLE;
        vkci_fail(err, err_len, "vkCreateDevice failed on %s (%s): %s (%d)", ctx->properties.deviceName,
                  device_type_name(ctx->properties.deviceType), vkci_result_name(r), (int)r);
        goto fail;
    }
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);

    memset(&pci, 0, sizeof pci);
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    /* Each dispatch records one short-lived buffer and frees it. */
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = ctx->queue_family;
    r = vkCreateCommandPool(ctx->device, &pci, NULL, &ctx->pool);
    if (r != VK_SUCCESS) {
        ctx->pool = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateCommandPool", r);
        goto fail;
    }

    if (ctx->timestamp_bits > 0) {
        VkQueryPoolCreateInfo qp;
        memset(&qp, 0, sizeof qp);
        qp.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        qp.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qp.queryCount = 2;
        r = vkCreateQueryPool(ctx->device, &qp, NULL, &ctx->timestamps);
        if (r != VK_SUCCESS) {
            ctx->timestamps = VK_NULL_HANDLE;
            vkci_fail_vk(err, err_len, "vkCreateQueryPool", r);
            goto fail;
        }
    }

    *out = ctx;
    return 0;
fail:
    vkc_destroy(ctx);
    return 1;
}

void vkc_destroy(VkcContext *ctx) {
    if (ctx == NULL) return;
    if (ctx->device != VK_NULL_HANDLE) {
        /* vkDestroyDevice requires all submitted work to be complete; the
         * result is ignored because there is nothing left to do on failure
         * (a lost device is idle by definition). */
        (void)vkDeviceWaitIdle(ctx->device);
        vkci_release_objects(ctx, &ctx->pending);
        vkDestroyQueryPool(ctx->device, ctx->timestamps, NULL);
        vkDestroyCommandPool(ctx->device, ctx->pool, NULL);
        vkDestroyDevice(ctx->device, NULL);
    }
    if (ctx->instance != VK_NULL_HANDLE) vkDestroyInstance(ctx->instance, NULL);
    free(ctx);
}

const char *vkc_device_name(const VkcContext *ctx) {
    return ctx == NULL ? "" : ctx->properties.deviceName;
}

int vkc_standard_sample_locations(const VkcContext *ctx) {
    return ctx != NULL && ctx->properties.limits.standardSampleLocations == VK_TRUE;
}

int vkc_device_is_cpu(const VkcContext *ctx) {
    return ctx != NULL && ctx->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}
