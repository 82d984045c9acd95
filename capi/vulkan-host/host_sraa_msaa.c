/* SRAA behind a rasterised 4x MSAA prepass. */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A reversed-Z perspective projection (column-major, Vulkan clip space:
 * y down, depth 1 at `near` and 0 at `far`), the kind of matrix an engine's
 * prepass uses. */
static void reversed_z_perspective(float fov_y, float aspect, float near, float far, float m[16]) {
    const float f = 1.0f / tanf(0.5f * fov_y);
    memset(m, 0, 16 * sizeof *m);
    m[0] = f / aspect;                  /* m[0][0] */
    m[5] = -f;                          /* m[1][1] */
    m[10] = near / (far - near);        /* m[2][2] */
    m[11] = -1.0f;                      /* m[2][3] */
    m[14] = near * far / (far - near);  /* m[3][2] */
}

/* SRAA from a rasterised 4x MSAA prepass (shaders/sraa/msaa.spv, or
 * msaa-lights1.spv with one light's shadows): the host draws the prepass
 * of msaa_prepass.vert (a D32 depth attachment, reversed Z, and an
 * Rgba32Float attachment of signed normals, 4 samples each) and binds it
 * as shaders/sraa.md lists: frame, sub_depth, sub_normal (the attachments
 * themselves), color (a 2D array of 1 + lights layers with lights),
 * [shaded_shadow, sub_shadow (R32Uint, the latter 4 layers: subsample k in
 * layer k),] sraa_output (Rgba16Float). The CPU resolve is given the
 * samples the GPU stored (read back by msaa_read.comp), decoded as the
 * shader decodes them, with the paper's weights the variant is built for
 * (the shaded sample is subsample 0). The shadow is a slanted screen-space
 * edge, evaluated at every subsample. */
int run_sraa_msaa(Host *h, const char *dir, const char *prepass_dir, uint32_t lights, uint32_t width, uint32_t height) {
    const char *spv = lights ? "sraa/msaa-lights1.spv" : "sraa/msaa.spv";
    const size_t n = (size_t)width * height;
    SraaFrameData d;
    uint32_t *code[4] = {NULL, NULL, NULL, NULL};
    size_t bytes[4] = {0, 0, 0, 0};
    const char *names[4] = {"msaa_prepass.vert.spv", "msaa_prepass.frag.spv", "msaa_read.comp.spv", NULL};
    VkcImage depth, normal, color, output, shaded_shadow, sub_shadow;
    VkcBuffer samples, uniform, staging;
    int have[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    memset(&depth, 0, sizeof depth);
    memset(&normal, 0, sizeof normal);
    memset(&color, 0, sizeof color);
    memset(&output, 0, sizeof output);
    memset(&shaded_shadow, 0, sizeof shaded_shadow);
    memset(&sub_shadow, 0, sizeof sub_shadow);
    int rc = sraa_data_alloc(h, width, height, lights, &d);
    if (rc) goto done;
    rc = 2;
    for (int i = 0; i < 3; i++)
        if (load_spirv(prepass_dir, names[i], &code[i], &bytes[i], h->err, sizeof h->err)) goto done;
    if (load_spirv(dir, spv, &code[3], &bytes[3], h->err, sizeof h->err)) goto done;
    if (!vkc_standard_sample_locations(h->vk)) {
        snprintf(h->err, sizeof h->err, "the device does not place MSAA samples at the standard positions "
                                        "SRAA's SUBPIXEL_OFFSETS assume");
        goto done;
    }

    /* The prepass. */
    float projection[16];
    reversed_z_perspective(1.0f, (float)width / (float)height, 0.5f, 50.0f, projection);
    if (vkc_image_create_attachment(h->vk, width, height, VK_FORMAT_D32_SFLOAT, VK_SAMPLE_COUNT_4_BIT, &depth,
                                    h->err, sizeof h->err))
        goto done;
    have[0] = 1;
    if (vkc_image_create_attachment(h->vk, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLE_COUNT_4_BIT,
                                    &normal, h->err, sizeof h->err))
        goto done;
    have[1] = 1;
    VkcDraw draw;
    memset(&draw, 0, sizeof draw);
    draw.vertex_spirv = code[0];
    draw.vertex_bytes = bytes[0];
    draw.fragment_spirv = code[1];
    draw.fragment_bytes = bytes[1];
    draw.push = projection;
    draw.push_bytes = sizeof projection;
    draw.vertex_count = 12;
    draw.color = &normal;
    draw.depth = &depth;
    draw.clear_depth = 0.0f; /* reversed Z: the far plane, and a miss */
    draw.depth_compare = VK_COMPARE_OP_GREATER;
    if (vkc_draw(h->vk, &draw, h->err, sizeof h->err)) goto done;

    /* Every sample back, as the resolve will read it. */
    if (vkc_buffer_create(h->vk, 4 * n * 16, &samples, h->err, sizeof h->err)) goto done;
    have[4] = 1;
    VkcBinding read[3];
    memset(read, 0, sizeof read);
    read[0].binding = 0;
    read[0].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    read[0].image = &depth;
    read[1].binding = 1;
    read[1].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    read[1].image = &normal;
    read[2].binding = 2;
    read[2].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    read[2].buffer = &samples;
    if (vkc_dispatch(h->vk, code[2], bytes[2], "main", read, 3, (width + 7) / 8, (height + 7) / 8, 1, h->err,
                     sizeof h->err))
        goto done;

    /* The geometry as the shader decodes it (sraa_geometry of HARDWARE_DEPTH
     * with signed normals): view depth |(m32 − d·m33) / (d·m23 − m22)|, a
     * miss (+inf, no normal) for the clear value, the normal made unit. */
    const float *t = samples.mapped;
    const float m22 = projection[10], m32 = projection[14], m23 = projection[11], m33 = projection[15];
    size_t misses = 0;
    for (size_t i = 0; i < 4 * n; i++) {
        const float *v = t + 4 * i;
        SubconeGeometry g;
        memset(&g, 0, sizeof g);
        const float z = fabsf((m32 - v[3] * m33) / (v[3] * m23 - m22));
        const float l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if (v[3] == 0.0f || !(z > 0.0f && z <= 3.4e38f)) {
            g.depth = INFINITY;
            misses++;
        } else {
            g.depth = z;
            if (l2 > 0.0f && l2 <= 3.4e38f) {
                const float inv = 1.0f / sqrtf(l2);
                g.normal.x = v[0] * inv;
                g.normal.y = v[1] * inv;
                g.normal.z = v[2] * inv;
            }
        }
        d.subs[i] = g;
    }
    /* Colours that follow the geometry (a shade of the normal, darker with
     * depth; the lit layer warmer), the shaded sample being subsample 0;
     * the shadow bits of a slanted edge. */
    for (size_t p = 0; p < n; p++) {
        const SubconeGeometry g = d.subs[4 * p];
        d.shaded[p] = g;
        const float fade = g.depth < 1e30f ? 1.0f / (1.0f + 0.1f * g.depth) : 0.0f;
        for (uint32_t l = 0; l < d.layers; l++) {
            SubconeVec3 c = {0.5f + 0.5f * g.normal.x * fade + 0.3f * (float)l, 0.3f + 0.6f * fade,
                             0.8f - 0.5f * g.normal.z * fade - 0.3f * (float)l};
            d.colors[p * d.layers + l] = c;
        }
        const float x = (float)(p % width) + 0.5f, y = (float)(p / width) + 0.5f;
        for (uint32_t k = 0; k < 4; k++)
            d.sub_shadow[4 * p + k] =
                x + SUB_OFFSETS[k][0] > 0.55f * (float)width - 0.35f * (y + SUB_OFFSETS[k][1]);
        d.shaded_shadow[p] = d.sub_shadow[4 * p];
    }
    if (subcone_sraa_params_paper(&d.params) != SUBCONE_STATUS_OK ||
        subcone_sraa_pass_uniform(&d.params, width, height, projection, 0.0f, 0.0f, &d.uniform) !=
            SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the SRAA uniform");
        goto done;
    }
    rc = sraa_data_resolve(h, &d);
    if (rc) goto done;
    rc = 2;

    /* The resolve on the GPU. */
    if (vkc_image_create(h->vk, width, height, d.layers, lights > 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16, &color,
                         h->err, sizeof h->err))
        goto done;
    have[2] = 1;
    if (lights) {
        if (vkc_image_create(h->vk, width, height, 1, 0, VK_FORMAT_R32_UINT, 4, &shaded_shadow, h->err,
                             sizeof h->err))
            goto done;
        have[7] = 1;
        if (vkc_image_create(h->vk, width, height, 4, 1, VK_FORMAT_R32_UINT, 4, &sub_shadow, h->err,
                             sizeof h->err))
            goto done;
        have[8] = 1;
    }
    if (vkc_image_create(h->vk, width, height, 1, 0, VK_FORMAT_R16G16B16A16_SFLOAT, 8, &output, h->err,
                         sizeof h->err))
        goto done;
    have[3] = 1;
    if (vkc_buffer_create(h->vk, sizeof d.uniform, &uniform, h->err, sizeof h->err)) goto done;
    have[5] = 1;
    memcpy(uniform.mapped, &d.uniform, sizeof d.uniform);
    if (vkc_buffer_create(h->vk, n * d.layers * 16, &staging, h->err, sizeof h->err)) goto done;
    have[6] = 1;
    /* Layer after layer: layer l of the color array holds every pixel's
     * layer l. */
    float *texels = staging.mapped;
    for (uint32_t l = 0; l < d.layers; l++) rgba_texels(d.colors + l, n, d.layers, texels + 4 * l * n);
    if (vkc_image_copy(h->vk, &color, &staging, 1, h->err, sizeof h->err)) goto done;
    if (lights) {
        uint32_t *bits = staging.mapped;
        memcpy(bits, d.shaded_shadow, n * sizeof *bits);
        if (vkc_image_copy(h->vk, &shaded_shadow, &staging, 1, h->err, sizeof h->err)) goto done;
        for (uint32_t k = 0; k < 4; k++)
            for (size_t p = 0; p < n; p++) bits[k * n + p] = d.sub_shadow[4 * p + k];
        if (vkc_image_copy(h->vk, &sub_shadow, &staging, 1, h->err, sizeof h->err)) goto done;
    }
    VkcBinding bindings[7];
    const VkcImage *unlit[5] = {NULL, &depth, &normal, &color, &output};
    const VkcImage *lit[7] = {NULL, &depth, &normal, &color, &shaded_shadow, &sub_shadow, &output};
    const VkcImage **images = lights ? lit : unlit;
    const uint32_t count = lights ? 7 : 5;
    memset(bindings, 0, sizeof bindings);
    for (uint32_t i = 0; i < count; i++) {
        bindings[i].binding = i;
        bindings[i].type = i == 0           ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                           : i == count - 1 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                            : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        bindings[i].buffer = &uniform;
        bindings[i].image = images[i];
    }
    if (vkc_dispatch(h->vk, code[3], bytes[3], "sraa_resolve_main", bindings, count, (width + 7) / 8,
                     (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    double ms = vkc_last_dispatch_ms(h->vk);
    if (vkc_image_copy(h->vk, &output, &staging, 0, h->err, sizeof h->err)) goto done;
    float *gpu = malloc(4 * n * sizeof *gpu);
    if (!gpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        goto done;
    }
    halves_to_floats(staging.mapped, 4 * n, gpu);
    /* Pixels the resolve changed (away from the sum of their own layers):
     * the comparison covers edges, not copies. */
    size_t blended = 0;
    for (size_t p = 0; p < n; p++) {
        SubconeVec3 own = {0.0f, 0.0f, 0.0f};
        for (uint32_t l = 0; l < d.layers; l++) {
            own.x += d.colors[p * d.layers + l].x;
            own.y += d.colors[p * d.layers + l].y;
            own.z += d.colors[p * d.layers + l].z;
        }
        blended += fabsf(d.cpu[p].x - own.x) + fabsf(d.cpu[p].y - own.y) + fabsf(d.cpu[p].z - own.z) > 1e-3f;
    }
    printf("sraa  %-26s %ux%u: a rasterised 4x MSAA prepass, %zu of %zu samples missed, %zu pixels blended\n",
           spv, width, height, misses, 4 * n, blended);
    /* The output is binary16: up to one of its ulps (2^-10 relative) on
     * top of the f32 resolve's tolerance, as for TAA. */
    rc = sraa_compare(h, spv, &d, gpu, SRAA_REL + 1.0 / 1024.0, ms);
    free(gpu);
done:
    if (have[0]) vkc_image_destroy(h->vk, &depth);
    if (have[1]) vkc_image_destroy(h->vk, &normal);
    if (have[2]) vkc_image_destroy(h->vk, &color);
    if (have[3]) vkc_image_destroy(h->vk, &output);
    if (have[4]) vkc_buffer_destroy(h->vk, &samples);
    if (have[5]) vkc_buffer_destroy(h->vk, &uniform);
    if (have[6]) vkc_buffer_destroy(h->vk, &staging);
    if (have[7]) vkc_image_destroy(h->vk, &shaded_shadow);
    if (have[8]) vkc_image_destroy(h->vk, &sub_shadow);
    for (int i = 0; i < 4; i++) free(code[i]);
    sraa_data_free(&d);
    return rc;
}
