/* Command submission: one command buffer and fence per call, waited on for
 * at most VKC_FENCE_TIMEOUT_NS, and the release of what a call created. */
#include "vkc_internal.h"

#include <string.h>

void vkci_release_objects(VkcContext *ctx, DispatchObjects *o) {
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

int vkci_submit_and_wait(VkcContext *ctx, DispatchObjects *o, void (*record)(VkCommandBuffer, const void *),
                         const void *user, const char *what, char *err, size_t err_len) {
    VkCommandBufferAllocateInfo ai;
    VkCommandBufferBeginInfo bi;
    VkFenceCreateInfo fi;
    VkSubmitInfo si;
    VkResult r;

    if (ctx->wedged) {
        vkci_fail(err, err_len, "%s: an earlier submission timed out; destroy the context", what);
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
        vkci_fail_vk(err, err_len, "vkAllocateCommandBuffers", r);
        return 1;
    }
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    r = vkBeginCommandBuffer(o->cmd, &bi);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkBeginCommandBuffer", r);
        return 1;
    }
    record(o->cmd, user);
    r = vkEndCommandBuffer(o->cmd);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkEndCommandBuffer", r);
        return 1;
    }
    memset(&fi, 0, sizeof fi);
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    r = vkCreateFence(ctx->device, &fi, NULL, &o->fence);
    if (r != VK_SUCCESS) {
        o->fence = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateFence", r);
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
        vkci_fail_vk(err, err_len, "vkQueueSubmit", r);
        return 1;
    }
    r = vkWaitForFences(ctx->device, 1, &o->fence, VK_TRUE, VKC_FENCE_TIMEOUT_NS);
    if (r == VK_TIMEOUT) {
        ctx->wedged = 1;
        ctx->pending = *o;
        memset(o, 0, sizeof *o);
        vkci_fail(err, err_len, "%s: vkWaitForFences timed out after %llu s (VK_TIMEOUT); the context is unusable",
                  what, (unsigned long long)(VKC_FENCE_TIMEOUT_NS / 1000000000ull));
        return 1;
    }
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkWaitForFences", r);
        return 1;
    }
    return 0;
}
