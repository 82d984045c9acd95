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

/* What the MSAA run creates, released by msaa_release: the SPIR-V (the
 * prepass's vertex and fragment shaders, the read-back, the resolve), the
 * images and buffers, and which of them exist (`have`, by MsaaHave). */
typedef struct MsaaResources {
    uint32_t *code[4];
    size_t bytes[4];
    VkcImage depth, normal, color, output, shaded_shadow, sub_shadow;
    VkcBuffer samples, uniform, staging;
    int have[9];
} MsaaResources;

enum MsaaHave {
    HAVE_DEPTH,
    HAVE_NORMAL,
    HAVE_COLOR,
    HAVE_OUTPUT,
    HAVE_SAMPLES,
    HAVE_UNIFORM,
    HAVE_STAGING,
    HAVE_SHADED_SHADOW,
    HAVE_SUB_SHADOW
};

/* Destroys every image and buffer of `r` that exists and frees the SPIR-V. */
static void msaa_release(Host *h, MsaaResources *r) {
    if (r->have[HAVE_DEPTH]) vkc_image_destroy(h->vk, &r->depth);
    if (r->have[HAVE_NORMAL]) vkc_image_destroy(h->vk, &r->normal);
    if (r->have[HAVE_COLOR]) vkc_image_destroy(h->vk, &r->color);
    if (r->have[HAVE_OUTPUT]) vkc_image_destroy(h->vk, &r->output);
    if (r->have[HAVE_SAMPLES]) vkc_buffer_destroy(h->vk, &r->samples);
    if (r->have[HAVE_UNIFORM]) vkc_buffer_destroy(h->vk, &r->uniform);
    if (r->have[HAVE_STAGING]) vkc_buffer_destroy(h->vk, &r->staging);
    if (r->have[HAVE_SHADED_SHADOW]) vkc_image_destroy(h->vk, &r->shaded_shadow);
    if (r->have[HAVE_SUB_SHADOW]) vkc_image_destroy(h->vk, &r->sub_shadow);
    for (int i = 0; i < 4; i++) free(r->code[i]);
}

/* Loads the prepass's three shaders and the resolve `spv`, and checks the
 * device places MSAA samples where SRAA assumes. */
static int msaa_load_shaders(Host *h, const char *dir, const char *prepass_dir, const char *spv, MsaaResources *r) {
    const char *names[3] = {"msaa_prepass.vert.spv", "msaa_prepass.frag.spv", "msaa_read.comp.spv"};
    for (int i = 0; i < 3; i++)
        if (load_spirv(prepass_dir, names[i], &r->code[i], &r->bytes[i], h->err, sizeof h->err)) return 2;
    if (load_spirv(dir, spv, &r->code[3], &r->bytes[3], h->err, sizeof h->err)) return 2;
    if (!vkc_standard_sample_locations(h->vk)) {
        snprintf(h->err, sizeof h->err, "the device does not place MSAA samples at the standard positions "
                                        "SRAA's SUBPIXEL_OFFSETS assume");
        return 2;
    }
    return 0;
}

/* Draws the prepass into a 4x D32 depth and an Rgba32Float normal
 * attachment, reversed Z with `projection`. */
static int msaa_draw_prepass(Host *h, uint32_t width, uint32_t height, float projection[16], MsaaResources *r) {
    if (vkc_image_create_attachment(h->vk, width, height, VK_FORMAT_D32_SFLOAT, VK_SAMPLE_COUNT_4_BIT, &r->depth,
                                    h->err, sizeof h->err))
        return 2;
    r->have[HAVE_DEPTH] = 1;
    if (vkc_image_create_attachment(h->vk, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLE_COUNT_4_BIT,
                                    &r->normal, h->err, sizeof h->err))
        return 2;
    r->have[HAVE_NORMAL] = 1;
    VkcDraw draw;
    memset(&draw, 0, sizeof draw);
    draw.vertex_spirv = r->code[0];
    draw.vertex_bytes = r->bytes[0];
    draw.fragment_spirv = r->code[1];
    draw.fragment_bytes = r->bytes[1];
    draw.push = projection;
    draw.push_bytes = 16 * sizeof *projection;
    draw.vertex_count = 12;
    draw.color = &r->normal;
    draw.depth = &r->depth;
    draw.clear_depth = 0.0f; /* reversed Z: the far plane, and a miss */
    draw.depth_compare = VK_COMPARE_OP_GREATER;
    if (vkc_draw(h->vk, &draw, h->err, sizeof h->err)) return 2;
    return 0;
}

/* Reads every sample of both attachments back into r->samples (4n texels of
 * 4 floats: the normal, then the depth) with msaa_read.comp. */
static int msaa_read_samples(Host *h, uint32_t width, uint32_t height, MsaaResources *r) {
    const size_t n = (size_t)width * height;
    if (vkc_buffer_create(h->vk, 4 * n * 16, &r->samples, h->err, sizeof h->err)) return 2;
    r->have[HAVE_SAMPLES] = 1;
    VkcBinding read[3];
    memset(read, 0, sizeof read);
    read[0].binding = 0;
    read[0].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    read[0].image = &r->depth;
    read[1].binding = 1;
    read[1].type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    read[1].image = &r->normal;
    read[2].binding = 2;
    read[2].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    read[2].buffer = &r->samples;
    if (vkc_dispatch(h->vk, r->code[2], r->bytes[2], "main", read, 3, (width + 7) / 8, (height + 7) / 8, 1, h->err,
                     sizeof h->err))
        return 2;
    return 0;
}

/* The geometry as the shader decodes it (sraa_geometry of HARDWARE_DEPTH
 * with signed normals) into d->subs: view depth |(m32 − d·m33) / (d·m23 −
 * m22)|, a miss (+inf, no normal) for the clear value, the normal made
 * unit. Returns the number of misses. */
static size_t msaa_decode_samples(const float *t, const float projection[16], SraaFrameData *d) {
    const size_t n = d->n;
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
        d->subs[i] = g;
    }
    return misses;
}

/* Colours that follow the geometry (a shade of the normal, darker with
 * depth; the lit layer warmer), the shaded sample being subsample 0; the
 * shadow bits of a slanted edge. */
static void msaa_shade_frame(SraaFrameData *d) {
    const size_t n = d->n;
    const uint32_t width = d->width;
    for (size_t p = 0; p < n; p++) {
        const SubconeGeometry g = d->subs[4 * p];
        d->shaded[p] = g;
        const float fade = g.depth < 1e30f ? 1.0f / (1.0f + 0.1f * g.depth) : 0.0f;
        for (uint32_t l = 0; l < d->layers; l++) {
            SubconeVec3 c = {0.5f + 0.5f * g.normal.x * fade + 0.3f * (float)l, 0.3f + 0.6f * fade,
                             0.8f - 0.5f * g.normal.z * fade - 0.3f * (float)l};
            d->colors[p * d->layers + l] = c;
        }
        const float x = (float)(p % width) + 0.5f, y = (float)(p / width) + 0.5f;
        for (uint32_t k = 0; k < 4; k++)
            d->sub_shadow[4 * p + k] =
                x + SUB_OFFSETS[k][0] > 0.55f * (float)width - 0.35f * (y + SUB_OFFSETS[k][1]);
        d->shaded_shadow[p] = d->sub_shadow[4 * p];
    }
}

/* Creates the resolve's images (colour layers, with lights the shadow bits,
 * the output), its uniform and a staging buffer, and uploads the frame. */
static int msaa_upload_frame(Host *h, const SraaFrameData *d, uint32_t lights, MsaaResources *r) {
    const uint32_t width = d->width, height = d->height;
    const size_t n = d->n;
    if (vkc_image_create(h->vk, width, height, d->layers, lights > 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16, &r->color,
                         h->err, sizeof h->err))
        return 2;
    r->have[HAVE_COLOR] = 1;
    if (lights) {
        if (vkc_image_create(h->vk, width, height, 1, 0, VK_FORMAT_R32_UINT, 4, &r->shaded_shadow, h->err,
                             sizeof h->err))
            return 2;
        r->have[HAVE_SHADED_SHADOW] = 1;
        if (vkc_image_create(h->vk, width, height, 4, 1, VK_FORMAT_R32_UINT, 4, &r->sub_shadow, h->err,
                             sizeof h->err))
            return 2;
        r->have[HAVE_SUB_SHADOW] = 1;
    }
    if (vkc_image_create(h->vk, width, height, 1, 0, VK_FORMAT_R16G16B16A16_SFLOAT, 8, &r->output, h->err,
                         sizeof h->err))
        return 2;
    r->have[HAVE_OUTPUT] = 1;
    if (vkc_buffer_create(h->vk, sizeof d->uniform, &r->uniform, h->err, sizeof h->err)) return 2;
    r->have[HAVE_UNIFORM] = 1;
    memcpy(r->uniform.mapped, &d->uniform, sizeof d->uniform);
    if (vkc_buffer_create(h->vk, n * d->layers * 16, &r->staging, h->err, sizeof h->err)) return 2;
    r->have[HAVE_STAGING] = 1;
    /* Layer after layer: layer l of the color array holds every pixel's
     * layer l. */
    float *texels = r->staging.mapped;
    for (uint32_t l = 0; l < d->layers; l++) rgba_texels(d->colors + l, n, d->layers, texels + 4 * l * n);
    if (vkc_image_copy(h->vk, &r->color, &r->staging, 1, h->err, sizeof h->err)) return 2;
    if (lights) {
        uint32_t *bits = r->staging.mapped;
        memcpy(bits, d->shaded_shadow, n * sizeof *bits);
        if (vkc_image_copy(h->vk, &r->shaded_shadow, &r->staging, 1, h->err, sizeof h->err)) return 2;
        for (uint32_t k = 0; k < 4; k++)
            for (size_t p = 0; p < n; p++) bits[k * n + p] = d->sub_shadow[4 * p + k];
        if (vkc_image_copy(h->vk, &r->sub_shadow, &r->staging, 1, h->err, sizeof h->err)) return 2;
    }
    return 0;
}

/* Runs the resolve shader over the prepass's attachments and the uploaded
 * frame, binding them as shaders/sraa.md lists. */
static int msaa_dispatch_resolve(Host *h, uint32_t lights, uint32_t width, uint32_t height, MsaaResources *r) {
    VkcBinding bindings[7];
    const VkcImage *unlit[5] = {NULL, &r->depth, &r->normal, &r->color, &r->output};
    const VkcImage *lit[7] = {NULL, &r->depth, &r->normal, &r->color, &r->shaded_shadow, &r->sub_shadow, &r->output};
    const VkcImage **images = lights ? lit : unlit;
    const uint32_t count = lights ? 7 : 5;
    memset(bindings, 0, sizeof bindings);
    for (uint32_t i = 0; i < count; i++) {
        bindings[i].binding = i;
        bindings[i].type = i == 0           ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                           : i == count - 1 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                            : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        bindings[i].buffer = &r->uniform;
        bindings[i].image = images[i];
    }
    if (vkc_dispatch(h->vk, r->code[3], r->bytes[3], "sraa_resolve_main", bindings, count, (width + 7) / 8,
                     (height + 7) / 8, 1, h->err, sizeof h->err))
        return 2;
    return 0;
}

/* Reads the output back, reports the misses and the pixels the resolve
 * blended, and compares it with the CPU's resolve: sraa_compare's result,
 * or 2 when the output cannot be read. */
static int msaa_compare_output(Host *h, const char *spv, const SraaFrameData *d, MsaaResources *r, size_t misses,
                               double ms) {
    const size_t n = d->n;
    if (vkc_image_copy(h->vk, &r->output, &r->staging, 0, h->err, sizeof h->err)) return 2;
    float *gpu = malloc(4 * n * sizeof *gpu);
    if (!gpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        return 2;
    }
    halves_to_floats(r->staging.mapped, 4 * n, gpu);
    /* Pixels the resolve changed (away from the sum of their own layers):
     * the comparison covers edges, not copies. */
    size_t blended = 0;
    for (size_t p = 0; p < n; p++) {
        SubconeVec3 own = {0.0f, 0.0f, 0.0f};
        for (uint32_t l = 0; l < d->layers; l++) {
            own.x += d->colors[p * d->layers + l].x;
            own.y += d->colors[p * d->layers + l].y;
            own.z += d->colors[p * d->layers + l].z;
        }
        blended += fabsf(d->cpu[p].x - own.x) + fabsf(d->cpu[p].y - own.y) + fabsf(d->cpu[p].z - own.z) > 1e-3f;
    }
    printf("sraa  %-26s %ux%u: a rasterised 4x MSAA prepass, %zu of %zu samples missed, %zu pixels blended\n",
           spv, d->width, d->height, misses, 4 * n, blended);
    /* The output is binary16: up to one of its ulps (2^-10 relative) on
     * top of the f32 resolve's tolerance, as for TAA. */
    int rc = sraa_compare(h, spv, d, gpu, SRAA_REL + 1.0 / 1024.0, ms);
    free(gpu);
    return rc;
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
    SraaFrameData d;
    MsaaResources r;
    float projection[16];
    size_t misses;
    memset(&r, 0, sizeof r);
    int rc = sraa_data_alloc(h, width, height, lights, &d);
    if (rc) goto done;
    rc = 2;
    if (msaa_load_shaders(h, dir, prepass_dir, spv, &r)) goto done;

    /* The prepass. */
    reversed_z_perspective(1.0f, (float)width / (float)height, 0.5f, 50.0f, projection);
    if (msaa_draw_prepass(h, width, height, projection, &r)) goto done;

    /* Every sample back, as the resolve will read it, and the frame made
     * of it. */
    if (msaa_read_samples(h, width, height, &r)) goto done;
    misses = msaa_decode_samples(r.samples.mapped, projection, &d);
    msaa_shade_frame(&d);
    if (subcone_sraa_params_paper(&d.params) != SUBCONE_STATUS_OK ||
        subcone_sraa_pass_uniform(&d.params, width, height, projection, 0.0f, 0.0f, &d.uniform) !=
            SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the SRAA uniform: %s",
                 subcone_last_error_message());
        goto done;
    }
    rc = sraa_data_resolve(h, &d);
    if (rc) goto done;
    rc = 2;

    /* The resolve on the GPU. */
    if (msaa_upload_frame(h, &d, lights, &r)) goto done;
    if (msaa_dispatch_resolve(h, lights, width, height, &r)) goto done;
    rc = msaa_compare_output(h, spv, &d, &r, misses, vkc_last_dispatch_ms(h->vk));
done:
    msaa_release(h, &r);
    sraa_data_free(&d);
    return rc;
}
