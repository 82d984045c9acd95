/*
 * A C engine running subcone's generated shaders on Vulkan, with no Rust in
 * its build: the SPIR-V of shaders/sraa/buffers*.spv and
 * shaders/ctss/testfield-buffers.spv, bound as shaders/sraa.md and
 * shaders/ctss.md list, their uniforms filled through the C ABI
 * (subcone.h), dispatched on the first Vulkan device, and compared with the
 * same frames computed on the CPU by the C ABI (subcone_sraa_resolve,
 * subcone_ctss_trace).
 *
 *   vulkan-host <shaders directory> [width height]
 *
 * Exit status 0 when every comparison holds, 1 when one fails, 2 when the
 * host cannot run (no Vulkan device, a missing file).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "subcone.h"
#include "vkc.h"

/* SRAA: |gpu − cpu| ≤ SRAA_REL·max(|gpu|, |cpu|) + SRAA_ABS per channel, the
 * tolerance of the kernels' reconstruction (TOL_RECONSTRUCT in
 * src/vectors/tolerance.rs): both evaluate eq. 1–2 in f32, and the GPU's exp
 * and the order of its adds may differ by a few ulps. */
#define SRAA_REL 1e-4f
#define SRAA_ABS 1e-6f
/* CTSS: a hit group may close one step earlier on one side where a distance
 * is an ulp from a threshold, so a few pixels may differ much; as the
 * backends' frame tolerance does, bound the mean tightly and the 99th
 * percentile more loosely (per pixel, the largest channel difference). */
#define CTSS_MEAN 1e-3
#define CTSS_P99 1e-2
/* subcone's default cone coverage in pixels (subcone_kernels::ctss::CONE_COVERAGE). */
#define CONE_COVERAGE 0.6f

typedef struct Host {
    VkcContext *vk;
    char err[512];
} Host;

/* A SPIR-V file of the shaders directory. */
static int load_spirv(const char *dir, const char *name, uint32_t **words, size_t *bytes, char *err,
                      size_t err_len) {
    char path[1024];
    if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int)sizeof path) {
        snprintf(err, err_len, "path too long: %s/%s", dir, name);
        return 1;
    }
    return vkc_read_file(path, words, bytes, err, err_len);
}

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

/* The 4x MSAA subsample offsets, SUBPIXEL_OFFSETS. */
static const float SUB_OFFSETS[4][2] = {
    {-0.125f, -0.375f}, {0.375f, -0.125f}, {-0.375f, 0.125f}, {0.125f, 0.375f}};

/* SRAA of one synthetic frame on the GPU (`spv`, the buffers variant with
 * `lights` lights) and on the CPU; 0 when they agree. */
static int run_sraa(Host *h, const char *dir, const char *spv, uint32_t lights, uint32_t width,
                    uint32_t height) {
    const uint32_t layers = 1 + lights;
    const size_t n = (size_t)width * height;
    int rc = 2;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcBuffer bufs[7];
    int made = 0;
    SubconeVec3 *cpu_colors = malloc(n * layers * sizeof *cpu_colors);
    SubconeVec3 *cpu_out = malloc(n * sizeof *cpu_out);
    SubconeGeometry *shaded = malloc(n * sizeof *shaded);
    SubconeGeometry *subs = malloc(4 * n * sizeof *subs);
    uint32_t *shaded_shadow = malloc(n * sizeof *shaded_shadow);
    uint32_t *sub_shadow = malloc(4 * n * sizeof *sub_shadow);
    if (!cpu_colors || !cpu_out || !shaded || !subs || !shaded_shadow || !sub_shadow) {
        snprintf(h->err, sizeof h->err, "out of memory");
        goto done;
    }
    if (load_spirv(dir, spv, &code, &code_bytes, h->err, sizeof h->err)) goto done;

    /* The frame: geometry at the pixel centres (the tuned preset shades
     * there) and at the subsamples, a colour per layer, shadow bits. */
    uint32_t seed = 12345u;
    for (uint32_t y = 0; y < height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            size_t p = (size_t)y * width + x;
            shaded[p] = geometry_at((float)x + 0.5f, (float)y + 0.5f, width);
            shaded_shadow[p] = next_unit(&seed) < 0.3f ? 1u : 0u;
            for (uint32_t k = 0; k < 4; k++) {
                subs[4 * p + k] = geometry_at((float)x + 0.5f + SUB_OFFSETS[k][0],
                                              (float)y + 0.5f + SUB_OFFSETS[k][1], width);
                sub_shadow[4 * p + k] = next_unit(&seed) < 0.3f ? 1u : 0u;
            }
            for (uint32_t l = 0; l < layers; l++) {
                SubconeVec3 c = {next_unit(&seed), next_unit(&seed), next_unit(&seed)};
                cpu_colors[p * layers + l] = c;
            }
        }
    }

    SubconeSraaParams params;
    SubconeSraaPassUniform uniform;
    if (subcone_sraa_params_default(&params) != SUBCONE_STATUS_OK ||
        subcone_sraa_pass_uniform(&params, width, height, NULL, 0.0f, 0.0f, &uniform) !=
            SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the SRAA uniform");
        goto done;
    }

    /* The bindings of shaders/sraa.md: frame, shaded_geo, sub_geo,
     * [shaded_shadow, sub_shadow,] color, sraa_output. Geometry is the C
     * ABI's SubconeGeometry (16 bytes, the shader's subcone_Geometry),
     * colours vec4<f32>. */
    const VkDeviceSize sizes[7] = {
        sizeof uniform, n * sizeof(SubconeGeometry), 4 * n * sizeof(SubconeGeometry),
        n * sizeof(uint32_t), 4 * n * sizeof(uint32_t), n * layers * 16, n * 16};
    const int order_lit[7] = {0, 1, 2, 3, 4, 5, 6};
    const int order_unlit[5] = {0, 1, 2, 5, 6};
    const int *order = lights ? order_lit : order_unlit;
    const uint32_t count = lights ? 7 : 5;
    for (int i = 0; i < 7; i++) {
        if (vkc_buffer_create(h->vk, sizes[i], &bufs[i], h->err, sizeof h->err)) goto done;
        made = i + 1;
    }
    memcpy(bufs[0].mapped, &uniform, sizeof uniform);
    memcpy(bufs[1].mapped, shaded, n * sizeof *shaded);
    memcpy(bufs[2].mapped, subs, 4 * n * sizeof *subs);
    memcpy(bufs[3].mapped, shaded_shadow, n * sizeof *shaded_shadow);
    memcpy(bufs[4].mapped, sub_shadow, 4 * n * sizeof *sub_shadow);
    float *gpu_colors = bufs[5].mapped;
    for (size_t i = 0; i < n * layers; i++) {
        gpu_colors[4 * i + 0] = cpu_colors[i].x;
        gpu_colors[4 * i + 1] = cpu_colors[i].y;
        gpu_colors[4 * i + 2] = cpu_colors[i].z;
        gpu_colors[4 * i + 3] = 1.0f;
    }
    VkcBinding bindings[7];
    for (uint32_t i = 0; i < count; i++) {
        bindings[i].binding = i;
        bindings[i].type =
            order[i] == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].buffer = &bufs[order[i]];
    }
    if (vkc_dispatch(h->vk, code, code_bytes, "sraa_resolve_main", bindings, count,
                     (width + 7) / 8, (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    double ms = vkc_last_dispatch_ms(h->vk);

    /* The CPU: layer 0 ungated, layer 1 + l gated by light l (eq. 2). */
    int8_t layer_lights[2] = {-1, 0};
    SubconeSraaFrame frame;
    memset(&frame, 0, sizeof frame);
    frame.width = width;
    frame.height = height;
    frame.layers = layers;
    frame.colors = cpu_colors;
    frame.colors_len = n * layers;
    frame.layer_lights = lights ? layer_lights : NULL;
    frame.shaded_geometry = shaded;
    frame.shaded_geometry_len = n;
    frame.shaded_shadow = lights ? shaded_shadow : NULL;
    frame.shaded_shadow_len = lights ? n : 0;
    frame.subsample_geometry = subs;
    frame.subsample_geometry_len = 4 * n;
    frame.subsample_shadow = lights ? sub_shadow : NULL;
    frame.subsample_shadow_len = lights ? 4 * n : 0;
    SubconeStatus st = subcone_sraa_resolve(&params, &frame, cpu_out, n);
    if (st != SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "subcone_sraa_resolve: status %d", (int)st);
        goto done;
    }

    const float *gpu = bufs[6].mapped;
    double max_abs = 0.0, max_rel = 0.0;
    size_t outside = 0;
    for (size_t p = 0; p < n; p++) {
        const float cpu[3] = {cpu_out[p].x, cpu_out[p].y, cpu_out[p].z};
        for (int c = 0; c < 3; c++) {
            float a = gpu[4 * p + c], b = cpu[c];
            float d = fabsf(a - b);
            float scale = fmaxf(fabsf(a), fabsf(b));
            if (!(d <= SRAA_REL * scale + SRAA_ABS)) outside++;
            if (d > max_abs) max_abs = d;
            if (scale > 0.0f && d / scale > max_rel) max_rel = d / scale;
        }
    }
    printf("sraa  %-22s %ux%u, %u layer(s): max |gpu-cpu| %.3g, max relative %.3g, "
           "%zu of %zu channels outside %.0e relative + %.0e; GPU %.3f ms\n",
           spv, width, height, layers, max_abs, max_rel, outside, 3 * n, (double)SRAA_REL,
           (double)SRAA_ABS, ms);
    rc = outside == 0 ? 0 : 1;
    if (rc) snprintf(h->err, sizeof h->err, "%s: %zu channels outside the tolerance", spv, outside);

done:
    for (int i = 0; i < made; i++) vkc_buffer_destroy(h->vk, &bufs[i]);
    free(code);
    free(cpu_colors);
    free(cpu_out);
    free(shaded);
    free(subs);
    free(shaded_shadow);
    free(sub_shadow);
    return rc;
}

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

/* CTSS of the test field on the GPU (testfield-buffers.spv) and on the CPU
 * (subcone_ctss_trace per pixel, the same rays); 0 when they agree. */
static int run_ctss(Host *h, const char *dir, uint32_t width, uint32_t height) {
    const size_t n = (size_t)width * height;
    const char *spv = "ctss/testfield-buffers.spv";
    int rc = 2;
    uint32_t *code = NULL;
    size_t code_bytes = 0;
    VkcBuffer bufs[3];
    int made = 0;
    double *diffs = malloc(n * sizeof *diffs);
    if (!diffs) {
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
    /* subcone's default cone (ctss::CONE_COVERAGE, the circumscribed footprint). */
    if (subcone_ctss_pass_uniform(eye, forward, up, fov_y, width, height, background, &uniform) !=
            SUBCONE_STATUS_OK ||
        subcone_cone_tan_theta(fov_y, height, CONE_COVERAGE, 0, &tan_theta) != SUBCONE_STATUS_OK ||
        subcone_ctss_params_default(tan_theta, &params) != SUBCONE_STATUS_OK) {
        snprintf(h->err, sizeof h->err, "the C ABI refused the CTSS camera or parameters");
        goto done;
    }
    params.t_max = 100.0f;
    params.max_steps = 256;

    /* The bindings of shaders/ctss.md: subcone_pass_frame,
     * subcone_pass_params, subcone_pass_output (vec4<f32> per pixel). */
    const VkDeviceSize sizes[3] = {sizeof uniform, sizeof params, n * 16};
    for (int i = 0; i < 3; i++) {
        if (vkc_buffer_create(h->vk, sizes[i], &bufs[i], h->err, sizeof h->err)) goto done;
        made = i + 1;
    }
    memcpy(bufs[0].mapped, &uniform, sizeof uniform);
    memcpy(bufs[1].mapped, &params, sizeof params);
    VkcBinding bindings[3] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bufs[0]},
                              {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bufs[1]},
                              {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bufs[2]}};
    if (vkc_dispatch(h->vk, code, code_bytes, "subcone_pass_ctss_main", bindings, 3,
                     (width + 7) / 8, (height + 7) / 8, 1, h->err, sizeof h->err))
        goto done;
    double ms = vkc_last_dispatch_ms(h->vk);

    const float *gpu = bufs[2].mapped;
    SubconeVec3 origin = {uniform.position[0], uniform.position[1], uniform.position[2]};
    SubconeVec3 up_axis = {uniform.up[0], uniform.up[1], uniform.up[2]};
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
                snprintf(h->err, sizeof h->err, "the CPU trace of pixel (%u, %u) failed", x, y);
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
    printf("ctss  %-22s %ux%u: per-pixel max-channel |gpu-cpu| mean %.3g (bound %.0e), "
           "p99 %.3g (bound %.0e), max %.3g, %zu of %zu pixels beyond 1e-4; GPU %.3f ms\n",
           spv, width, height, mean, CTSS_MEAN, p99, CTSS_P99, max, differ, n, ms);
    rc = (mean <= CTSS_MEAN && p99 <= CTSS_P99) ? 0 : 1;
    if (rc) snprintf(h->err, sizeof h->err, "%s: outside the tolerance", spv);

done:
    for (int i = 0; i < made; i++) vkc_buffer_destroy(h->vk, &bufs[i]);
    free(code);
    free(diffs);
    return rc;
}

int main(int argc, char **argv) {
    if (argc != 2 && argc != 4) {
        fprintf(stderr, "usage: %s <shaders directory> [width height]\n", argv[0]);
        return 2;
    }
    uint32_t width = 96, height = 64;
    if (argc == 4) {
        long w = strtol(argv[2], NULL, 10), hh = strtol(argv[3], NULL, 10);
        if (w < 1 || hh < 1 || w > 4096 || hh > 4096) {
            fprintf(stderr, "vulkan-host: a size in 1..=4096 per side, not %s x %s\n", argv[2],
                    argv[3]);
            return 2;
        }
        width = (uint32_t)w;
        height = (uint32_t)hh;
    }
    if (subcone_version() !=
        (SUBCONE_VERSION_MAJOR << 16 | SUBCONE_VERSION_MINOR << 8 | SUBCONE_VERSION_PATCH)) {
        fprintf(stderr, "vulkan-host: the library's version is not the header's\n");
        return 2;
    }
    Host h;
    memset(&h, 0, sizeof h);
    if (vkc_create(&h.vk, h.err, sizeof h.err)) {
        fprintf(stderr, "vulkan-host: %s\n", h.err);
        return 2;
    }
    printf("vulkan-host: %s%s\n", vkc_device_name(h.vk),
           vkc_device_is_cpu(h.vk) ? " (a CPU device)" : "");
    int worst = 0;
    const struct {
        const char *spv;
        uint32_t lights;
    } sraa[2] = {{"sraa/buffers.spv", 0}, {"sraa/buffers-lights1.spv", 1}};
    for (int i = 0; i < 2; i++) {
        int rc = run_sraa(&h, argv[1], sraa[i].spv, sraa[i].lights, width, height);
        if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
        if (rc > worst) worst = rc;
    }
    int rc = run_ctss(&h, argv[1], width, height);
    if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
    if (rc > worst) worst = rc;
    vkc_destroy(h.vk);
    printf("vulkan-host: %s\n", worst == 0 ? "every pass matches the CPU" : "FAILED");
    return worst;
}
