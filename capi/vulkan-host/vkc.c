/* vkc: see vkc.h. Every object a call creates is released on its own error
 * path through a single cleanup label, so a failure leaves nothing behind. */
#include "vkc.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Headers before 1.2.175 have only the (now deprecated) VK_VERSION_* forms. */
#ifndef VK_API_VERSION_MAJOR
#define VK_API_VERSION_MAJOR(v) VK_VERSION_MAJOR(v)
#define VK_API_VERSION_MINOR(v) VK_VERSION_MINOR(v)
#endif

#define SPIRV_MAGIC 0x07230203u

/* What one dispatch creates and destroys. Every handle starts as
 * VK_NULL_HANDLE, which the destroy calls accept. */
typedef struct DispatchObjects {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout pipeline_layout;
    VkShaderModule module;
    /* A draw's fragment shader, render pass and framebuffer. */
    VkShaderModule fragment_module;
    VkRenderPass render_pass;
    VkFramebuffer framebuffer;
    VkPipeline pipeline;
    VkDescriptorPool descriptor_pool;
    VkCommandBuffer cmd;
    VkFence fence;
} DispatchObjects;

struct VkcContext {
    VkInstance instance;
    VkPhysicalDevice physical;
    VkPhysicalDeviceProperties properties;
    VkPhysicalDeviceMemoryProperties memory;
    VkDevice device;
    uint32_t queue_family;
    /* Whether the queue family supports graphics (vkc_draw needs it). */
    int graphics;
    VkQueue queue;
    VkCommandPool pool;
    /* Two timestamps around the dispatch; VK_NULL_HANDLE when the queue
     * family reports timestampValidBits == 0. */
    VkQueryPool timestamps;
    uint32_t timestamp_bits;
    double last_ms;
    /* Set when a fence wait timed out: the device may still be running the
     * dispatch whose objects are parked in `pending`, so no further
     * submission is made, and buffers and the context wait for the device
     * before they are freed. */
    int wedged;
    DispatchObjects pending;
};

static void release_objects(VkcContext *ctx, DispatchObjects *o) {
    vkDestroyFence(ctx->device, o->fence, NULL);
    if (o->cmd != VK_NULL_HANDLE) vkFreeCommandBuffers(ctx->device, ctx->pool, 1, &o->cmd);
    vkDestroyDescriptorPool(ctx->device, o->descriptor_pool, NULL);
    vkDestroyPipeline(ctx->device, o->pipeline, NULL);
    vkDestroyShaderModule(ctx->device, o->module, NULL);
    vkDestroyShaderModule(ctx->device, o->fragment_module, NULL);
    vkDestroyFramebuffer(ctx->device, o->framebuffer, NULL);
    vkDestroyRenderPass(ctx->device, o->render_pass, NULL);
    vkDestroyPipelineLayout(ctx->device, o->pipeline_layout, NULL);
    vkDestroyDescriptorSetLayout(ctx->device, o->set_layout, NULL);
    memset(o, 0, sizeof *o);
}

/* Writes a formatted one-line reason into err, tolerating a NULL or empty
 * buffer so callers never have to check before reporting. */
static void fail(char *err, size_t err_len, const char *fmt, ...) {
    va_list ap;
    if (err == NULL || err_len == 0) return;
    va_start(ap, fmt);
    vsnprintf(err, err_len, fmt, ap);
    va_end(ap);
}

/* The enumerant's name, so a message can be searched for in the spec. */
static const char *result_name(VkResult r) {
    switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_EVENT_SET: return "VK_EVENT_SET";
    case VK_EVENT_RESET: return "VK_EVENT_RESET";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    case VK_ERROR_FRAGMENTED_POOL: return "VK_ERROR_FRAGMENTED_POOL";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
    case VK_ERROR_INVALID_EXTERNAL_HANDLE: return "VK_ERROR_INVALID_EXTERNAL_HANDLE";
    case VK_ERROR_INVALID_SHADER_NV: return "VK_ERROR_INVALID_SHADER_NV";
    default: return "VkResult";
    }
}

/* "vkFoo failed: VK_ERROR_BAR (-n)" in one place, so every message has the
 * same shape. */
static void fail_vk(char *err, size_t err_len, const char *call, VkResult r) {
    fail(err, err_len, "%s failed: %s (%d)", call, result_name(r), (int)r);
}

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
        fail_vk(err, err_len, "vkEnumeratePhysicalDevices", r);
        return 1;
    }
    if (n == 0) {
        fail(err, err_len, "vkEnumeratePhysicalDevices found no Vulkan device (is a driver such as lavapipe "
             "installed?)");
        return 1;
    }
    devices = (VkPhysicalDevice *)malloc(n * sizeof *devices);
    if (devices == NULL) {
        fail(err, err_len, "out of host memory listing %u devices", (unsigned)n);
        return 1;
    }
    r = vkEnumeratePhysicalDevices(ctx->instance, &n, devices);
    /* VK_INCOMPLETE only means a device appeared between the two calls; the
     * n written are still valid. */
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) {
        fail_vk(err, err_len, "vkEnumeratePhysicalDevices", r);
        goto done;
    }

    if (override != NULL && override[0] != '\0') {
        char *end = NULL;
        unsigned long index;
        errno = 0;
        index = strtoul(override, &end, 10);
        if (errno != 0 || end == override || *end != '\0' || override[0] == '-' || index >= n) {
            fail(err, err_len, "VKC_DEVICE=%s is not a device index (0..%u)", override, (unsigned)(n - 1));
            goto done;
        }
        vkGetPhysicalDeviceProperties(devices[index], &ctx->properties);
        if (compute_family(devices[index], &family, &bits, &graphics) != 0) {
            fail(err, err_len, "VKC_DEVICE=%lu (%s, %s) has no compute queue", index, ctx->properties.deviceName,
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
            fail(err, err_len, "none of the %u Vulkan devices has a compute queue", (unsigned)n);
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
        fail(err, err_len, "vkc_create: out is NULL");
        return 1;
    }
    *out = NULL;
    ctx = (VkcContext *)calloc(1, sizeof *ctx);
    if (ctx == NULL) {
        fail(err, err_len, "vkc_create: out of host memory");
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
            fail(err, err_len, "vkCreateInstance failed: %s (%d): no usable Vulkan driver (ICD) was found",
                 result_name(r), (int)r);
        else
            fail_vk(err, err_len, "vkCreateInstance", r);
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
        fail(err, err_len, "vkCreateDevice failed on %s (%s): %s (%d)", ctx->properties.deviceName,
             device_type_name(ctx->properties.deviceType), result_name(r), (int)r);
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
        fail_vk(err, err_len, "vkCreateCommandPool", r);
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
            fail_vk(err, err_len, "vkCreateQueryPool", r);
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
        release_objects(ctx, &ctx->pending);
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

double vkc_last_dispatch_ms(const VkcContext *ctx) {
    return ctx == NULL ? -1.0 : ctx->last_ms;
}

/* The first memory type allowed by `type_bits` that has all of `flags`, or -1.
 * Memory types are listed in the driver's order of preference, so the first
 * match is the one to take. */
static int find_memory_type(const VkPhysicalDeviceMemoryProperties *mem, uint32_t type_bits,
                            VkMemoryPropertyFlags flags) {
    uint32_t i;
    for (i = 0; i < mem->memoryTypeCount; i++) {
        if ((type_bits & (1u << i)) && (mem->memoryTypes[i].propertyFlags & flags) == flags) return (int)i;
    }
    return -1;
}

int vkc_buffer_create(VkcContext *ctx, VkDeviceSize size, VkcBuffer *out, char *err, size_t err_len) {
    VkBufferCreateInfo bci;
    VkMemoryRequirements req;
    VkMemoryAllocateInfo mai;
    VkResult r;
    int type;

    if (err != NULL && err_len > 0) err[0] = '\0';
    if (out == NULL) {
        fail(err, err_len, "vkc_buffer_create: out is NULL");
        return 1;
    }
    memset(out, 0, sizeof *out);
    if (ctx == NULL) {
        fail(err, err_len, "vkc_buffer_create: ctx is NULL");
        return 1;
    }
    if (size == 0) {
        fail(err, err_len, "vkc_buffer_create: size is 0 (Vulkan buffers must be nonzero)");
        return 1;
    }

    memset(&bci, 0, sizeof bci);
    bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bci.size = size;
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    r = vkCreateBuffer(ctx->device, &bci, NULL, &out->buffer);
    if (r != VK_SUCCESS) {
        out->buffer = VK_NULL_HANDLE;
        fail(err, err_len, "vkCreateBuffer (%llu bytes) failed: %s (%d)", (unsigned long long)size,
             result_name(r), (int)r);
        goto fail;
    }
    vkGetBufferMemoryRequirements(ctx->device, out->buffer, &req);
    type = find_memory_type(&ctx->memory, req.memoryTypeBits,
                            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (type < 0) {
        fail(err, err_len, "no host-visible, host-coherent memory type for a buffer (memoryTypeBits 0x%x)",
             (unsigned)req.memoryTypeBits);
        goto fail;
    }
    memset(&mai, 0, sizeof mai);
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = (uint32_t)type;
    r = vkAllocateMemory(ctx->device, &mai, NULL, &out->memory);
    if (r != VK_SUCCESS) {
        out->memory = VK_NULL_HANDLE;
        fail(err, err_len, "vkAllocateMemory (%llu bytes) failed: %s (%d)", (unsigned long long)req.size,
             result_name(r), (int)r);
        goto fail;
    }
    r = vkBindBufferMemory(ctx->device, out->buffer, out->memory, 0);
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkBindBufferMemory", r);
        goto fail;
    }
    r = vkMapMemory(ctx->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped);
    if (r != VK_SUCCESS) {
        out->mapped = NULL;
        fail_vk(err, err_len, "vkMapMemory", r);
        goto fail;
    }
    out->size = size;
    return 0;
fail:
    vkc_buffer_destroy(ctx, out);
    return 1;
}

void vkc_buffer_destroy(VkcContext *ctx, VkcBuffer *buf) {
    if (ctx == NULL || buf == NULL) return;
    /* After a timed-out dispatch the device may still be using any buffer.
     * The result is ignored: a lost device is idle. */
    if (ctx->wedged && ctx->device != VK_NULL_HANDLE) (void)vkDeviceWaitIdle(ctx->device);
    if (buf->mapped != NULL) vkUnmapMemory(ctx->device, buf->memory);
    vkDestroyBuffer(ctx->device, buf->buffer, NULL);
    vkFreeMemory(ctx->device, buf->memory, NULL);
    memset(buf, 0, sizeof *buf);
}

/* Rejects what a driver is not required to diagnose (and may crash on):
 * malformed SPIR-V headers, bad descriptor types, duplicate or oversized
 * bindings, out-of-range group counts. */
static int check_dispatch_args(const VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, const char *entry,
                               const VkcBinding *bindings, uint32_t binding_count, const uint32_t groups[3],
                               char *err, size_t err_len) {
    const VkPhysicalDeviceLimits *lim = &ctx->properties.limits;
    uint32_t i, j;
    if (spirv == NULL || entry == NULL || (bindings == NULL && binding_count > 0)) {
        fail(err, err_len, "vkc_dispatch: spirv, entry or bindings is NULL");
        return 1;
    }
    /* Five words is the SPIR-V header alone. */
    if (spirv_bytes < 20 || spirv_bytes % 4 != 0) {
        fail(err, err_len, "vkc_dispatch: SPIR-V size %lu is not a multiple of 4 of at least 20 bytes",
             (unsigned long)spirv_bytes);
        return 1;
    }
    if (spirv[0] != SPIRV_MAGIC) {
        fail(err, err_len, "vkc_dispatch: not SPIR-V (first word 0x%08x, expected 0x%08x%s)", (unsigned)spirv[0],
             SPIRV_MAGIC, spirv[0] == 0x03022307u ? ", the module is byte-swapped" : "");
        return 1;
    }
    for (i = 0; i < 3; i++) {
        if (groups[i] > lim->maxComputeWorkGroupCount[i]) {
            fail(err, err_len, "vkc_dispatch: group count %u in dimension %u exceeds maxComputeWorkGroupCount %u",
                 (unsigned)groups[i], (unsigned)i, (unsigned)lim->maxComputeWorkGroupCount[i]);
            return 1;
        }
    }
    for (i = 0; i < binding_count; i++) {
        const VkcBinding *b = &bindings[i];
        VkDeviceSize range_limit;
        for (j = 0; j < i; j++) {
            if (bindings[j].binding == b->binding) {
                fail(err, err_len, "vkc_dispatch: binding %u appears twice", (unsigned)b->binding);
                return 1;
            }
        }
        if (b->type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE || b->type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
            if (b->image == NULL || b->image->view == VK_NULL_HANDLE) {
                fail(err, err_len, "vkc_dispatch: binding %u has no image", (unsigned)b->binding);
                return 1;
            }
            continue;
        }
        if (b->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
            range_limit = lim->maxUniformBufferRange;
        } else if (b->type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            range_limit = lim->maxStorageBufferRange;
        } else {
            fail(err, err_len, "vkc_dispatch: binding %u has descriptor type %d (only UNIFORM_BUFFER, "
                 "STORAGE_BUFFER, SAMPLED_IMAGE and STORAGE_IMAGE are supported)", (unsigned)b->binding,
                 (int)b->type);
            return 1;
        }
        if (b->buffer == NULL || b->buffer->buffer == VK_NULL_HANDLE || b->buffer->size == 0) {
            fail(err, err_len, "vkc_dispatch: binding %u has no buffer", (unsigned)b->binding);
            return 1;
        }
        /* The descriptor covers the whole buffer, which the device caps. */
        if (b->buffer->size > range_limit) {
            fail(err, err_len, "vkc_dispatch: binding %u is %llu bytes, over the device's %s range of %llu",
                 (unsigned)b->binding, (unsigned long long)b->buffer->size,
                 b->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ? "uniform" : "storage",
                 (unsigned long long)range_limit);
            return 1;
        }
    }
    return 0;
}

/* Records `record(cmd, user)` into a one-time command buffer (o->cmd),
 * submits it with a fence (o->fence) and waits for at most
 * VKC_FENCE_TIMEOUT_NS. The caller releases `o` (release_objects) either
 * way: on a timeout the device may still be using everything in `o`, so it
 * is parked in the context for vkc_destroy (which waits for the device),
 * `o` is zeroed, and the context is wedged: no later submission. */
static int submit_and_wait(VkcContext *ctx, DispatchObjects *o, void (*record)(VkCommandBuffer, const void *),
                           const void *user, const char *what, char *err, size_t err_len) {
    VkCommandBufferAllocateInfo ai;
    VkCommandBufferBeginInfo bi;
    VkFenceCreateInfo fi;
    VkSubmitInfo si;
    VkResult r;

    if (ctx->wedged) {
        fail(err, err_len, "%s: an earlier submission timed out; destroy the context", what);
        return 1;
    }
    memset(&ai, 0, sizeof ai);
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = ctx->pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    r = vkAllocateCommandBuffers(ctx->device, &ai, &o->cmd);
    if (r != VK_SUCCESS) {
        o->cmd = VK_NULL_HANDLE;
        fail_vk(err, err_len, "vkAllocateCommandBuffers", r);
        return 1;
    }
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    r = vkBeginCommandBuffer(o->cmd, &bi);
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkBeginCommandBuffer", r);
        return 1;
    }
    record(o->cmd, user);
    r = vkEndCommandBuffer(o->cmd);
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkEndCommandBuffer", r);
        return 1;
    }
    memset(&fi, 0, sizeof fi);
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    r = vkCreateFence(ctx->device, &fi, NULL, &o->fence);
    if (r != VK_SUCCESS) {
        o->fence = VK_NULL_HANDLE;
        fail_vk(err, err_len, "vkCreateFence", r);
        return 1;
    }
    /* Host writes to coherent memory made before this call are visible to
     * the device without a barrier: vkQueueSubmit guarantees it. */
    memset(&si, 0, sizeof si);
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &o->cmd;
    r = vkQueueSubmit(ctx->queue, 1, &si, o->fence);
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkQueueSubmit", r);
        return 1;
    }
    r = vkWaitForFences(ctx->device, 1, &o->fence, VK_TRUE, VKC_FENCE_TIMEOUT_NS);
    if (r == VK_TIMEOUT) {
        ctx->wedged = 1;
        ctx->pending = *o;
        memset(o, 0, sizeof *o);
        fail(err, err_len, "%s: vkWaitForFences timed out after %llu s (VK_TIMEOUT); the context is unusable",
             what, (unsigned long long)(VKC_FENCE_TIMEOUT_NS / 1000000000ull));
        return 1;
    }
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkWaitForFences", r);
        return 1;
    }
    return 0;
}

/* What the dispatch's command buffer binds and runs. */
typedef struct DispatchJob {
    const VkcContext *ctx;
    VkPipeline pipeline;
    VkPipelineLayout layout;
    VkDescriptorSet set;
    uint32_t groups[3];
} DispatchJob;

static void record_dispatch(VkCommandBuffer cmd, const void *user) {
    const DispatchJob *job = (const DispatchJob *)user;
    VkMemoryBarrier to_host;
    /* Queries must be reset before each use; doing it in the command
     * buffer avoids needing 1.2's host reset. */
    if (job->ctx->timestamps != VK_NULL_HANDLE) {
        vkCmdResetQueryPool(cmd, job->ctx->timestamps, 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, job->ctx->timestamps, 0);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, job->pipeline);
    if (job->set != VK_NULL_HANDLE)
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, job->layout, 0, 1, &job->set, 0, NULL);
    vkCmdDispatch(cmd, job->groups[0], job->groups[1], job->groups[2]);
    if (job->ctx->timestamps != VK_NULL_HANDLE)
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, job->ctx->timestamps, 1);
    /* A signalled fence does not by itself make device writes visible to
     * the host, even in coherent memory; this barrier does (and to later
     * copies). */
    memset(&to_host, 0, sizeof to_host);
    to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &to_host, 0, NULL, 0,
                         NULL);
}

/* A shader module of `bytes` bytes of SPIR-V (`what` names it in errors).
 * On failure *out stays VK_NULL_HANDLE. */
static int shader_module(VkcContext *ctx, const uint32_t *words, size_t bytes, const char *what,
                         VkShaderModule *out, char *err, size_t err_len) {
    VkShaderModuleCreateInfo ci;
    VkResult r;
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    ci.codeSize = bytes;
    ci.pCode = words;
    r = vkCreateShaderModule(ctx->device, &ci, NULL, out);
    if (r != VK_SUCCESS) {
        *out = VK_NULL_HANDLE;
        fail(err, err_len, "vkCreateShaderModule (%s) failed: %s (%d)", what, result_name(r), (int)r);
        return 1;
    }
    return 0;
}

/* A pipeline layout of one descriptor set layout (or none, for
 * VK_NULL_HANDLE) and `push_bytes` bytes of vertex push constants (0 for
 * none). On failure *out stays VK_NULL_HANDLE. */
static int pipeline_layout(VkcContext *ctx, VkDescriptorSetLayout set_layout, uint32_t push_bytes,
                           VkPipelineLayout *out, char *err, size_t err_len) {
    VkPushConstantRange range;
    VkPipelineLayoutCreateInfo ci;
    VkResult r;
    range.stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
    range.offset = 0;
    range.size = push_bytes;
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    ci.setLayoutCount = set_layout != VK_NULL_HANDLE ? 1 : 0;
    ci.pSetLayouts = &set_layout;
    ci.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    ci.pPushConstantRanges = &range;
    r = vkCreatePipelineLayout(ctx->device, &ci, NULL, out);
    if (r != VK_SUCCESS) {
        *out = VK_NULL_HANDLE;
        fail_vk(err, err_len, "vkCreatePipelineLayout", r);
        return 1;
    }
    return 0;
}

int vkc_dispatch(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, const char *entry,
                 const VkcBinding *bindings, uint32_t binding_count, uint32_t gx, uint32_t gy, uint32_t gz,
                 char *err, size_t err_len) {
    const uint32_t groups[3] = {gx, gy, gz};
    VkDescriptorSetLayoutBinding *layout_bindings = NULL;
    VkDescriptorBufferInfo *buffer_infos = NULL;
    VkWriteDescriptorSet *writes = NULL;
    DispatchObjects o;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkDescriptorImageInfo *image_infos = NULL;
    uint32_t uniform_count = 0, storage_count = 0, sampled_count = 0, storage_image_count = 0, i;
    double elapsed_ms = -1.0;
    int rc = 1;
    VkResult r;

    memset(&o, 0, sizeof o);
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (ctx == NULL) {
        fail(err, err_len, "vkc_dispatch: ctx is NULL");
        return 1;
    }
    ctx->last_ms = -1.0;
    if (ctx->wedged) {
        fail(err, err_len, "vkc_dispatch: an earlier dispatch timed out; destroy the context");
        return 1;
    }
    if (check_dispatch_args(ctx, spirv, spirv_bytes, entry, bindings, binding_count, groups, err, err_len) != 0)
        return 1;

    if (binding_count > 0) {
        layout_bindings = (VkDescriptorSetLayoutBinding *)calloc(binding_count, sizeof *layout_bindings);
        buffer_infos = (VkDescriptorBufferInfo *)calloc(binding_count, sizeof *buffer_infos);
        image_infos = (VkDescriptorImageInfo *)calloc(binding_count, sizeof *image_infos);
        writes = (VkWriteDescriptorSet *)calloc(binding_count, sizeof *writes);
        if (layout_bindings == NULL || buffer_infos == NULL || image_infos == NULL || writes == NULL) {
            fail(err, err_len, "vkc_dispatch: out of host memory for %u bindings", (unsigned)binding_count);
            goto cleanup;
        }
    }
    for (i = 0; i < binding_count; i++) {
        layout_bindings[i].binding = bindings[i].binding;
        layout_bindings[i].descriptorType = bindings[i].type;
        layout_bindings[i].descriptorCount = 1;
        layout_bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        if (bindings[i].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
            uniform_count++;
        else if (bindings[i].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
            storage_count++;
        else if (bindings[i].type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE)
            sampled_count++;
        else
            storage_image_count++;
    }

    {
        VkDescriptorSetLayoutCreateInfo ci;
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        ci.bindingCount = binding_count;
        ci.pBindings = layout_bindings;
        r = vkCreateDescriptorSetLayout(ctx->device, &ci, NULL, &o.set_layout);
        if (r != VK_SUCCESS) {
            o.set_layout = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkCreateDescriptorSetLayout", r);
            goto cleanup;
        }
    }
    if (pipeline_layout(ctx, o.set_layout, 0, &o.pipeline_layout, err, err_len) != 0) goto cleanup;
    if (shader_module(ctx, spirv, spirv_bytes, "compute", &o.module, err, err_len) != 0) goto cleanup;
    {
        VkComputePipelineCreateInfo ci;
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
        ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = o.module;
        ci.stage.pName = entry;
        ci.layout = o.pipeline_layout;
        ci.basePipelineIndex = -1;
        r = vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &ci, NULL, &o.pipeline);
        if (r != VK_SUCCESS) {
            o.pipeline = VK_NULL_HANDLE;
            fail(err, err_len, "vkCreateComputePipelines (entry point \"%s\") failed: %s (%d)", entry,
                 result_name(r), (int)r);
            goto cleanup;
        }
    }

    /* A pool needs a nonzero descriptorCount per size entry, so an empty set
     * gets no pool and is simply not bound. */
    if (binding_count > 0) {
        VkDescriptorPoolSize sizes[4];
        VkDescriptorPoolCreateInfo ci;
        VkDescriptorSetAllocateInfo ai;
        uint32_t size_count = 0;
        if (uniform_count > 0) {
            sizes[size_count].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            sizes[size_count].descriptorCount = uniform_count;
            size_count++;
        }
        if (storage_count > 0) {
            sizes[size_count].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            sizes[size_count].descriptorCount = storage_count;
            size_count++;
        }
        if (sampled_count > 0) {
            sizes[size_count].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
            sizes[size_count].descriptorCount = sampled_count;
            size_count++;
        }
        if (storage_image_count > 0) {
            sizes[size_count].type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            sizes[size_count].descriptorCount = storage_image_count;
            size_count++;
        }
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        ci.maxSets = 1;
        ci.poolSizeCount = size_count;
        ci.pPoolSizes = sizes;
        r = vkCreateDescriptorPool(ctx->device, &ci, NULL, &o.descriptor_pool);
        if (r != VK_SUCCESS) {
            o.descriptor_pool = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkCreateDescriptorPool", r);
            goto cleanup;
        }
        memset(&ai, 0, sizeof ai);
        ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
        ai.descriptorPool = o.descriptor_pool;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &o.set_layout;
        r = vkAllocateDescriptorSets(ctx->device, &ai, &set);
        if (r != VK_SUCCESS) {
            set = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkAllocateDescriptorSets", r);
            goto cleanup;
        }
        for (i = 0; i < binding_count; i++) {
            writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            writes[i].dstSet = set;
            writes[i].dstBinding = bindings[i].binding;
            writes[i].descriptorCount = 1;
            writes[i].descriptorType = bindings[i].type;
            /* `image` is read only for image types: a caller that binds a
             * buffer need not set it. */
            if (bindings[i].type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE ||
                bindings[i].type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
                image_infos[i].imageView = bindings[i].image->view;
                image_infos[i].imageLayout = VK_IMAGE_LAYOUT_GENERAL;
                writes[i].pImageInfo = &image_infos[i];
            } else {
                buffer_infos[i].buffer = bindings[i].buffer->buffer;
                buffer_infos[i].offset = 0;
                buffer_infos[i].range = VK_WHOLE_SIZE;
                writes[i].pBufferInfo = &buffer_infos[i];
            }
        }
        vkUpdateDescriptorSets(ctx->device, binding_count, writes, 0, NULL);
    }

    {
        DispatchJob job;
        job.ctx = ctx;
        job.pipeline = o.pipeline;
        job.layout = o.pipeline_layout;
        job.set = set;
        memcpy(job.groups, groups, sizeof job.groups);
        if (submit_and_wait(ctx, &o, record_dispatch, &job, "vkc_dispatch", err, err_len) != 0) goto cleanup;
    }

    if (ctx->timestamps != VK_NULL_HANDLE) {
        uint64_t ticks[2];
        uint64_t delta;
        r = vkGetQueryPoolResults(ctx->device, ctx->timestamps, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
        if (r != VK_SUCCESS) {
            fail_vk(err, err_len, "vkGetQueryPoolResults", r);
            goto cleanup;
        }
        delta = ticks[1] - ticks[0];
        /* Only the low timestampValidBits count; masking the difference
         * survives one wrap of the counter. */
        if (ctx->timestamp_bits < 64) delta &= (1ull << ctx->timestamp_bits) - 1ull;
        elapsed_ms = (double)delta * (double)ctx->properties.limits.timestampPeriod / 1.0e6;
    }
    ctx->last_ms = elapsed_ms;
    rc = 0;

cleanup:
    release_objects(ctx, &o);
    free(layout_bindings);
    free(buffer_infos);
    free(image_infos);
    free(writes);
    return rc;
}

static VkImageSubresourceRange all_layers(VkImageAspectFlags aspect, uint32_t layers) {
    VkImageSubresourceRange range;
    memset(&range, 0, sizeof range);
    range.aspectMask = aspect;
    range.levelCount = 1;
    range.layerCount = layers;
    return range;
}

/* UNDEFINED to GENERAL, once, after creation. */
static void record_to_general(VkCommandBuffer cmd, const void *user) {
    const VkcImage *img = (const VkcImage *)user;
    VkImageMemoryBarrier b;
    memset(&b, 0, sizeof b);
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                      VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img->image;
    b.subresourceRange = all_layers(img->aspect, img->layers);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 0, NULL,
                         1, &b);
}

/* The image of vkc_image_create (one sample, a colour aspect) and of
 * vkc_image_create_attachment. */
static int image_create(VkcContext *ctx, uint32_t width, uint32_t height, uint32_t layers, int array_view,
                        VkFormat format, VkDeviceSize texel_bytes, VkSampleCountFlagBits samples,
                        VkImageUsageFlags usage, VkImageAspectFlags aspect, VkcImage *out, char *err,
                        size_t err_len) {
    VkImageCreateInfo ici;
    VkImageViewCreateInfo vci;
    VkMemoryRequirements req;
    VkMemoryAllocateInfo mai;
    VkResult r;
    int type;

    if (err != NULL && err_len > 0) err[0] = '\0';
    if (out == NULL || ctx == NULL) {
        fail(err, err_len, "vkc_image_create: %s is NULL", out == NULL ? "out" : "ctx");
        return 1;
    }
    memset(out, 0, sizeof *out);
    if (width == 0 || height == 0 || layers == 0 || texel_bytes == 0) {
        fail(err, err_len, "vkc_image_create: a zero size (%ux%u, %u layers, %llu bytes a texel)", (unsigned)width,
             (unsigned)height, (unsigned)layers, (unsigned long long)texel_bytes);
        return 1;
    }
    memset(&ici, 0, sizeof ici);
    ici.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = format;
    ici.extent.width = width;
    ici.extent.height = height;
    ici.extent.depth = 1;
    ici.mipLevels = 1;
    ici.arrayLayers = layers;
    ici.samples = samples;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    r = vkCreateImage(ctx->device, &ici, NULL, &out->image);
    if (r != VK_SUCCESS) {
        out->image = VK_NULL_HANDLE;
        fail(err, err_len, "vkCreateImage (format %d, %ux%u, %u layers, %u samples) failed: %s (%d)", (int)format,
             (unsigned)width, (unsigned)height, (unsigned)layers, (unsigned)samples, result_name(r), (int)r);
        goto fail;
    }
    vkGetImageMemoryRequirements(ctx->device, out->image, &req);
    type = find_memory_type(&ctx->memory, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = find_memory_type(&ctx->memory, req.memoryTypeBits, 0);
    if (type < 0) {
        fail(err, err_len, "no memory type for an image (memoryTypeBits 0x%x)", (unsigned)req.memoryTypeBits);
        goto fail;
    }
    memset(&mai, 0, sizeof mai);
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = (uint32_t)type;
    r = vkAllocateMemory(ctx->device, &mai, NULL, &out->memory);
    if (r != VK_SUCCESS) {
        out->memory = VK_NULL_HANDLE;
        fail_vk(err, err_len, "vkAllocateMemory (image)", r);
        goto fail;
    }
    r = vkBindImageMemory(ctx->device, out->image, out->memory, 0);
    if (r != VK_SUCCESS) {
        fail_vk(err, err_len, "vkBindImageMemory", r);
        goto fail;
    }
    memset(&vci, 0, sizeof vci);
    vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vci.image = out->image;
    vci.viewType = array_view ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = all_layers(aspect, layers);
    r = vkCreateImageView(ctx->device, &vci, NULL, &out->view);
    if (r != VK_SUCCESS) {
        out->view = VK_NULL_HANDLE;
        fail_vk(err, err_len, "vkCreateImageView", r);
        goto fail;
    }
    out->format = format;
    out->width = width;
    out->height = height;
    out->layers = layers;
    out->texel_bytes = texel_bytes;
    out->samples = samples;
    out->aspect = aspect;
    {
        DispatchObjects o;
        int rc;
        memset(&o, 0, sizeof o);
        rc = submit_and_wait(ctx, &o, record_to_general, out, "vkc_image_create", err, err_len);
        release_objects(ctx, &o);
        if (rc != 0) goto fail;
    }
    return 0;
fail:
    vkc_image_destroy(ctx, out);
    return 1;
}

int vkc_image_create(VkcContext *ctx, uint32_t width, uint32_t height, uint32_t layers, int array_view,
                     VkFormat format, VkDeviceSize texel_bytes, VkcImage *out, char *err, size_t err_len) {
    return image_create(ctx, width, height, layers, array_view, format, texel_bytes, VK_SAMPLE_COUNT_1_BIT,
                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                            VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT, out, err, err_len);
}

static int is_depth_format(VkFormat format) {
    return format == VK_FORMAT_D16_UNORM || format == VK_FORMAT_X8_D24_UNORM_PACK32 || format == VK_FORMAT_D32_SFLOAT;
}

int vkc_image_create_attachment(VkcContext *ctx, uint32_t width, uint32_t height, VkFormat format,
                                VkSampleCountFlagBits samples, VkcImage *out, char *err, size_t err_len) {
    const int depth = is_depth_format(format);
    /* texel_bytes only sizes copies, which an attachment refuses. */
    return image_create(ctx, width, height, 1, 0, format, 1, samples,
                        VK_IMAGE_USAGE_SAMPLED_BIT | (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                            : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT),
                        depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, out, err, err_len);
}

void vkc_image_destroy(VkcContext *ctx, VkcImage *img) {
    if (ctx == NULL || img == NULL) return;
    if (ctx->wedged && ctx->device != VK_NULL_HANDLE) (void)vkDeviceWaitIdle(ctx->device);
    vkDestroyImageView(ctx->device, img->view, NULL);
    vkDestroyImage(ctx->device, img->image, NULL);
    vkFreeMemory(ctx->device, img->memory, NULL);
    memset(img, 0, sizeof *img);
}

typedef struct CopyJob {
    const VkcImage *img;
    const VkcBuffer *buffer;
    int to_image;
} CopyJob;

/* Earlier writes (a dispatch, a copy) before the copy; the copy's writes
 * before what follows (a dispatch reads the image, the host the buffer). */
static void record_copy(VkCommandBuffer cmd, const void *user) {
    const CopyJob *job = (const CopyJob *)user;
    VkMemoryBarrier before, after;
    VkBufferImageCopy region;
    memset(&before, 0, sizeof before);
    before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_WRITE_BIT;
    before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                             VK_PIPELINE_STAGE_HOST_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, NULL, 0, NULL);
    memset(&region, 0, sizeof region);
    region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    region.imageSubresource.layerCount = job->img->layers;
    region.imageExtent.width = job->img->width;
    region.imageExtent.height = job->img->height;
    region.imageExtent.depth = 1;
    if (job->to_image)
        vkCmdCopyBufferToImage(cmd, job->buffer->buffer, job->img->image, VK_IMAGE_LAYOUT_GENERAL, 1, &region);
    else
        vkCmdCopyImageToBuffer(cmd, job->img->image, VK_IMAGE_LAYOUT_GENERAL, job->buffer->buffer, 1, &region);
    memset(&after, 0, sizeof after);
    after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0, NULL, 0,
                         NULL);
}

int vkc_image_copy(VkcContext *ctx, const VkcImage *img, const VkcBuffer *buffer, int to_image, char *err,
                   size_t err_len) {
    CopyJob job;
    VkDeviceSize need;
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (ctx == NULL || img == NULL || buffer == NULL || img->image == VK_NULL_HANDLE ||
        buffer->buffer == VK_NULL_HANDLE) {
        fail(err, err_len, "vkc_image_copy: a NULL or destroyed context, image or buffer");
        return 1;
    }
    if (img->samples != VK_SAMPLE_COUNT_1_BIT || img->aspect != VK_IMAGE_ASPECT_COLOR_BIT) {
        fail(err, err_len, "vkc_image_copy: a multisampled or depth attachment cannot be copied; read it in a shader");
        return 1;
    }
    need = (VkDeviceSize)img->width * img->height * img->layers * img->texel_bytes;
    if (buffer->size < need) {
        fail(err, err_len, "vkc_image_copy: the buffer holds %llu bytes, the image %llu",
             (unsigned long long)buffer->size, (unsigned long long)need);
        return 1;
    }
    job.img = img;
    job.buffer = buffer;
    job.to_image = to_image;
    {
        DispatchObjects o;
        int rc;
        memset(&o, 0, sizeof o);
        rc = submit_and_wait(ctx, &o, record_copy, &job, "vkc_image_copy", err, err_len);
        release_objects(ctx, &o);
        return rc;
    }
}

int vkc_read_file(const char *path, uint32_t **words, size_t *bytes, char *err, size_t err_len) {
    FILE *f;
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;

    if (err != NULL && err_len > 0) err[0] = '\0';
    if (words == NULL || bytes == NULL) {
        fail(err, err_len, "vkc_read_file: words or bytes is NULL");
        return 1;
    }
    *words = NULL;
    *bytes = 0;
    if (path == NULL) {
        fail(err, err_len, "vkc_read_file: path is NULL");
        return 1;
    }
    f = fopen(path, "rb");
    if (f == NULL) {
        fail(err, err_len, "cannot open %s: %s", path, strerror(errno));
        return 1;
    }
    /* Read in growing chunks rather than trusting fseek/ftell, which fail on
     * pipes and overflow long on 32-bit hosts. */
    for (;;) {
        size_t got;
        if (len == cap) {
            size_t next = cap == 0 ? 65536 : cap * 2;
            unsigned char *grown;
            if (next < cap) {
                fail(err, err_len, "%s is too large", path);
                goto fail;
            }
            grown = (unsigned char *)realloc(data, next);
            if (grown == NULL) {
                fail(err, err_len, "out of host memory reading %s", path);
                goto fail;
            }
            data = grown;
            cap = next;
        }
        got = fread(data + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        fail(err, err_len, "error reading %s", path);
        goto fail;
    }
    if (len == 0) {
        fail(err, err_len, "%s is empty", path);
        goto fail;
    }
    if (len % 4 != 0) {
        fail(err, err_len, "%s is %lu bytes, not a whole number of 32-bit SPIR-V words", path, (unsigned long)len);
        goto fail;
    }
    fclose(f);
    /* malloc'd memory is aligned for any object type, so the bytes may be
     * read as words. */
    *words = (uint32_t *)(void *)data;
    *bytes = len;
    return 0;
fail:
    fclose(f);
    free(data);
    return 1;
}

typedef struct DrawJob {
    const VkcDraw *draw;
    VkPipeline pipeline;
    VkPipelineLayout layout;
    VkRenderPass render_pass;
    VkFramebuffer framebuffer;
} DrawJob;

static void record_draw(VkCommandBuffer cmd, const void *user) {
    const DrawJob *job = (const DrawJob *)user;
    const VkcDraw *d = job->draw;
    VkRenderPassBeginInfo bi;
    VkClearValue clears[2];
    VkMemoryBarrier after;
    memset(clears, 0, sizeof clears);
    memcpy(clears[0].color.float32, d->clear_color, sizeof d->clear_color);
    clears[1].depthStencil.depth = d->clear_depth;
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    bi.renderPass = job->render_pass;
    bi.framebuffer = job->framebuffer;
    bi.renderArea.extent.width = d->color->width;
    bi.renderArea.extent.height = d->color->height;
    bi.clearValueCount = 2;
    bi.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, job->pipeline);
    if (d->push_bytes > 0)
        vkCmdPushConstants(cmd, job->layout, VK_SHADER_STAGE_VERTEX_BIT, 0, d->push_bytes, d->push);
    vkCmdDraw(cmd, d->vertex_count, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    /* The attachments' writes before the next dispatch samples them. */
    memset(&after, 0, sizeof after);
    after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    after.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    after.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(cmd,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                             VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &after, 0, NULL, 0, NULL);
}

static int check_draw_args(const VkcContext *ctx, const VkcDraw *d, char *err, size_t err_len) {
    if (!ctx->graphics) {
        fail(err, err_len, "vkc_draw: the device's compute queue (family %u) has no graphics",
             (unsigned)ctx->queue_family);
        return 1;
    }
    if (d->vertex_spirv == NULL || d->fragment_spirv == NULL || d->vertex_bytes == 0 || d->fragment_bytes == 0 ||
        d->vertex_bytes % 4 != 0 || d->fragment_bytes % 4 != 0 || d->vertex_spirv[0] != SPIRV_MAGIC ||
        d->fragment_spirv[0] != SPIRV_MAGIC) {
        fail(err, err_len, "vkc_draw: a shader is missing or not SPIR-V");
        return 1;
    }
    if (d->color == NULL || d->depth == NULL || d->color->image == VK_NULL_HANDLE ||
        d->depth->image == VK_NULL_HANDLE) {
        fail(err, err_len, "vkc_draw: a NULL or destroyed attachment");
        return 1;
    }
    if (d->color->aspect != VK_IMAGE_ASPECT_COLOR_BIT || d->depth->aspect != VK_IMAGE_ASPECT_DEPTH_BIT ||
        d->color->width != d->depth->width || d->color->height != d->depth->height ||
        d->color->samples != d->depth->samples) {
        fail(err, err_len, "vkc_draw: the attachments are not a colour and a depth image of one size and sample count");
        return 1;
    }
    if (d->push_bytes % 4 != 0 || d->push_bytes > 128 || (d->push_bytes > 0 && d->push == NULL)) {
        fail(err, err_len, "vkc_draw: push constants of %u bytes (a multiple of 4, at most 128)",
             (unsigned)d->push_bytes);
        return 1;
    }
    return 0;
}

int vkc_draw(VkcContext *ctx, const VkcDraw *d, char *err, size_t err_len) {
    DispatchObjects o;
    VkResult r;
    int rc = 1;
    memset(&o, 0, sizeof o);
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (ctx == NULL || d == NULL) {
        fail(err, err_len, "vkc_draw: %s is NULL", ctx == NULL ? "ctx" : "draw");
        return 1;
    }
    if (check_draw_args(ctx, d, err, err_len) != 0) return 1;
    {
        /* Both attachments stay in GENERAL: loaded by a clear, stored for
         * the dispatch that samples them. */
        VkAttachmentDescription att[2];
        VkAttachmentReference color_ref, depth_ref;
        VkSubpassDescription sub;
        VkSubpassDependency dep;
        VkRenderPassCreateInfo ci;
        memset(att, 0, sizeof att);
        att[0].format = d->color->format;
        att[1].format = d->depth->format;
        for (int i = 0; i < 2; i++) {
            att[i].samples = d->color->samples;
            att[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            att[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            att[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            att[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            att[i].initialLayout = VK_IMAGE_LAYOUT_GENERAL;
            att[i].finalLayout = VK_IMAGE_LAYOUT_GENERAL;
        }
        color_ref.attachment = 0;
        color_ref.layout = VK_IMAGE_LAYOUT_GENERAL;
        depth_ref.attachment = 1;
        depth_ref.layout = VK_IMAGE_LAYOUT_GENERAL;
        memset(&sub, 0, sizeof sub);
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &color_ref;
        sub.pDepthStencilAttachment = &depth_ref;
        /* Earlier shader reads and transfers of the images (an earlier
         * dispatch sampled them) before the clear writes them. */
        memset(&dep, 0, sizeof dep);
        dep.srcSubpass = VK_SUBPASS_EXTERNAL;
        dep.dstSubpass = 0;
        dep.srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
        dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
        dep.srcAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
        ci.attachmentCount = 2;
        ci.pAttachments = att;
        ci.subpassCount = 1;
        ci.pSubpasses = &sub;
        ci.dependencyCount = 1;
        ci.pDependencies = &dep;
        r = vkCreateRenderPass(ctx->device, &ci, NULL, &o.render_pass);
        if (r != VK_SUCCESS) {
            o.render_pass = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkCreateRenderPass", r);
            goto cleanup;
        }
    }
    {
        VkImageView views[2];
        VkFramebufferCreateInfo ci;
        views[0] = d->color->view;
        views[1] = d->depth->view;
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        ci.renderPass = o.render_pass;
        ci.attachmentCount = 2;
        ci.pAttachments = views;
        ci.width = d->color->width;
        ci.height = d->color->height;
        ci.layers = 1;
        r = vkCreateFramebuffer(ctx->device, &ci, NULL, &o.framebuffer);
        if (r != VK_SUCCESS) {
            o.framebuffer = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkCreateFramebuffer", r);
            goto cleanup;
        }
    }
    if (pipeline_layout(ctx, VK_NULL_HANDLE, d->push_bytes, &o.pipeline_layout, err, err_len) != 0 ||
        shader_module(ctx, d->vertex_spirv, d->vertex_bytes, "vertex", &o.module, err, err_len) != 0 ||
        shader_module(ctx, d->fragment_spirv, d->fragment_bytes, "fragment", &o.fragment_module, err, err_len) != 0)
        goto cleanup;
    {
        VkPipelineShaderStageCreateInfo stages[2];
        VkPipelineVertexInputStateCreateInfo vi;
        VkPipelineInputAssemblyStateCreateInfo ia;
        VkViewport viewport;
        VkRect2D scissor;
        VkPipelineViewportStateCreateInfo vp;
        VkPipelineRasterizationStateCreateInfo rs;
        VkPipelineMultisampleStateCreateInfo ms;
        VkPipelineDepthStencilStateCreateInfo ds;
        VkPipelineColorBlendAttachmentState blend;
        VkPipelineColorBlendStateCreateInfo cb;
        VkGraphicsPipelineCreateInfo ci;
        memset(stages, 0, sizeof stages);
        for (int i = 0; i < 2; i++) {
            stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
            stages[i].pName = "main";
        }
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = o.module;
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = o.fragment_module;
        memset(&vi, 0, sizeof vi);
        vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
        memset(&ia, 0, sizeof ia);
        ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
        ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        memset(&viewport, 0, sizeof viewport);
        viewport.width = (float)d->color->width;
        viewport.height = (float)d->color->height;
        viewport.maxDepth = 1.0f;
        memset(&scissor, 0, sizeof scissor);
        scissor.extent.width = d->color->width;
        scissor.extent.height = d->color->height;
        memset(&vp, 0, sizeof vp);
        vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
        vp.viewportCount = 1;
        vp.pViewports = &viewport;
        vp.scissorCount = 1;
        vp.pScissors = &scissor;
        memset(&rs, 0, sizeof rs);
        rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
        rs.polygonMode = VK_POLYGON_MODE_FILL;
        rs.cullMode = VK_CULL_MODE_NONE;
        rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        rs.lineWidth = 1.0f;
        memset(&ms, 0, sizeof ms);
        ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
        ms.rasterizationSamples = d->color->samples;
        memset(&ds, 0, sizeof ds);
        ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
        ds.depthTestEnable = VK_TRUE;
        ds.depthWriteEnable = VK_TRUE;
        ds.depthCompareOp = d->depth_compare;
        memset(&blend, 0, sizeof blend);
        blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                               VK_COLOR_COMPONENT_A_BIT;
        memset(&cb, 0, sizeof cb);
        cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
        cb.attachmentCount = 1;
        cb.pAttachments = &blend;
        memset(&ci, 0, sizeof ci);
        ci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
        ci.stageCount = 2;
        ci.pStages = stages;
        ci.pVertexInputState = &vi;
        ci.pInputAssemblyState = &ia;
        ci.pViewportState = &vp;
        ci.pRasterizationState = &rs;
        ci.pMultisampleState = &ms;
        ci.pDepthStencilState = &ds;
        ci.pColorBlendState = &cb;
        ci.layout = o.pipeline_layout;
        ci.renderPass = o.render_pass;
        ci.basePipelineIndex = -1;
        r = vkCreateGraphicsPipelines(ctx->device, VK_NULL_HANDLE, 1, &ci, NULL, &o.pipeline);
        if (r != VK_SUCCESS) {
            o.pipeline = VK_NULL_HANDLE;
            fail_vk(err, err_len, "vkCreateGraphicsPipelines", r);
            goto cleanup;
        }
    }
    {
        DrawJob job;
        job.draw = d;
        job.pipeline = o.pipeline;
        job.layout = o.pipeline_layout;
        job.render_pass = o.render_pass;
        job.framebuffer = o.framebuffer;
        if (submit_and_wait(ctx, &o, record_draw, &job, "vkc_draw", err, err_len) != 0) goto cleanup;
    }
    rc = 0;
cleanup:
    release_objects(ctx, &o);
    return rc;
}
