/*
 * vkc: the smallest Vulkan compute host that can run subcone's generated
 * SPIR-V: one device, one compute queue, host-visible buffers, one dispatch
 * at a time, waited on before the call returns. C99, no global state, no
 * layers or extensions.
 *
 * Every function that can fail returns 0 on success and nonzero on failure,
 * and then writes a one-line reason (naming the failing Vulkan call and its
 * VkResult where there is one) into `err` (at most `err_len` bytes, always
 * NUL-terminated; `err` may be NULL). Nothing aborts on bad input; whatever a
 * failing call created is released before it returns.
 *
 * A context must be used from one thread at a time (the queue and the command
 * pool are not internally synchronised).
 */
#ifndef VKC_H
#define VKC_H

#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

/* How long vkc_dispatch waits for its fence before giving up, in
 * nanoseconds: long enough for a software rasteriser on a large grid, short
 * enough that a hung device is reported rather than waited on forever.
 * Overridable with -D when compiling vkc's sources (vkc_submit.c waits; e.g.
 * to test the timeout path). */
#ifndef VKC_FENCE_TIMEOUT_NS
#define VKC_FENCE_TIMEOUT_NS (60ull * 1000ull * 1000ull * 1000ull)
#endif

typedef struct VkcContext VkcContext; /* opaque */

/* Creates an instance (API 1.1 when the loader has it, else 1.0), picks a
 * physical device with a compute queue (a discrete or integrated GPU before
 * any other kind, a CPU device last; the environment variable
 * VKC_DEVICE=<index into vkEnumeratePhysicalDevices> overrides the choice),
 * and creates a logical device, its first compute queue and a command pool.
 * On success *out owns all of them; on failure *out is NULL. */
int vkc_create(VkcContext **out, char *err, size_t err_len);

/* Waits for the device to go idle, then destroys everything the context
 * owns. Buffers must have been destroyed first. NULL is a no-op. */
void vkc_destroy(VkcContext *ctx);

/* VkPhysicalDeviceProperties::deviceName of the chosen device ("" for NULL). */
const char *vkc_device_name(const VkcContext *ctx);

/* Whether the chosen device is VK_PHYSICAL_DEVICE_TYPE_CPU (lavapipe,
 * SwiftShader), so a caller can tell a software run from a GPU one. */
int vkc_device_is_cpu(const VkcContext *ctx);

/* VkPhysicalDeviceLimits::standardSampleLocations: whether a multisampled
 * attachment's samples sit at the standard positions (for 4 samples,
 * (0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625, 0.875)). */
int vkc_standard_sample_locations(const VkcContext *ctx);

/* A buffer in host-visible, host-coherent memory, mapped for its lifetime:
 * the host writes inputs and reads outputs through `mapped` with no flushes
 * or copies. Usage: STORAGE_BUFFER | UNIFORM_BUFFER | TRANSFER_SRC |
 * TRANSFER_DST. */
typedef struct VkcBuffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
    VkDeviceSize size;
} VkcBuffer;

/* Creates a buffer of `size` bytes (nonzero). On failure *out is zeroed. */
int vkc_buffer_create(VkcContext *ctx, VkDeviceSize size, VkcBuffer *out, char *err, size_t err_len);

/* Unmaps and frees a buffer and zeroes *buf. A zeroed buffer or NULL is a
 * no-op, so it is safe on a buffer whose creation failed. vkc_dispatch waits
 * for its work, so no buffer is in use between calls (after a timeout this
 * waits for the device first). */
void vkc_buffer_destroy(VkcContext *ctx, VkcBuffer *buf);

/* A 2D image of `layers` layers, one mip level, one sample, in device
 * memory, with a view of all its layers (VK_IMAGE_VIEW_TYPE_2D_ARRAY when
 * created with `array_view`, else 2D). It stays in VK_IMAGE_LAYOUT_GENERAL,
 * where a shader may sample it, store to it and a copy may read or write it. */
typedef struct VkcImage {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    VkFormat format;
    uint32_t width;
    uint32_t height;
    uint32_t layers;
    VkDeviceSize texel_bytes;
    /* VK_SAMPLE_COUNT_1_BIT, or an attachment's count. */
    VkSampleCountFlagBits samples;
    /* VK_IMAGE_ASPECT_COLOR_BIT, or DEPTH for a depth attachment. */
    VkImageAspectFlags aspect;
} VkcImage;

/* Creates an image of `format` (`texel_bytes` bytes a texel), usable as a
 * sampled image, a storage image and a copy source and destination. On
 * failure *out is zeroed. */
int vkc_image_create(VkcContext *ctx, uint32_t width, uint32_t height, uint32_t layers, int array_view,
                     VkFormat format, VkDeviceSize texel_bytes, VkcImage *out, char *err, size_t err_len);

/* An image a draw renders into and a dispatch then samples: a colour
 * attachment, or a depth attachment when `format` is a depth format
 * (VK_FORMAT_D32_SFLOAT, ...), of `samples` samples (a multisampled image
 * is a texture_multisampled_2d / texture_depth_multisampled_2d to a
 * shader), one layer, in VK_IMAGE_LAYOUT_GENERAL. It cannot be copied
 * (vkc_image_copy refuses it): a shader reads it. On failure *out is
 * zeroed. */
int vkc_image_create_attachment(VkcContext *ctx, uint32_t width, uint32_t height, VkFormat format,
                                VkSampleCountFlagBits samples, VkcImage *out, char *err, size_t err_len);

/* Frees an image and zeroes *img; a zeroed image or NULL is a no-op. */
void vkc_image_destroy(VkcContext *ctx, VkcImage *img);

/* Copies `buffer` (texels tightly packed, row after row, layer after layer;
 * at least width·height·layers·texel_bytes bytes) into the image when
 * `to_image`, else the image into `buffer`, and waits. */
int vkc_image_copy(VkcContext *ctx, const VkcImage *img, const VkcBuffer *buffer, int to_image, char *err,
                   size_t err_len);

/* One descriptor of set 0: `type` is VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER or
 * VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bound over the whole of `buffer`, or
 * VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE or VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
 * bound to `image`'s view (in VK_IMAGE_LAYOUT_GENERAL). Only the member the
 * type names is read. */
typedef struct VkcBinding {
    uint32_t binding;
    VkDescriptorType type;
    const VkcBuffer *buffer;
    const VkcImage *image;
} VkcBinding;

/* Runs one compute dispatch and waits for it: builds descriptor set 0 from
 * `bindings` (binding numbers unique), a compute pipeline from the SPIR-V
 * words (`spirv_bytes` a nonzero multiple of 4) and the entry point `entry`,
 * records vkCmdDispatch(gx, gy, gz) followed by a barrier that makes shader
 * writes visible to the host and to later copies, submits, waits on a fence for at most
 * VKC_FENCE_TIMEOUT_NS, and destroys the pipeline objects. The group counts
 * must be within the device's maxComputeWorkGroupCount.
 *
 * If the wait times out, the objects the device may still be reading are
 * kept until vkc_destroy, every later vkc_dispatch on the context fails, and
 * vkc_buffer_destroy and vkc_destroy first wait for the device to go idle
 * (or be lost): destroy the buffers and the context. */
int vkc_dispatch(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, const char *entry,
                 const VkcBinding *bindings, uint32_t binding_count, uint32_t gx, uint32_t gy, uint32_t gz,
                 char *err, size_t err_len);

/* One draw: a raster pass of `vertex_count` vertices (no vertex buffer:
 * the vertex shader makes them from gl_VertexIndex; triangle list, no
 * culling) into `color` and `depth`, two attachments of one size and
 * sample count made by vkc_image_create_attachment, cleared to
 * `clear_color` and `clear_depth` first, depth tested with `depth_compare`
 * and written. `push` (`push_bytes`, a multiple of 4 up to 128) is the
 * vertex shader's push constants; both shaders' entry point is "main".
 * Afterwards both attachments are in VK_IMAGE_LAYOUT_GENERAL with their
 * writes visible to the next dispatch. The context's queue must support
 * graphics (vkc_create prefers such a queue). Waits as vkc_dispatch does. */
typedef struct VkcDraw {
    const uint32_t *vertex_spirv;
    size_t vertex_bytes;
    const uint32_t *fragment_spirv;
    size_t fragment_bytes;
    const void *push;
    uint32_t push_bytes;
    uint32_t vertex_count;
    const VkcImage *color;
    const VkcImage *depth;
    float clear_color[4];
    float clear_depth;
    VkCompareOp depth_compare;
} VkcDraw;

int vkc_draw(VkcContext *ctx, const VkcDraw *draw, char *err, size_t err_len);

/* Device time of the last successful vkc_dispatch in milliseconds, measured
 * with timestamp queries around the dispatch; negative when the queue has no
 * timestamp support, or before the first (and after a failed) dispatch. */
double vkc_last_dispatch_ms(const VkcContext *ctx);

/* Reads a whole file (a SPIR-V module) into malloc'd memory, to be released
 * with free(). Fails on an empty file or one whose size is not a multiple of
 * 4; on failure *words is NULL and *bytes 0. */
int vkc_read_file(const char *path, uint32_t **words, size_t *bytes, char *err, size_t err_len);

#endif /* VKC_H */
