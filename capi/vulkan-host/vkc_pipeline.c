/* The pipeline pieces a dispatch and a draw share: shader modules and
 * pipeline layouts. */
#include "vkc_internal.h"

#include <string.h>

int vkci_shader_module(VkcContext *ctx, const uint32_t *words, size_t bytes, const char *what,
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
        vkci_fail(err, err_len, "vkCreateShaderModule (%s) failed: %s (%d)", what, vkci_result_name(r), (int)r);
        return 1;
    }
    return 0;
}

int vkci_pipeline_layout(VkcContext *ctx, VkDescriptorSetLayout set_layout, uint32_t push_bytes,
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
        vkci_fail_vk(err, err_len, "vkCreatePipelineLayout", r);
        return 1;
    }
    return 0;
}
