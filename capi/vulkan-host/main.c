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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host.h"

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
