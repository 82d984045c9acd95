/* SRAA: the synthetic frame and its CPU resolve (shared with the MSAA
 * variant), the comparison, and SRAA from storage buffers and from
 * textures. */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A deterministic sequence in [0, 1). */
static float next_unit(uint32_t *state) {
    *state = *state * 1664525u + 1013904223u;
    return (float)(*state >> 8) / 16777216.0f;
}

static SubconeVec3 normalized(float x, float y, float z) {
    float l = sqrtf(x * x + y * y + z * z);
    SubconeVec3 v = {x / l, y / l, z / l};
    return v;
}

/* The geometry at image point (x, y): two curved surfaces meeting along a
 * slanted edge (a depth step), their normals turning from pixel to pixel, so
 * that both factors of eq. 1 (depth and normal) weigh the neighbours. */
static SubconeGeometry geometry_at(float x, float y, uint32_t width) {
    SubconeGeometry g;
    if (x < 0.37f * (float)width + 0.45f * y) {
        g.normal = normalized(0.8f * sinf(0.7f * x), 0.6f * cosf(0.5f * y), -1.0f);
        g.depth = 2.0f + 0.05f * sinf(0.3f * x + 0.2f * y);
    } else {
        g.normal = normalized(0.3f + 0.5f * cosf(0.9f * y), 0.2f, -1.0f);
        g.depth = 2.6f + 0.02f * y;
    }
    return g;
}

const float SUB_OFFSETS[4][2] = {
    {-0.125f, -0.375f}, {0.375f, -0.125f}, {-0.375f, 0.125f}, {0.125f, 0.375f}};

void sraa_data_free(SraaFrameData *d) {
    free(d->colors);
    free(d->shaded);
    free(d->subs);
    free(d->shaded_shadow);
    free(d->sub_shadow);
    free(d->cpu);
    memset(d, 0, sizeof *d);
}

int sraa_data_alloc(Host *h, uint32_t width, uint32_t height, uint32_t lights, SraaFrameData *d) {
    memset(d, 0, sizeof *d);
    d->width = width;
    d->height = height;
    d->layers = 1 + lights;
    d->n = (size_t)width * height;
    const size_t n = d->n;
    d->colors = malloc(n * d->layers * sizeof *d->colors);
    d->shaded = malloc(n * sizeof *d->shaded);
    d->subs = malloc(4 * n * sizeof *d->subs);
    d->shaded_shadow = malloc(n * sizeof *d->shaded_shadow);
    d->sub_shadow = malloc(4 * n * sizeof *d->sub_shadow);
    d->cpu = malloc(n * sizeof *d->cpu);
    if (!d->colors || !d->shaded || !d->subs || !d->shaded_shadow || !d->sub_shadow || !d->cpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        return 2;
    }
    return 0;
}

int sraa_data_resolve(Host *h, SraaFrameData *d) {
    const size_t n = d->n;
    const int lights = d->layers > 1;
    int8_t layer_lights[2] = {-1, 0};
    SubconeSraaFrame frame;
    memset(&frame, 0, sizeof frame);
    frame.size = sizeof frame;
    frame.width = d->width;
    frame.height = d->height;
    frame.layers = d->layers;
    frame.colors = d->colors;
    frame.colors_len = n * d->layers;
    frame.layer_lights = lights ? layer_lights : NULL;
    frame.shaded_geometry = d->shaded;
    frame.shaded_geometry_len = n;
    frame.shaded_shadow = lights ? d->shaded_shadow : NULL;
    frame.shaded_shadow_len = lights ? n : 0;
    frame.subsample_geometry = d->subs;
    frame.subsample_geometry_len = 4 * n;
    frame.subsample_shadow = lights ? d->sub_shadow : NULL;
    frame.subsample_shadow_len = lights ? 4 * n : 0;
    SubconeStatus st = subcone_sraa_resolve(&d->params, &frame, d->cpu, n);
    if (st != SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "status %d: %s", (int)st, subcone_last_error_message());
        return 2;
    }
    return 0;
}

/* The synthetic frame: geometry at the pixel centres (the tuned preset
 * shades there) and at the subsamples, a colour per layer, shadow bits; the
 * uniform; and the CPU's resolve of it. */
static int sraa_data_make(Host *h, uint32_t width, uint32_t height, uint32_t lights, SraaFrameData *d) {
    int rc = sraa_data_alloc(h, width, height, lights, d);
    if (rc) return rc;
    uint32_t seed = 12345u;
    for (uint32_t y = 0; y < height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            size_t p = (size_t)y * width + x;
            d->shaded[p] = geometry_at((float)x + 0.5f, (float)y + 0.5f, width);
            d->shaded_shadow[p] = next_unit(&seed) < 0.3f ? 1u : 0u;
            for (uint32_t k = 0; k < 4; k++) {
                d->subs[4 * p + k] = geometry_at((float)x + 0.5f + SUB_OFFSETS[k][0],
                                                 (float)y + 0.5f + SUB_OFFSETS[k][1], width);
                d->sub_shadow[4 * p + k] = next_unit(&seed) < 0.3f ? 1u : 0u;
            }
            for (uint32_t l = 0; l < d->layers; l++) {
                SubconeVec3 c = {next_unit(&seed), next_unit(&seed), next_unit(&seed)};
                d->colors[p * d->layers + l] = c;
            }
        }
    }
    if (subcone_sraa_params_default(&d->params) != SUBCONE_STATUS_OK ||
        subcone_sraa_pass_uniform(&d->params, width, height, NULL, 0.0f, 0.0f, &d->uniform) !=
            SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the SRAA uniform: %s",
                 subcone_last_error_message());
        return 2;
    }
    return sraa_data_resolve(h, d);
}

int sraa_compare(Host *h, const char *spv, const SraaFrameData *d, const float *gpu, double rel, double ms) {
    double max_abs = 0.0, max_rel = 0.0;
    size_t outside = 0;
    for (size_t p = 0; p < d->n; p++) {
        const float cpu[3] = {d->cpu[p].x, d->cpu[p].y, d->cpu[p].z};
        for (int c = 0; c < 3; c++) {
            float a = gpu[4 * p + c], b = cpu[c];
            float e = fabsf(a - b);
            float scale = fmaxf(fabsf(a), fabsf(b));
            if (!(e <= rel * scale + SRAA_ABS)) outside++;
            if (e > max_abs) max_abs = e;
            if (scale > 0.0f && e / scale > max_rel) max_rel = e / scale;
        }
    }
    printf("sraa  %-26s %ux%u, %u layer(s): max |gpu-cpu| %.3g, max relative %.3g, "
           "%zu of %zu channels outside %.3g relative + %.0e; one dispatch %.3f ms\n",
           spv, d->width, d->height, d->layers, max_abs, max_rel, outside, 3 * d->n, rel, (double)SRAA_ABS, ms);
    if (outside) snprintf(h->err, sizeof h->err, "%s: %zu channels outside the tolerance", spv, outside);
    return outside == 0 ? 0 : 1;
}

/* SRAA from storage buffers (shaders/sraa/buffers*.spv, `lights` lights):
 * the bindings of shaders/sraa.md, frame, shaded_geo, sub_geo,
 * [shaded_shadow, sub_shadow,] color, sraa_output. Geometry is the C ABI's
 * SubconeGeometry (16 bytes, the shader's subcone_Geometry), colours
 * vec4<f32>. */
int run_sraa_buffers(Host *h, const char *dir, const char *spv, uint32_t lights, uint32_t width, uint32_t height) {
    SraaFrameData d;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcBuffer bufs[7];
    int made = 0;
    int rc = sraa_data_make(h, width, height, lights, &d);
    if (rc) goto done;
    rc = 2;
    if (load_spirv(dir, spv, &code, &code_bytes, h->err, sizeof h->err)) goto done;
    const size_t n = d.n;
    const VkDeviceSize sizes[7] = {
        sizeof d.uniform, n * sizeof(SubconeGeometry), 4 * n * sizeof(SubconeGeometry),
        n * sizeof(uint32_t), 4 * n * sizeof(uint32_t), n * d.layers * 16, n * 16};
    const int order_lit[7] = {0, 1, 2, 3, 4, 5, 6};
    const int order_unlit[5] = {0, 1, 2, 5, 6};
    const int *order = lights ? order_lit : order_unlit;
    const uint32_t count = lights ? 7 : 5;
    for (int i = 0; i < 7; i++) {
        if (vkc_buffer_create(h->vk, sizes[i], &bufs[i], h->err, sizeof h->err)) goto done;
        made = i + 1;
    }
    memcpy(bufs[0].mapped, &d.uniform, sizeof d.uniform);
    memcpy(bufs[1].mapped, d.shaded, n * sizeof *d.shaded);
    memcpy(bufs[2].mapped, d.subs, 4 * n * sizeof *d.subs);
    memcpy(bufs[3].mapped, d.shaded_shadow, n * sizeof *d.shaded_shadow);
    memcpy(bufs[4].mapped, d.sub_shadow, 4 * n * sizeof *d.sub_shadow);
    rgba_texels(d.colors, n * d.layers, 1, bufs[5].mapped);
    VkcBinding bindings[7];
    memset(bindings, 0, sizeof bindings);
    for (uint32_t i = 0; i < count; i++) {
        bindings[i].binding = i;
        bindings[i].type =
            order[i] == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].buffer = &bufs[order[i]];
    }
    if (vkc_dispatch(h->vk, code, code_bytes, "sraa_resolve_main", bindings, count,
                     (width + 7) / 8, (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    rc = sraa_compare(h, spv, &d, bufs[6].mapped, SRAA_REL, vkc_last_dispatch_ms(h->vk));
done:
    for (int i = 0; i < made; i++) vkc_buffer_destroy(h->vk, &bufs[i]);
    free(code);
    sraa_data_free(&d);
    return rc;
}

/* SRAA from textures (shaders/sraa/packed.spv): the bindings of
 * shaders/sraa.md, frame; sub_depth, four layers of (normal, linear view
 * depth); centre_depth (.x) and centre_normal (.xyz) at the pixel centres;
 * color; sraa_output, an Rgba32Float storage image. Every texture here is
 * Rgba32Float, uploaded through a staging buffer. */
int run_sraa_packed(Host *h, const char *dir, uint32_t width, uint32_t height) {
    const char *spv = "sraa/packed.spv";
    const VkFormat rgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
    SraaFrameData d;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcImage img[5];
    VkcBuffer uniform, staging;
    int images = 0, have_uniform = 0, have_staging = 0;
    memset(img, 0, sizeof img);
    int rc = sraa_data_make(h, width, height, 0, &d);
    if (rc) goto done;
    rc = 2;
    if (load_spirv(dir, spv, &code, &code_bytes, h->err, sizeof h->err)) goto done;
    const size_t n = d.n;
    /* sub_depth (4 layers), centre_depth, centre_normal, color, output. */
    const uint32_t layers[5] = {4, 1, 1, 1, 1};
    for (int i = 0; i < 5; i++) {
        if (vkc_image_create(h->vk, width, height, layers[i], i == 0, rgba32f, 16, &img[i], h->err,
                             sizeof h->err))
            goto done;
        images = i + 1;
    }
    if (vkc_buffer_create(h->vk, sizeof d.uniform, &uniform, h->err, sizeof h->err)) goto done;
    have_uniform = 1;
    memcpy(uniform.mapped, &d.uniform, sizeof d.uniform);
    if (vkc_buffer_create(h->vk, 4 * n * 16, &staging, h->err, sizeof h->err)) goto done;
    have_staging = 1;
    float *t = staging.mapped;
    /* Layer k of sub_depth holds every pixel's subsample k. */
    for (uint32_t k = 0; k < 4; k++) {
        for (size_t p = 0; p < n; p++) {
            const SubconeGeometry g = d.subs[4 * p + k];
            float *texel = t + 4 * (k * n + p);
            texel[0] = g.normal.x;
            texel[1] = g.normal.y;
            texel[2] = g.normal.z;
            texel[3] = g.depth;
        }
    }
    if (vkc_image_copy(h->vk, &img[0], &staging, 1, h->err, sizeof h->err)) goto done;
    for (int which = 1; which <= 3; which++) {
        if (which == 3) {
            rgba_texels(d.colors, n, 1, t);
        } else {
            for (size_t p = 0; p < n; p++) {
                float *texel = t + 4 * p;
                const SubconeGeometry g = d.shaded[p];
                texel[0] = which == 1 ? g.depth : g.normal.x;
                texel[1] = which == 1 ? 0.0f : g.normal.y;
                texel[2] = which == 1 ? 0.0f : g.normal.z;
                texel[3] = 0.0f;
            }
        }
        if (vkc_image_copy(h->vk, &img[which], &staging, 1, h->err, sizeof h->err)) goto done;
    }
    VkcBinding bindings[6];
    memset(bindings, 0, sizeof bindings);
    bindings[0].binding = 0;
    bindings[0].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    bindings[0].buffer = &uniform;
    for (uint32_t i = 1; i < 6; i++) {
        bindings[i].binding = i;
        bindings[i].type = i == 5 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        bindings[i].image = &img[i - 1];
    }
    if (vkc_dispatch(h->vk, code, code_bytes, "sraa_resolve_main", bindings, 6, (width + 7) / 8,
                     (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    double ms = vkc_last_dispatch_ms(h->vk);
    if (vkc_image_copy(h->vk, &img[4], &staging, 0, h->err, sizeof h->err)) goto done;
    rc = sraa_compare(h, spv, &d, staging.mapped, SRAA_REL, ms);
done:
    for (int i = 0; i < images; i++) vkc_image_destroy(h->vk, &img[i]);
    if (have_uniform) vkc_buffer_destroy(h->vk, &uniform);
    if (have_staging) vkc_buffer_destroy(h->vk, &staging);
    free(code);
    sraa_data_free(&d);
    return rc;
}
