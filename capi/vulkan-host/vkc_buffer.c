/* Host-visible buffers, and the memory type search images share. */
#include "vkc_internal.h"

#include <string.h>

int vkci_find_memory_type(const VkPhysicalDeviceMemoryProperties *mem, uint32_t type_bits,
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
        vkci_fail(err, err_len, "vkc_buffer_create: out is NULL");
        return 1;
    }
    memset(out, 0, sizeof *out);
    if (ctx == NULL) {
        vkci_fail(err, err_len, "vkc_buffer_create: ctx is NULL");
        return 1;
    }
    if (size == 0) {
        vkci_fail(err, err_len, "vkc_buffer_create: size is 0 (Vulkan buffers must be nonzero)");
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
        vkci_fail(err, err_len, "vkCreateBuffer (%llu bytes) failed: %s (%d)", (unsigned long long)size,
                  vkci_result_name(r), (int)r);
        goto fail;
    }
    vkGetBufferMemoryRequirements(ctx->device, out->buffer, &req);
    type = vkci_find_memory_type(&ctx->memory, req.memoryTypeBits,
                                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (type < 0) {
        vkci_fail(err, err_len, "no host-visible, host-coherent memory type for a buffer (memoryTypeBits 0x%x)",
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
        vkci_fail(err, err_len, "vkAllocateMemory (%llu bytes) failed: %s (%d)", (unsigned long long)req.size,
                  vkci_result_name(r), (int)r);
        goto fail;
    }
    r = vkBindBufferMemory(ctx->device, out->buffer, out->memory, 0);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkBindBufferMemory", r);
        goto fail;
    }
    r = vkMapMemory(ctx->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped);
    if (r != VK_SUCCESS) {
        out->mapped = NULL;
        vkci_fail_vk(err, err_len, "vkMapMemory", r);
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
