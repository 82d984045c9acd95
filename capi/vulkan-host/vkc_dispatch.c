/* One compute dispatch: its checks, descriptor set, compute pipeline and
 * command buffer, and its device time from the timestamp queries. */
#include "vkc_internal.h"

#include <stdlib.h>
#include <string.h>

/* Rejects what a driver is not required to diagnose (and may crash on):
 * malformed SPIR-V headers, bad descriptor types, duplicate or oversized
 * bindings, out-of-range group counts. */
static int check_dispatch_args(const VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, const char *entry,
                               const VkcBinding *bindings, uint32_t binding_count, const uint32_t groups[3],
                               char *err, size_t err_len) {
    const VkPhysicalDeviceLimits *lim = &ctx->properties.limits;
    uint32_t i, j;
    if (spirv == NULL || entry == NULL || (bindings == NULL && binding_count > 0)) {
        vkci_fail(err, err_len, "vkc_dispatch: spirv, entry or bindings is NULL");
        return 1;
    }
    /* Five words is the SPIR-V header alone. */
    if (spirv_bytes < 20 || spirv_bytes % 4 != 0) {
        vkci_fail(err, err_len, "vkc_dispatch: SPIR-V size %lu is not a multiple of 4 of at least 20 bytes",
                  (unsigned long)spirv_bytes);
        return 1;
    }
    if (spirv[0] != SPIRV_MAGIC) {
        vkci_fail(err, err_len, "vkc_dispatch: not SPIR-V (first word 0x%08x, expected 0x%08x%s)", (unsigned)spirv[0],
                  SPIRV_MAGIC, spirv[0] == 0x03022307u ? ", the module is byte-swapped" : "");
        return 1;
    }
    for (i = 0; i < 3; i++) {
        if (groups[i] > lim->maxComputeWorkGroupCount[i]) {
            vkci_fail(err, err_len, "vkc_dispatch: group count %u in dimension %u exceeds maxComputeWorkGroupCount %u",
                      (unsigned)groups[i], (unsigned)i, (unsigned)lim->maxComputeWorkGroupCount[i]);
            return 1;
        }
    }
    for (i = 0; i < binding_count; i++) {
        const VkcBinding *b = &bindings[i];
        VkDeviceSize range_limit;
        for (j = 0; j < i; j++) {
            if (bindings[j].binding == b->binding) {
                vkci_fail(err, err_len, "vkc_dispatch: binding %u appears twice", (unsigned)b->binding);
                return 1;
            }
        }
        if (b->type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE || b->type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
            if (b->image == NULL || b->image->view == VK_NULL_HANDLE) {
                vkci_fail(err, err_len, "vkc_dispatch: binding %u has no image", (unsigned)b->binding);
                return 1;
            }
            continue;
        }
        if (b->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
            range_limit = lim->maxUniformBufferRange;
        } else if (b->type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            range_limit = lim->maxStorageBufferRange;
        } else {
            vkci_fail(err, err_len, "vkc_dispatch: binding %u has descriptor type %d (only UNIFORM_BUFFER, "
                      "STORAGE_BUFFER, SAMPLED_IMAGE and STORAGE_IMAGE are supported)", (unsigned)b->binding,
                      (int)b->type);
            return 1;
        }
        if (b->buffer == NULL || b->buffer->buffer == VK_NULL_HANDLE || b->buffer->size == 0) {
            vkci_fail(err, err_len, "vkc_dispatch: binding %u has no buffer", (unsigned)b->binding);
            return 1;
        }
        /* The descriptor covers the whole buffer, which the device caps. */
        if (b->buffer->size > range_limit) {
            vkci_fail(err, err_len, "vkc_dispatch: binding %u is %llu bytes, over the device's %s range of %llu",
                      (unsigned)b->binding, (unsigned long long)b->buffer->size,
                      b->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ? "uniform" : "storage",
                      (unsigned long long)range_limit);
            return 1;
        }
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

/* The host-side arrays one dispatch's descriptors are built from, one entry
 * per binding, and how many descriptors of each type the pool needs. */
typedef struct DispatchScratch {
    VkDescriptorSetLayoutBinding *layout_bindings;
    VkDescriptorBufferInfo *buffer_infos;
    VkDescriptorImageInfo *image_infos;
    VkWriteDescriptorSet *writes;
    uint32_t uniform_count, storage_count, sampled_count, storage_image_count;
} DispatchScratch;

/* Frees the scratch arrays (NULL ones too). */
static void free_scratch(DispatchScratch *s) {
    free(s->layout_bindings);
    free(s->buffer_infos);
    free(s->image_infos);
    free(s->writes);
}

/* Allocates the scratch arrays and fills the layout bindings and the
 * per-type counts; on failure the caller still frees what was allocated. */
static int prepare_bindings(const VkcBinding *bindings, uint32_t binding_count, DispatchScratch *s, char *err,
                            size_t err_len) {
    uint32_t i;
    if (binding_count > 0) {
        s->layout_bindings = (VkDescriptorSetLayoutBinding *)calloc(binding_count, sizeof *s->layout_bindings);
        s->buffer_infos = (VkDescriptorBufferInfo *)calloc(binding_count, sizeof *s->buffer_infos);
        s->image_infos = (VkDescriptorImageInfo *)calloc(binding_count, sizeof *s->image_infos);
        s->writes = (VkWriteDescriptorSet *)calloc(binding_count, sizeof *s->writes);
        if (s->layout_bindings == NULL || s->buffer_infos == NULL || s->image_infos == NULL || s->writes == NULL) {
            vkci_fail(err, err_len, "vkc_dispatch: out of host memory for %u bindings", (unsigned)binding_count);
            return 1;
        }
    }
    for (i = 0; i < binding_count; i++) {
        s->layout_bindings[i].binding = bindings[i].binding;
        s->layout_bindings[i].descriptorType = bindings[i].type;
        s->layout_bindings[i].descriptorCount = 1;
        s->layout_bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        if (bindings[i].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
            s->uniform_count++;
        else if (bindings[i].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
            s->storage_count++;
        else if (bindings[i].type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE)
            s->sampled_count++;
        else
            s->storage_image_count++;
    }
    return 0;
}

/* The descriptor set layout of the bindings. On failure o->set_layout
 * stays VK_NULL_HANDLE. */
static int create_set_layout(VkcContext *ctx, const DispatchScratch *s, uint32_t binding_count, DispatchObjects *o,
                             char *err, size_t err_len) {
    VkDescriptorSetLayoutCreateInfo ci;
    VkResult r;
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    ci.bindingCount = binding_count;
    ci.pBindings = s->layout_bindings;
    r = vkCreateDescriptorSetLayout(ctx->device, &ci, NULL, &o->set_layout);
    if (r != VK_SUCCESS) {
        o->set_layout = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateDescriptorSetLayout", r);
        return 1;
    }
    return 0;
}

/* The compute pipeline of o's module at `entry`. On failure o->pipeline
 * stays VK_NULL_HANDLE. */
static int create_compute_pipeline(VkcContext *ctx, const char *entry, DispatchObjects *o, char *err,
                                   size_t err_len) {
    VkComputePipelineCreateInfo ci;
    VkResult r;
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = o->module;
    ci.stage.pName = entry;
    ci.layout = o->pipeline_layout;
    ci.basePipelineIndex = -1;
    r = vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &ci, NULL, &o->pipeline);
    if (r != VK_SUCCESS) {
        o->pipeline = VK_NULL_HANDLE;
        vkci_fail(err, err_len, "vkCreateComputePipelines (entry point \"%s\") failed: %s (%d)", entry,
                  vkci_result_name(r), (int)r);
        return 1;
    }
    return 0;
}

/* The descriptor pool (o->descriptor_pool) and its one set, written with
 * the bindings; binding_count must be nonzero. On failure the pool, if
 * made, is left in `o` for the caller to release and *set stays
 * VK_NULL_HANDLE. */
static int write_descriptor_set(VkcContext *ctx, const VkcBinding *bindings, uint32_t binding_count,
                                DispatchScratch *s, DispatchObjects *o, VkDescriptorSet *set, char *err,
                                size_t err_len) {
    VkDescriptorPoolSize sizes[4];
    VkDescriptorPoolCreateInfo ci;
    VkDescriptorSetAllocateInfo ai;
    uint32_t size_count = 0, i;
    VkResult r;
    if (s->uniform_count > 0) {
        sizes[size_count].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        sizes[size_count].descriptorCount = s->uniform_count;
        size_count++;
    }
    if (s->storage_count > 0) {
        sizes[size_count].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        sizes[size_count].descriptorCount = s->storage_count;
        size_count++;
    }
    if (s->sampled_count > 0) {
        sizes[size_count].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        sizes[size_count].descriptorCount = s->sampled_count;
        size_count++;
    }
    if (s->storage_image_count > 0) {
        sizes[size_count].type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        sizes[size_count].descriptorCount = s->storage_image_count;
        size_count++;
    }
    memset(&ci, 0, sizeof ci);
    ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    ci.maxSets = 1;
    ci.poolSizeCount = size_count;
    ci.pPoolSizes = sizes;
    r = vkCreateDescriptorPool(ctx->device, &ci, NULL, &o->descriptor_pool);
    if (r != VK_SUCCESS) {
        o->descriptor_pool = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkCreateDescriptorPool", r);
        return 1;
    }
    memset(&ai, 0, sizeof ai);
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = o->descriptor_pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &o->set_layout;
    r = vkAllocateDescriptorSets(ctx->device, &ai, set);
    if (r != VK_SUCCESS) {
        *set = VK_NULL_HANDLE;
        vkci_fail_vk(err, err_len, "vkAllocateDescriptorSets", r);
        return 1;
    }
    for (i = 0; i < binding_count; i++) {
        s->writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        s->writes[i].dstSet = *set;
        s->writes[i].dstBinding = bindings[i].binding;
        s->writes[i].descriptorCount = 1;
        s->writes[i].descriptorType = bindings[i].type;
        /* `image` is read only for image types: a caller that binds a
         * buffer need not set it. */
        if (bindings[i].type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE ||
            bindings[i].type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
            s->image_infos[i].imageView = bindings[i].image->view;
            s->image_infos[i].imageLayout = VK_IMAGE_LAYOUT_GENERAL;
            s->writes[i].pImageInfo = &s->image_infos[i];
        } else {
            s->buffer_infos[i].buffer = bindings[i].buffer->buffer;
            s->buffer_infos[i].offset = 0;
            s->buffer_infos[i].range = VK_WHOLE_SIZE;
            s->writes[i].pBufferInfo = &s->buffer_infos[i];
        }
    }
    vkUpdateDescriptorSets(ctx->device, binding_count, s->writes, 0, NULL);
    return 0;
}

/* The device time between the two timestamps of the last submission, in
 * *elapsed_ms (left as it is when the queue has no timestamps). */
static int read_elapsed_ms(VkcContext *ctx, double *elapsed_ms, char *err, size_t err_len) {
    uint64_t ticks[2];
    uint64_t delta;
    VkResult r;
    if (ctx->timestamps == VK_NULL_HANDLE) return 0;
    r = vkGetQueryPoolResults(ctx->device, ctx->timestamps, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    if (r != VK_SUCCESS) {
        vkci_fail_vk(err, err_len, "vkGetQueryPoolResults", r);
        return 1;
    }
    delta = ticks[1] - ticks[0];
    /* Only the low timestampValidBits count; masking the difference
     * survives one wrap of the counter. */
    if (ctx->timestamp_bits < 64) delta &= (1ull << ctx->timestamp_bits) - 1ull;
    *elapsed_ms = (double)delta * (double)ctx->properties.limits.timestampPeriod / 1.0e6;
    return 0;
}

int vkc_dispatch(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, const char *entry,
                 const VkcBinding *bindings, uint32_t binding_count, uint32_t gx, uint32_t gy, uint32_t gz,
                 char *err, size_t err_len) {
    const uint32_t groups[3] = {gx, gy, gz};
    DispatchScratch scratch;
    DispatchObjects o;
    VkDescriptorSet set = VK_NULL_HANDLE;
    double elapsed_ms = -1.0;
    int rc = 1;

    memset(&o, 0, sizeof o);
    memset(&scratch, 0, sizeof scratch);
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (ctx == NULL) {
        vkci_fail(err, err_len, "vkc_dispatch: ctx is NULL");
        return 1;
    }
    ctx->last_ms = -1.0;
    if (ctx->wedged) {
        vkci_fail(err, err_len, "vkc_dispatch: an earlier dispatch timed out; destroy the context");
        return 1;
    }
    if (check_dispatch_args(ctx, spirv, spirv_bytes, entry, bindings, binding_count, groups, err, err_len) != 0)
        return 1;

    if (prepare_bindings(bindings, binding_count, &scratch, err, err_len) != 0) goto cleanup;
    if (create_set_layout(ctx, &scratch, binding_count, &o, err, err_len) != 0) goto cleanup;
    if (vkci_pipeline_layout(ctx, o.set_layout, 0, &o.pipeline_layout, err, err_len) != 0) goto cleanup;
    if (vkci_shader_module(ctx, spirv, spirv_bytes, "compute", &o.module, err, err_len) != 0) goto cleanup;
    if (create_compute_pipeline(ctx, entry, &o, err, err_len) != 0) goto cleanup;
    /* A pool needs a nonzero descriptorCount per size entry, so an empty set
     * gets no pool and is simply not bound. */
    if (binding_count > 0 &&
        write_descriptor_set(ctx, bindings, binding_count, &scratch, &o, &set, err, err_len) != 0)
        goto cleanup;

    {
        DispatchJob job;
        job.ctx = ctx;
        job.pipeline = o.pipeline;
        job.layout = o.pipeline_layout;
        job.set = set;
        memcpy(job.groups, groups, sizeof job.groups);
        if (vkci_submit_and_wait(ctx, &o, record_dispatch, &job, "vkc_dispatch", err, err_len) != 0) goto cleanup;
    }

    if (read_elapsed_ms(ctx, &elapsed_ms, err, err_len) != 0) goto cleanup;
    ctx->last_ms = elapsed_ms;
    rc = 0;

cleanup:
    vkci_release_objects(ctx, &o);
    free_scratch(&scratch);
    return rc;
}

double vkc_last_dispatch_ms(const VkcContext *ctx) {
    return ctx == NULL ? -1.0 : ctx->last_ms;
}
