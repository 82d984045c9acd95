/* What vkc's source files share (vkc.h is the API): the context's layout,
 * the objects one dispatch or draw creates, and the helpers more than one
 * file calls, named vkci_ so that they cannot collide with a program's
 * names. Not part of the API.
 *
 * Every object a call creates is released on its own error path through a
 * single cleanup label, so a failure leaves nothing behind.
 *
 * The files, by concern: vkc_error.c (the error messages), vkc_device.c
 * (instance, device, queue, the context), vkc_buffer.c (buffers and memory
 * types), vkc_image.c (images, attachments, copies), vkc_pipeline.c (shader
 * modules, pipeline layouts), vkc_submit.c (command buffers, fences, the
 * timeout), vkc_dispatch.c (descriptor sets, the compute pipeline, timing),
 * vkc_draw.c (the raster pass), vkc_file.c (reading SPIR-V). */
#ifndef VKC_INTERNAL_H
#define VKC_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "vkc.h"

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

/* vkc_error.c */

/* Writes a formatted one-line reason into err, tolerating a NULL or empty
 * buffer so callers never have to check before reporting. */
void vkci_fail(char *err, size_t err_len, const char *fmt, ...);

/* The enumerant's name, so a message can be searched for in the spec. */
const char *vkci_result_name(VkResult r);

/* "vkFoo failed: VK_ERROR_BAR (-n)" in one place, so every message has the
 * same shape. */
void vkci_fail_vk(char *err, size_t err_len, const char *call, VkResult r);

/* vkc_buffer.c */

/* The first memory type allowed by `type_bits` that has all of `flags`, or -1.
 * Memory types are listed in the driver's order of preference, so the first
 * match is the one to take. */
int vkci_find_memory_type(const VkPhysicalDeviceMemoryProperties *mem, uint32_t type_bits, VkMemoryPropertyFlags flags);

/* vkc_pipeline.c */

/* A shader module of `bytes` bytes of SPIR-V (`what` names it in errors).
 * On failure *out stays VK_NULL_HANDLE. */
int vkci_shader_module(VkcContext *ctx, const uint32_t *words, size_t bytes, const char *what,
                       VkShaderModule *out, char *err, size_t err_len);

/* A pipeline layout of one descriptor set layout (or none, for
 * VK_NULL_HANDLE) and `push_bytes` bytes of vertex push constants (0 for
 * none). On failure *out stays VK_NULL_HANDLE. */
int vkci_pipeline_layout(VkcContext *ctx, VkDescriptorSetLayout set_layout, uint32_t push_bytes,
                         VkPipelineLayout *out, char *err, size_t err_len);

/* vkc_submit.c */

/* Destroys every object in `o` (VK_NULL_HANDLE ones are skipped by the
 * destroy calls) and zeroes it. */
void vkci_release_objects(VkcContext *ctx, DispatchObjects *o);

/* Records `record(cmd, user)` into a one-time command buffer (o->cmd),
 * submits it with a fence (o->fence) and waits for at most
 * VKC_FENCE_TIMEOUT_NS. The caller releases `o` (vkci_release_objects) either
 * way: on a timeout the device may still be using everything in `o`, so it
 * is parked in the context for vkc_destroy (which waits for the device),
 * `o` is zeroed, and the context is wedged: no later submission. */
int vkci_submit_and_wait(VkcContext *ctx, DispatchObjects *o, void (*record)(VkCommandBuffer, const void *),
                         const void *user, const char *what, char *err, size_t err_len);

#endif /* VKC_INTERNAL_H */
