/*
 * A C engine running subcone's generated shaders on Vulkan, with no Rust in
 * its build: the SPIR-V of shaders/sraa/buffers*.spv, shaders/sraa/packed.spv,
 * shaders/sraa/msaa*.spv (behind a rasterised 4x MSAA prepass),
 * shaders/ctss/testfield-*.spv, shaders/fxaa/default.spv and
 * shaders/taa/default.spv (storage buffers, sampled textures and storage
 * images), bound as shaders/{sraa,ctss,fxaa,taa}.md list, their uniforms
 * filled through the C ABI (subcone.h), dispatched on the first Vulkan
 * device, and compared with the same frames computed on the CPU by the C
 * ABI (subcone_sraa_resolve, subcone_ctss_trace, subcone_fxaa_image,
 * subcone_taa_resolve).
 *
 *   vulkan-host <shaders directory> <prepass SPIR-V directory> [width height]
 *
 * The second directory holds the host's own shaders, compiled from GLSL by
 * the Makefile: the rasterised MSAA prepass (msaa_prepass.vert, .frag) and
 * the read-back of its samples (msaa_read.comp).
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

/* `count` colours, `stride` apart in `colors`, as RGBA texels (alpha 1, 4
 * floats each) into `out`. */
static void rgba_texels(const SubconeVec3 *colors, size_t count, size_t stride, float *out) {
    for (size_t i = 0; i < count; i++) {
        const SubconeVec3 c = colors[i * stride];
        out[4 * i] = c.x;
        out[4 * i + 1] = c.y;
        out[4 * i + 2] = c.z;
        out[4 * i + 3] = 1.0f;
    }
}

/* The 4x MSAA subsample offsets, SUBPIXEL_OFFSETS. */
static const float SUB_OFFSETS[4][2] = {
    {-0.125f, -0.375f}, {0.375f, -0.125f}, {-0.375f, 0.125f}, {0.125f, 0.375f}};

/* One synthetic SRAA frame and its CPU resolve. */
typedef struct SraaFrameData {
    uint32_t width, height, layers;
    size_t n;
    SubconeSraaParams params;
    SubconeSraaPassUniform uniform;
    SubconeVec3 *colors;     /* n·layers, pixel by pixel */
    SubconeGeometry *shaded; /* n, at the pixel centres */
    SubconeGeometry *subs;   /* 4n, at SUB_OFFSETS */
    uint32_t *shaded_shadow, *sub_shadow;
    SubconeVec3 *cpu; /* n: subcone_sraa_resolve's */
} SraaFrameData;

static void sraa_data_free(SraaFrameData *d) {
    free(d->colors);
    free(d->shaded);
    free(d->subs);
    free(d->shaded_shadow);
    free(d->sub_shadow);
    free(d->cpu);
    memset(d, 0, sizeof *d);
}

/* The frame's arrays, allocated for `width × height` pixels and 1 + `lights`
 * layers. */
static int sraa_data_alloc(Host *h, uint32_t width, uint32_t height, uint32_t lights, SraaFrameData *d) {
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

/* The CPU's resolve of the frame (d->cpu) with d->params: layer 0
 * ungated, layer 1 + l gated by light l (eq. 2). */
static int sraa_data_resolve(Host *h, SraaFrameData *d) {
    const size_t n = d->n;
    const int lights = d->layers > 1;
    int8_t layer_lights[2] = {-1, 0};
    SubconeSraaFrame frame;
    memset(&frame, 0, sizeof frame);
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
        snprintf(h->err, sizeof h->err, "subcone_sraa_resolve: status %d", (int)st);
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
        snprintf(h->err, sizeof h->err, "the C ABI refused the SRAA uniform");
        return 2;
    }
    return sraa_data_resolve(h, d);
}

/* The GPU's resolve (`gpu`, RGBA per pixel) against the CPU's, within
 * `rel` relative + SRAA_ABS per channel. */
static int sraa_compare(Host *h, const char *spv, const SraaFrameData *d, const float *gpu, double rel,
                        double ms) {
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
static int run_sraa_buffers(Host *h, const char *dir, const char *spv, uint32_t lights, uint32_t width,
                            uint32_t height) {
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
static int run_sraa_packed(Host *h, const char *dir, uint32_t width, uint32_t height) {
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

/* An IEEE 754 binary16 value as a float. */
static float half_to_float(uint16_t h) {
    const uint32_t sign = (uint32_t)(h >> 15) << 31;
    const uint32_t exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    float magnitude;
    if (exponent == 0)
        magnitude = ldexpf((float)mantissa, -24);
    else if (exponent == 31)
        magnitude = mantissa ? NAN : INFINITY;
    else
        magnitude = ldexpf((float)(mantissa | 0x400), (int)exponent - 25);
    return sign ? -magnitude : magnitude;
}

/* `count` binary16 values as floats. */
static void halves_to_floats(const void *halves, size_t count, float *out) {
    const uint16_t *h = halves;
    for (size_t i = 0; i < count; i++) out[i] = half_to_float(h[i]);
}

/* CTSS of the test field on the GPU and on the CPU (subcone_ctss_trace per
 * pixel, the same rays); 0 when they agree. `texture`: the variant writing
 * an Rgba16Float storage image (testfield-texture.spv), else the one
 * writing a storage buffer (testfield-buffers.spv). */
static int run_ctss(Host *h, const char *dir, uint32_t width, uint32_t height, int texture) {
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
        snprintf(h->err, sizeof h->err, "the C ABI refused the CTSS camera or parameters");
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
static int run_sraa_msaa(Host *h, const char *dir, const char *prepass_dir, uint32_t lights, uint32_t width,
                         uint32_t height) {
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
static int run_fxaa(Host *h, const char *dir, uint32_t width, uint32_t height) {
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
        snprintf(h->err, sizeof h->err, "the C ABI refused the FXAA frame");
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
static int run_taa(Host *h, const char *dir, uint32_t width, uint32_t height, float exposure) {
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
        snprintf(h->err, sizeof h->err, "the C ABI refused the TAA frame");
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

int main(int argc, char **argv) {
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: %s <shaders directory> <prepass SPIR-V directory> [width height]\n", argv[0]);
        return 2;
    }
    uint32_t width = 96, height = 64;
    if (argc == 5) {
        long w = strtol(argv[3], NULL, 10), hh = strtol(argv[4], NULL, 10);
        if (w < 1 || hh < 1 || w > 4096 || hh > 4096) {
            fprintf(stderr, "vulkan-host: a size in 1..=4096 per side, not %s x %s\n", argv[3],
                    argv[4]);
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
    /* The dispatch times below come from the device's timestamp queries; a
     * software device's do not time its work (the Rust GPU check does not
     * trust lavapipe's either). They are printed, never judged. */
    if (vkc_device_is_cpu(h.vk))
        printf("vulkan-host: a CPU device's timestamps: the dispatch times below are not measurements\n");
    int worst = 0;
    const struct {
        const char *spv;
        uint32_t lights;
    } sraa[2] = {{"sraa/buffers.spv", 0}, {"sraa/buffers-lights1.spv", 1}};
    for (int i = 0; i < 2; i++) {
        int rc = run_sraa_buffers(&h, argv[1], sraa[i].spv, sraa[i].lights, width, height);
        if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
        if (rc > worst) worst = rc;
    }
    int rc = run_sraa_packed(&h, argv[1], width, height);
    if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
    if (rc > worst) worst = rc;
    for (uint32_t lights = 0; lights < 2; lights++) {
        rc = run_sraa_msaa(&h, argv[1], argv[2], lights, width, height);
        if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
        if (rc > worst) worst = rc;
    }
    for (int texture = 0; texture < 2; texture++) {
        rc = run_ctss(&h, argv[1], width, height, texture);
        if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
        if (rc > worst) worst = rc;
    }
    rc = run_fxaa(&h, argv[1], width, height);
    if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
    if (rc > worst) worst = rc;
    for (int tone_mapped = 0; tone_mapped < 2; tone_mapped++) {
        rc = run_taa(&h, argv[1], width, height, tone_mapped ? 0.5f : 0.0f);
        if (rc) fprintf(stderr, "vulkan-host: %s\n", h.err);
        if (rc > worst) worst = rc;
    }
    vkc_destroy(h.vk);
    printf("vulkan-host: %s\n", worst == 0 ? "every pass matches the CPU" : "FAILED");
    return worst;
}
