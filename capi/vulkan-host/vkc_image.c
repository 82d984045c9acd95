/* Images, attachments, and copies between an image and a buffer. */
#include "vkc_internal.h"

#include <string.h>

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
        vkci_fail(err, err_len, "vkc_image_create: %s is NULL", out == NULL ? "out" : "ctx");
        return 1;
    }
    memset(out, 0, sizeof *out);
    if (width == 0 || height == 0 || layers == 0 || texel_bytes == 0) {
        vkci_fail(err, err_len, "vkc_image_create: a zero size (%ux%u, %u layers, %llu bytes a texel)", (unsigned)width,
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
        vkci_fail(err, err_len, "vkCreateImage (format %d, %ux%u, %u layers, %u samples) failed: %s (%d)", (int)format,
                  (unsigned)width, (unsigned)height, (unsigned)layers, (unsigned)samples, vkci_result_name(r), (int)r);
        goto fail;
    }
    vkGetImageMemoryRequirements(ctx->device, out->image, &req);
    type = vkci_find_memory_type(&ctx->memory, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = vkci_find_memory_type(&ctx->memory, req.memoryTypeBits, 0);
    if (type < 0) {
        vkci_fail(err, err_len, "no memory type for an image (memoryTypeBits 0x%x)", (unsigned)req.memoryTypeBits);
        goto fail;
    }
    memset(&mai, 0, sizeof mai);
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = (uint32_t)type;
    r = vkAllocateMemory(ctx->device, &mai, NULL, &out->memory);
    if (r != VK_SUCCESS) {
        out->memory = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkAllocateMemory (image)", r);
        goto fail;
    }
    r = vkBindImageMemory(ctx->device, out->image, out->memory, 0);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkBindImageMemory", r);
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
        vkci_fail_vk(err, err_len, "vkCreateImageView", r);
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
        rc = vkci_submit_and_wait(ctx, &o, record_to_general, out, "vkc_image_create", err, err_len);
        vkci_release_objects(ctx, &o);
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
        vkci_fail(err, err_len, "vkc_image_copy: a NULL or destroyed context, image or buffer");
        return 1;
    }
    if (img->samples != VK_SAMPLE_COUNT_1_BIT || img->aspect != VK_IMAGE_ASPECT_COLOR_BIT) {
        vkci_fail(err, err_len,
                  "vkc_image_copy: a multisampled or depth attachment cannot be copied; read it in a shader");
        return 1;
    }
    need = (VkDeviceSize)img->width * img->height * img->layers * img->texel_bytes;
    if (buffer->size < need) {
        vkci_fail(err, err_len, "vkc_image_copy: the buffer holds %llu bytes, the image %llu",
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
        rc = vkci_submit_and_wait(ctx, &o, record_copy, &job, "vkc_image_copy", err, err_len);
        vkci_release_objects(ctx, &o);
        return rc;
    }
}
