/* CTSS of the test field, on the GPU and on the CPU. */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* CTSS: a hit group may close one step earlier on one side where a distance
 * is an ulp from a threshold, so a few pixels may differ much; as the
 * backends' frame tolerance does, bound the mean tightly and the 99th
 * percentile more loosely (per pixel, the largest channel difference). */
#define CTSS_MEAN 1e-3
#define CTSS_P99 1e-2
/* subcone's default cone coverage in pixels (subcone_kernels::ctss::CONE_COVERAGE). */
#define CONE_COVERAGE 0.6f

/* The test field of shaders/ctss/testfield-*: subcone_passes'
 * standalone::TEST_FIELD_WGSL, written again in C. */
static SubconeFieldSample test_field(void *user, SubconeVec3 p) {
    (void)user;
    float dx = p.x, dy = p.y, dz = p.z - 4.0f;
    float sphere = sqrtf(dx * dx + dy * dy + dz * dz) - 1.0f;
    float ground = p.y + 1.0f;
    SubconeFieldSample s;
    if (sphere < ground) {
        s.distance = sphere;
        s.step = sphere;
        s.object = 0;
    } else {
        s.distance = ground;
        s.step = ground;
        s.object = 1;
    }
    return s;
}

static SubconeVec3 test_shade(void *user, SubconeVec3 p, SubconeVec3 n, SubconeVec3 dir) {
    (void)user;
    (void)dir;
    float lambert = fmaxf(n.x * 0.48f + n.y * 0.8f + n.z * -0.36f, 0.0f);
    SubconeVec3 albedo = {0.9f, 0.3f, 0.2f};
    if (p.y < -0.999f) {
        albedo.x = 0.7f;
        albedo.y = 0.7f;
        albedo.z = 0.7f;
    }
    float k = 0.15f + lambert;
    SubconeVec3 c = {albedo.x * k, albedo.y * k, albedo.z * k};
    return c;
}

static int compare_floats(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* CTSS of the test field on the GPU and on the CPU (subcone_ctss_trace per
 * pixel, the same rays); 0 when they agree. `texture`: the variant writing
 * an Rgba16Float storage image (testfield-texture.spv), else the one
 * writing a storage buffer (testfield-buffers.spv). */
int run_ctss(Host *h, const char *dir, uint32_t width, uint32_t height, int texture) {
    const size_t n = (size_t)width * height;
    const char *spv = texture ? "ctss/testfield-texture.spv" : "ctss/testfield-buffers.spv";
    int rc = 2;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcBuffer bufs[3];
    VkcImage out_image;
    int made = 0, have_image = 0;
    double *diffs = malloc(n * sizeof *diffs);
    float *gpu = malloc(4 * n * sizeof *gpu);
    memset(&out_image, 0, sizeof out_image);
    if (!diffs || !gpu) {
        snprintf(h->err, sizeof h->err, "out of memory");
        goto done;
    }
    if (load_spirv(dir, spv, &code, &code_bytes, h->err, sizeof h->err)) goto done;

    const float fov_y = 0.8f;
    SubconeVec3 eye = {0.0f, 0.3f, 0.0f}, forward = {0.0f, -0.1f, 1.0f}, up = {0.0f, 1.0f, 0.0f};
    SubconeVec3 background = {0.1f, 0.2f, 0.4f};
    SubconeCtssPassUniform uniform;
    SubconeCtssParams params;
    float tan_theta;
    /* subcone's default cone (CONE_COVERAGE, the circumscribed footprint). */
    if (subcone_ctss_pass_uniform(eye, forward, up, fov_y, width, height, background, &uniform) !=
            SUBCONE_STATUS_OK ||
        subcone_cone_tan_theta(fov_y, height, CONE_COVERAGE, 0, &tan_theta) != SUBCONE_STATUS_OK ||
        subcone_ctss_params_default(tan_theta, &params) != SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the CTSS camera or parameters: %s",
                 subcone_last_error_message());
        goto done;
    }
    params.t_max = 100.0f;
    params.max_steps = 256;

    /* The bindings of shaders/ctss.md: subcone_pass_frame,
     * subcone_pass_params, subcone_pass_output (a vec4<f32> buffer, or an
     * Rgba16Float storage image read back through the third buffer). */
    const VkDeviceSize sizes[3] = {sizeof uniform, sizeof params, n * 16};
    for (int i = 0; i < 3; i++) {
        if (vkc_buffer_create(h->vk, sizes[i], &bufs[i], h->err, sizeof h->err)) goto done;
        made = i + 1;
    }
    memcpy(bufs[0].mapped, &uniform, sizeof uniform);
    memcpy(bufs[1].mapped, &params, sizeof params);
    VkcBinding bindings[3];
    memset(bindings, 0, sizeof bindings);
    for (uint32_t i = 0; i < 3; i++) {
        bindings[i].binding = i;
        bindings[i].type = i < 2 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].buffer = &bufs[i];
    }
    if (texture) {
        if (vkc_image_create(h->vk, width, height, 1, 0, VK_FORMAT_R16G16B16A16_SFLOAT, 8, &out_image, h->err,
                             sizeof h->err))
            goto done;
        have_image = 1;
        bindings[2].type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        bindings[2].buffer = NULL;
        bindings[2].image = &out_image;
    }
    if (vkc_dispatch(h->vk, code, code_bytes, "subcone_pass_ctss_main", bindings, 3, (width + 7) / 8,
                     (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    double ms = vkc_last_dispatch_ms(h->vk);
    if (texture) {
        if (vkc_image_copy(h->vk, &out_image, &bufs[2], 0, h->err, sizeof h->err)) goto done;
        halves_to_floats(bufs[2].mapped, 4 * n, gpu);
    } else {
        memcpy(gpu, bufs[2].mapped, 4 * n * sizeof *gpu);
    }

    const SubconePinholeCamera *cam = &uniform.camera;
    SubconeVec3 origin = {cam->position[0], cam->position[1], cam->position[2]};
    SubconeVec3 up_axis = {cam->up[0], cam->up[1], cam->up[2]};
    double sum = 0.0, max = 0.0;
    for (uint32_t y = 0; y < height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            size_t p = (size_t)y * width + x;
            SubconeVec3 d;
            SubconeCtssResult r;
            if (subcone_pinhole_ray(&uniform, (float)x + 0.5f, (float)y + 0.5f, &d) !=
                    SUBCONE_STATUS_OK ||
                subcone_ctss_trace(&params, origin, d, up_axis, test_field, NULL, test_shade, NULL,
                                   background, &r) != SUBCONE_STATUS_OK) {
                snprintf(h->err, sizeof h->err, "the CPU trace of pixel (%u, %u) failed: %s", x, y,
                         subcone_last_error_message());
                goto done;
            }
            const float cpu[3] = {r.color.x, r.color.y, r.color.z};
            double worst = 0.0;
            for (int c = 0; c < 3; c++) {
                double e = fabs((double)gpu[4 * p + c] - (double)cpu[c]);
                if (!(e <= worst)) worst = e; /* a NaN stays the worst */
            }
            diffs[p] = worst;
            sum += worst;
            if (!(worst <= max)) max = worst;
        }
    }
    qsort(diffs, n, sizeof *diffs, compare_floats);
    double mean = sum / (double)n, p99 = diffs[(size_t)(0.99 * (double)(n - 1))];
    size_t differ = 0;
    for (size_t p = 0; p < n; p++) differ += diffs[p] > 1e-4;
    printf("ctss  %-26s %ux%u: per-pixel max-channel |gpu-cpu| mean %.3g (bound %.0e), "
           "p99 %.3g (bound %.0e), max %.3g, %zu of %zu pixels beyond 1e-4%s; one dispatch %.3f ms\n",
           spv, width, height, mean, CTSS_MEAN, p99, CTSS_P99, max, differ, n,
           texture ? " (binary16 output)" : "", ms);
    rc = (mean <= CTSS_MEAN && p99 <= CTSS_P99) ? 0 : 1;
    if (rc) snprintf(h->err, sizeof h->err, "%s: outside the tolerance", spv);

done:
    if (have_image) vkc_image_destroy(h->vk, &out_image);
    for (int i = 0; i < made; i++) vkc_buffer_destroy(h->vk, &bufs[i]);
    free(code);
    free(diffs);
    free(gpu);
    return rc;
}
