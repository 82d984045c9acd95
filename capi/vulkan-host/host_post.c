/* The post passes, FXAA and TAA: one way to run them, their input, and
 * each one's comparison with the CPU. */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The post passes (shaders/fxaa.md, shaders/taa.md): two uniform buffers at
 * bindings 0 and 1, `inputs` sampled textures at 2.., the Rgba16Float
 * storage image after them. Every input is an Rgba32Float texture of
 * width × height texels (4 floats each; the velocity's xy are its first
 * two). `gpu` receives the output as 4·width·height floats. */
typedef struct PostPass {
    const char *spv, *entry;
    const void *uniform[2];
    size_t uniform_bytes[2];
    const float *inputs[3];
    uint32_t input_count;
} PostPass;

static int run_post(Host *h, const char *dir, const PostPass *pass, uint32_t width, uint32_t height,
                    float *gpu, double *ms) {
    const size_t n = (size_t)width * height;
    int rc = 2, buffers = 0, images = 0;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcBuffer buf[3]; /* the two uniforms, the staging buffer */
    VkcImage img[4];  /* the inputs, the output */
    memset(img, 0, sizeof img);
    if (load_spirv(dir, pass->spv, &code, &code_bytes, h->err, sizeof h->err)) goto done;
    const VkDeviceSize sizes[3] = {pass->uniform_bytes[0], pass->uniform_bytes[1], n * 16};
    for (int i = 0; i < 3; i++) {
        if (vkc_buffer_create(h->vk, sizes[i], &buf[i], h->err, sizeof h->err)) goto done;
        buffers = i + 1;
        if (i < 2) memcpy(buf[i].mapped, pass->uniform[i], pass->uniform_bytes[i]);
    }
    const uint32_t k = pass->input_count;
    for (uint32_t i = 0; i <= k; i++) {
        const int output = i == k;
        if (vkc_image_create(h->vk, width, height, 1, 0,
                             output ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT,
                             output ? 8 : 16, &img[i], h->err, sizeof h->err))
            goto done;
        images = (int)i + 1;
        if (!output) {
            memcpy(buf[2].mapped, pass->inputs[i], n * 16);
            if (vkc_image_copy(h->vk, &img[i], &buf[2], 1, h->err, sizeof h->err)) goto done;
        }
    }
    VkcBinding bindings[6];
    memset(bindings, 0, sizeof bindings);
    for (uint32_t i = 0; i < k + 3; i++) {
        bindings[i].binding = i;
        if (i < 2) {
            bindings[i].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            bindings[i].buffer = &buf[i];
        } else {
            bindings[i].type = i == k + 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
            bindings[i].image = &img[i - 2];
        }
    }
    if (vkc_dispatch(h->vk, code, code_bytes, pass->entry, bindings, k + 3, (width + 7) / 8,
                     (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    *ms = vkc_last_dispatch_ms(h->vk);
    if (vkc_image_copy(h->vk, &img[k], &buf[2], 0, h->err, sizeof h->err)) goto done;
    halves_to_floats(buf[2].mapped, 4 * n, gpu);
    rc = 0;
done:
    for (int i = 0; i < images; i++) vkc_image_destroy(h->vk, &img[i]);
    for (int i = 0; i < buffers; i++) vkc_buffer_destroy(h->vk, &buf[i]);
    free(code);
    return rc;
}

/* A post pass's input: slanted edges, a disk and a thin line over a
 * gradient, an HDR highlight and a NaN (both passes sanitise), 4 floats per
 * pixel. `phase` moves the pattern (TAA's history is the previous frame's). */
static void post_input(uint32_t width, uint32_t height, uint32_t phase, float *out) {
    for (uint32_t y = 0; y < height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            float *t = out + 4 * ((size_t)y * width + x);
            const float fx = (float)x + 0.5f + 0.7f * (float)phase, fy = (float)y + 0.5f;
            const float dx = fx - 0.6f * (float)width, dy = fy - 0.5f * (float)height;
            const int edge = fx < 0.3f * (float)width + 0.4f * fy;
            const int disk = dx * dx + dy * dy < 0.09f * (float)(height * height);
            const int line = fabsf(fy - 0.2f * fx - 5.0f) < 0.5f;
            float r = 0.1f + 0.6f * fy / (float)height, g = 0.2f, b = 0.3f;
            if (edge) r = 0.9f, g = 0.75f, b = 0.2f;
            if (disk) r = 0.05f, g = 0.5f, b = 0.9f;
            if (line) r = g = b = 1.0f;
            t[0] = r;
            t[1] = g;
            t[2] = b;
            t[3] = 1.0f;
        }
    }
    out[4 * ((size_t)(height / 3) * width + width / 4)] = 40.0f;
    out[4 * ((size_t)(height / 2) * width + width / 5) + 1] = NAN;
}

/* sRGB-encoded 8-bit value of a linear colour channel, as the Rust frames'
 * to_srgb8: clamped, the sRGB curve, rounded. */
static int srgb8(float c) {
    if (!(c > 0.0f)) c = 0.0f;
    if (c > 1.0f) c = 1.0f;
    const float e = c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
    return (int)(e * 255.0f + 0.5f);
}

/* FXAA (shaders/fxaa/default.spv) against subcone_fxaa_image. FXAA's
 * decisions are thresholds on luma, and the kernel quantises to 8 bits, so
 * the bound is the Rust pass test's: no channel more than FXAA_MAX_STEPS
 * steps apart in 8-bit sRGB. FXAA must change the image (edges blended)
 * from 8x8 pixels up. */
#define FXAA_MAX_STEPS 2
int run_fxaa(Host *h, const char *dir, uint32_t width, uint32_t height) {
    const size_t n = (size_t)width * height;
    int rc = 2;
    float *input = malloc(4 * n * sizeof *input), *gpu = malloc(4 * n * sizeof *gpu),
          *cpu = malloc(4 * n * sizeof *cpu);
    SubconeFxaaParams params;
    SubconeFxaaPassFrame frame;
    if (!input || !gpu || !cpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        goto done;
    }
    post_input(width, height, 0, input);
    if (subcone_fxaa_params_quality(&params) != SUBCONE_STATUS_OK ||
        subcone_fxaa_pass_frame(width, height, &frame) != SUBCONE_STATUS_OK ||
        subcone_fxaa_image(&params, width, height, input, 4 * n, cpu, 4 * n) != SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the FXAA frame: %s",
                 subcone_last_error_message());
        goto done;
    }
    PostPass pass = {"fxaa/default.spv", "fxaa_main", {&params, &frame}, {sizeof params, sizeof frame},
                     {input}, 1};
    double ms = 0.0;
    if (run_post(h, dir, &pass, width, height, gpu, &ms)) goto done;
    int worst = 0;
    size_t differ = 0, filtered = 0;
    for (size_t p = 0; p < n; p++) {
        int pixel = 0, changed = 0;
        for (int c = 0; c < 3; c++) {
            const int d = abs(srgb8(gpu[4 * p + c]) - srgb8(cpu[4 * p + c]));
            if (d > pixel) pixel = d;
            changed |= abs(srgb8(cpu[4 * p + c]) - srgb8(input[4 * p + c])) > 4;
        }
        if (!(gpu[4 * p] == gpu[4 * p] && gpu[4 * p + 1] == gpu[4 * p + 1] && gpu[4 * p + 2] == gpu[4 * p + 2]))
            pixel = 256; /* a NaN from the GPU */
        if (pixel > worst) worst = pixel;
        differ += pixel > 0;
        filtered += changed;
    }
    printf("fxaa  %-26s %ux%u: largest 8-bit sRGB step |gpu-cpu| %d (bound %d), %zu of %zu pixels "
           "differ by a step or more, %zu pixels filtered (binary16 output); one dispatch %.3f ms\n",
           pass.spv, width, height, worst, FXAA_MAX_STEPS, differ, n, filtered, ms);
    /* From 8x8 pixels up the input has edges, and FXAA must blend some. */
    const int edges = width >= 8 && height >= 8;
    rc = worst <= FXAA_MAX_STEPS && (!edges || filtered > n / 100) ? 0 : 1;
    if (rc) snprintf(h->err, sizeof h->err, "%s: outside the tolerance or nothing filtered", pass.spv);
done:
    free(input);
    free(gpu);
    free(cpu);
    return rc;
}

/* TAA (shaders/taa/default.spv) against subcone_taa_resolve, linear and
 * tone-mapped (`exposure`): |gpu − cpu| ≤ TAA_REL·max(|cpu|, TAA_FLOOR) per
 * channel. The kernel is one f32 formula (no thresholds): the Rust pass
 * test bounds it by 1e-4 relative with an f32 output. The output here is
 * binary16, and a device may round a conversion to it toward zero rather
 * than to nearest (this one's errors reach nearly a whole ulp), so its
 * rounding alone may reach one binary16 ulp, 2^-10 relative. */
#define TAA_REL (1.0 / 1024.0 + 1e-4)
#define TAA_FLOOR 1e-3
int run_taa(Host *h, const char *dir, uint32_t width, uint32_t height, float exposure) {
    const size_t n = (size_t)width * height;
    int rc = 2;
    float *current = malloc(4 * n * sizeof(float)), *history = malloc(4 * n * sizeof(float)),
          *velocity = malloc(4 * n * sizeof(float)), *motion = malloc(2 * n * sizeof(float)),
          *gpu = malloc(4 * n * sizeof(float)), *cpu = malloc(4 * n * sizeof(float));
    SubconeTaaParams params;
    SubconeTaaPassOrigin origin = {0, 0, {0, 0}};
    if (!current || !history || !velocity || !motion || !gpu || !cpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        goto done;
    }
    post_input(width, height, 1, current);
    post_input(width, height, 0, history);
    /* Motion of up to two pixels each way (current minus previous), some
     * reprojected off the image near the borders. */
    for (size_t p = 0; p < n; p++) {
        motion[2 * p] = (float)(p % 5) * 0.9f - 1.8f;
        motion[2 * p + 1] = (float)(p % 3) * 1.4f - 1.4f;
        velocity[4 * p] = motion[2 * p];
        velocity[4 * p + 1] = motion[2 * p + 1];
        velocity[4 * p + 2] = velocity[4 * p + 3] = 0.0f;
    }
    if (subcone_taa_params(width, height, 3, exposure, &params) != SUBCONE_STATUS_OK ||
        subcone_taa_resolve(&params, current, 4 * n, motion, 2 * n, history, 4 * n, cpu, 4 * n) !=
            SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the TAA frame: %s",
                 subcone_last_error_message());
        goto done;
    }
    PostPass pass = {"taa/default.spv", "taa_main", {&params, &origin}, {sizeof params, sizeof origin},
                     {current, velocity, history}, 3};
    double ms = 0.0;
    if (run_post(h, dir, &pass, width, height, gpu, &ms)) goto done;
    double worst = 0.0;
    size_t outside = 0;
    for (size_t i = 0; i < 4 * n; i++) {
        if (i % 4 == 3) continue;
        const double c = cpu[i], e = fabs((double)gpu[i] - c) / fmax(fabs(c), TAA_FLOOR);
        if (!(e <= worst)) worst = e; /* a NaN stays the worst */
        outside += !(e <= TAA_REL);
    }
    printf("taa   %-26s %ux%u, %s: largest relative |gpu-cpu| %.3g (bound %.3g), %zu channels "
           "outside (binary16 output); one dispatch %.3f ms\n",
           pass.spv, width, height, exposure > 0.0f ? "tone-mapped" : "linear", worst, TAA_REL, outside,
           ms);
    rc = outside == 0 ? 0 : 1;
    if (rc) snprintf(h->err, sizeof h->err, "%s: outside the tolerance", pass.spv);
done:
    free(current);
    free(history);
    free(velocity);
    free(motion);
    free(gpu);
    free(cpu);
    return rc;
}
