/* One draw: the render pass, framebuffer and graphics pipeline of a raster
 * pass into two attachments. */
#include "vkc_internal.h"

#include <string.h>

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
        vkci_fail(err, err_len, "vkc_draw: the device's compute queue (family %u) has no graphics",
                  (unsigned)ctx->queue_family);
        return 1;
    }
    if (d->vertex_spirv == NULL || d->fragment_spirv == NULL || d->vertex_bytes == 0 || d->fragment_bytes == 0 ||
        d->vertex_bytes % 4 != 0 || d->fragment_bytes % 4 != 0 || d->vertex_spirv[0] != SPIRV_MAGIC ||
        d->fragment_spirv[0] != SPIRV_MAGIC) {
        vkci_fail(err, err_len, "vkc_draw: a shader is missing or not SPIR-V");
        return 1;
    }
    if (d->color == NULL || d->depth == NULL || d->color->image == VK_NULL_HANDLE ||
        d->depth->image == VK_NULL_HANDLE) {
        vkci_fail(err, err_len, "vkc_draw: a NULL or destroyed attachment");
        return 1;
    }
    if (d->color->aspect != VK_IMAGE_ASPECT_COLOR_BIT || d->depth->aspect != VK_IMAGE_ASPECT_DEPTH_BIT ||
        d->color->width != d->depth->width || d->color->height != d->depth->height ||
        d->color->samples != d->depth->samples) {
        vkci_fail(err, err_len,
                  "vkc_draw: the attachments are not a colour and a depth image of one size and sample count");
        return 1;
    }
    if (d->push_bytes % 4 != 0 || d->push_bytes > 128 || (d->push_bytes > 0 && d->push == NULL)) {
        vkci_fail(err, err_len, "vkc_draw: push constants of %u bytes (a multiple of 4, at most 128)",
                  (unsigned)d->push_bytes);
        return 1;
    }
    return 0;
}

/* The render pass of one subpass. Both attachments stay in GENERAL: loaded
 * by a clear, stored for the dispatch that samples them. On failure
 * o->render_pass stays VK_NULL_HANDLE. */
static int create_render_pass(VkcContext *ctx, const VkcDraw *d, DispatchObjects *o, char *err, size_t err_len) {
    VkAttachmentDescription att[2];
    VkAttachmentReference color_ref, depth_ref;
    VkSubpassDescription sub;
    VkSubpassDependency dep;
    VkRenderPassCreateInfo ci;
    VkResult r;
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
    r = vkCreateRenderPass(ctx->device, &ci, NULL, &o->render_pass);
    if (r != VK_SUCCESS) {
        o->render_pass = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateRenderPass", r);
        return 1;
    }
    return 0;
}

/* The framebuffer of the colour and depth attachments' views. On failure
 * o->framebuffer stays VK_NULL_HANDLE. */
static int create_framebuffer(VkcContext *ctx, const VkcDraw *d, DispatchObjects *o, char *err, size_t err_len) {
    VkImageView views[2];
    VkFramebufferCreateInfo ci;
    VkResult r;
    views[0] = d->color->view;
    views[1] = d->depth->view;
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    ci.renderPass = o->render_pass;
    ci.attachmentCount = 2;
    ci.pAttachments = views;
    ci.width = d->color->width;
    ci.height = d->color->height;
    ci.layers = 1;
    r = vkCreateFramebuffer(ctx->device, &ci, NULL, &o->framebuffer);
    if (r != VK_SUCCESS) {
        o->framebuffer = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateFramebuffer", r);
        return 1;
    }
    return 0;
}

/* The graphics pipeline's fixed-function state, which the create info
 * points into. */
typedef struct DrawStates {
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
} DrawStates;

/* Fills `s`: the two shader stages of `o`, a triangle list without vertex
 * input over the whole attachment, no culling, the depth test of the draw,
 * every colour channel written. */
static void fill_draw_states(const VkcDraw *d, const DispatchObjects *o, DrawStates *s) {
    memset(s->stages, 0, sizeof s->stages);
    for (int i = 0; i < 2; i++) {
        s->stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        s->stages[i].pName = "main";
    }
    s->stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    s->stages[0].module = o->module;
    s->stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    s->stages[1].module = o->fragment_module;
    memset(&s->vi, 0, sizeof s->vi);
    s->vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    memset(&s->ia, 0, sizeof s->ia);
    s->ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    s->ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    memset(&s->viewport, 0, sizeof s->viewport);
    s->viewport.width = (float)d->color->width;
    s->viewport.height = (float)d->color->height;
    s->viewport.maxDepth = 1.0f;
    memset(&s->scissor, 0, sizeof s->scissor);
    s->scissor.extent.width = d->color->width;
    s->scissor.extent.height = d->color->height;
    memset(&s->vp, 0, sizeof s->vp);
    s->vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    s->vp.viewportCount = 1;
    s->vp.pViewports = &s->viewport;
    s->vp.scissorCount = 1;
    s->vp.pScissors = &s->scissor;
    memset(&s->rs, 0, sizeof s->rs);
    s->rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    s->rs.polygonMode = VK_POLYGON_MODE_FILL;
    s->rs.cullMode = VK_CULL_MODE_NONE;
    s->rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    s->rs.lineWidth = 1.0f;
    memset(&s->ms, 0, sizeof s->ms);
    s->ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    s->ms.rasterizationSamples = d->color->samples;
    memset(&s->ds, 0, sizeof s->ds);
    s->ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    s->ds.depthTestEnable = VK_TRUE;
    s->ds.depthWriteEnable = VK_TRUE;
    s->ds.depthCompareOp = d->depth_compare;
    memset(&s->blend, 0, sizeof s->blend);
    s->blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                              VK_COLOR_COMPONENT_A_BIT;
    memset(&s->cb, 0, sizeof s->cb);
    s->cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    s->cb.attachmentCount = 1;
    s->cb.pAttachments = &s->blend;
}

/* The graphics pipeline of the draw's shaders in o's render pass and
 * layout. On failure o->pipeline stays VK_NULL_HANDLE. */
static int create_graphics_pipeline(VkcContext *ctx, const VkcDraw *d, DispatchObjects *o, char *err,
                                    size_t err_len) {
    DrawStates s;
    VkGraphicsPipelineCreateInfo ci;
    VkResult r;
    fill_draw_states(d, o, &s);
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    ci.stageCount = 2;
    ci.pStages = s.stages;
    ci.pVertexInputState = &s.vi;
    ci.pInputAssemblyState = &s.ia;
    ci.pViewportState = &s.vp;
    ci.pRasterizationState = &s.rs;
    ci.pMultisampleState = &s.ms;
    ci.pDepthStencilState = &s.ds;
    ci.pColorBlendState = &s.cb;
    ci.layout = o->pipeline_layout;
    ci.renderPass = o->render_pass;
    ci.basePipelineIndex = -1;
    r = vkCreateGraphicsPipelines(ctx->device, VK_NULL_HANDLE, 1, &ci, NULL, &o->pipeline);
    if (r != VK_SUCCESS) {
        o->pipeline = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateGraphicsPipelines", r);
        return 1;
    }
    return 0;
}

int vkc_draw(VkcContext *ctx, const VkcDraw *d, char *err, size_t err_len) {
    DispatchObjects o;
    int rc = 1;
    memset(&o, 0, sizeof o);
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (ctx == NULL || d == NULL) {
        vkci_fail(err, err_len, "vkc_draw: %s is NULL", ctx == NULL ? "ctx" : "draw");
        return 1;
    }
    if (check_draw_args(ctx, d, err, err_len) != 0) return 1;
    if (create_render_pass(ctx, d, &o, err, err_len) != 0) goto cleanup;
    if (create_framebuffer(ctx, d, &o, err, err_len) != 0) goto cleanup;
    if (vkci_pipeline_layout(ctx, VK_NULL_HANDLE, d->push_bytes, &o.pipeline_layout, err, err_len) != 0 ||
        vkci_shader_module(ctx, d->vertex_spirv, d->vertex_bytes, "vertex", &o.module, err, err_len) != 0 ||
        vkci_shader_module(ctx, d->fragment_spirv, d->fragment_bytes, "fragment", &o.fragment_module, err,
                           err_len) != 0)
        goto cleanup;
    if (create_graphics_pipeline(ctx, d, &o, err, err_len) != 0) goto cleanup;
    {
        DrawJob job;
        job.draw = d;
        job.pipeline = o.pipeline;
        job.layout = o.pipeline_layout;
        job.render_pass = o.render_pass;
        job.framebuffer = o.framebuffer;
        if (vkci_submit_and_wait(ctx, &o, record_draw, &job, "vkc_draw", err, err_len) != 0) goto cleanup;
    }
    rc = 0;
cleanup:
    vkci_release_objects(ctx, &o);
    return rc;
}
