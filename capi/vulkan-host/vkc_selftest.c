/* vkc's self test: runs selftest.comp (out[i] = in[i] * scale + i) on 1000
 * elements on the default device and checks every output exactly, then checks
 * that bad input is reported as an error rather than crashing.
 *
 * Usage: vkc_selftest <selftest.spv>. Prints "vkc selftest: <device>: ok" and
 * exits 0, or prints the first failure to stderr and exits 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vkc.h"

#define N 1000u
#define LOCAL_SIZE 64u
/* The output buffer is longer than N so the shader's bounds check is tested:
 * the tail must keep its sentinel. */
#define OUT_LEN 1024u
#define SENTINEL -12345.0f

/* std140 layout of selftest.comp's Params block. */
typedef struct Params {
    uint32_t n;
    float scale;
} Params;

/* Inputs are multiples of 1/2 below 400 in magnitude and the scales are
 * short binary fractions, so every product and sum is exact in float: the
 * device's result must equal the host's bit for bit, fused or not. */
static float input(uint32_t i) {
    return (float)i * 0.5f - 100.0f;
}

static int run_once(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, VkcBuffer *params, VkcBuffer *in,
                    VkcBuffer *out, float scale, char *err, size_t err_len) {
    VkcBinding bindings[3];
    Params p;
    float *o = (float *)out->mapped;
    uint32_t i;

    p.n = N;
    p.scale = scale;
    memcpy(params->mapped, &p, sizeof p);
    for (i = 0; i < OUT_LEN; i++) o[i] = SENTINEL;

    memset(bindings, 0, sizeof bindings);
    bindings[0].binding = 0;
    bindings[0].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    bindings[0].buffer = params;
    bindings[1].binding = 1;
    bindings[1].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[1].buffer = in;
    bindings[2].binding = 2;
    bindings[2].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[2].buffer = out;
    if (vkc_dispatch(ctx, spirv, spirv_bytes, "main", bindings, 3, (N + LOCAL_SIZE - 1) / LOCAL_SIZE, 1, 1, err,
                     err_len) != 0)
        return 1;

    for (i = 0; i < OUT_LEN; i++) {
        float want = i < N ? input(i) * scale + (float)i : SENTINEL;
        if (o[i] != want) {
            snprintf(err, err_len, "scale %g: out[%u] = %.9g, expected %.9g", (double)scale, (unsigned)i,
                     (double)o[i], (double)want);
            return 1;
        }
    }
    return 0;
}

/* Each call must fail and say why; `what` names the case in the report. */
static int expect_failure(int rc, const char *what, const char *msg, char *err, size_t err_len) {
    if (rc == 0) {
        snprintf(err, err_len, "%s was accepted", what);
        return 1;
    }
    if (msg[0] == '\0') {
        snprintf(err, err_len, "%s failed without a message", what);
        return 1;
    }
    return 0;
}

/* The attachments and draws vkc refuses: a copy of a multisampled
 * attachment, a draw without a draw, a draw whose attachments differ in
 * sample count. Each attachment made is destroyed. */
static int bad_draws(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, VkcBuffer *in, char *err,
                     size_t err_len) {
    char msg[256];
    VkcImage color, depth;
    VkcDraw draw;
    int rc = 1;
    memset(&color, 0, sizeof color);
    memset(&depth, 0, sizeof depth);
    if (vkc_image_create_attachment(ctx, 4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLE_COUNT_4_BIT, &color, err,
                                    err_len) ||
        vkc_image_create_attachment(ctx, 4, 4, VK_FORMAT_D32_SFLOAT, VK_SAMPLE_COUNT_1_BIT, &depth, err, err_len))
        goto done;
    msg[0] = '\0';
    if (expect_failure(vkc_image_copy(ctx, &color, in, 0, msg, sizeof msg), "a copy of a multisampled attachment",
                       msg, err, err_len))
        goto done;
    msg[0] = '\0';
    if (expect_failure(vkc_draw(ctx, NULL, msg, sizeof msg), "a NULL draw", msg, err, err_len)) goto done;
    memset(&draw, 0, sizeof draw);
    /* Any SPIR-V passes the argument checks; the attachments do not. */
    draw.vertex_spirv = draw.fragment_spirv = spirv;
    draw.vertex_bytes = draw.fragment_bytes = spirv_bytes;
    draw.vertex_count = 3;
    draw.color = &color;
    draw.depth = &depth;
    draw.depth_compare = VK_COMPARE_OP_ALWAYS;
    msg[0] = '\0';
    if (expect_failure(vkc_draw(ctx, &draw, msg, sizeof msg), "attachments of different sample counts", msg, err,
                       err_len))
        goto done;
    draw.depth = &color;
    msg[0] = '\0';
    if (expect_failure(vkc_draw(ctx, &draw, msg, sizeof msg), "a colour image as the depth attachment", msg, err,
                       err_len))
        goto done;
    rc = 0;
done:
    vkc_image_destroy(ctx, &color);
    vkc_image_destroy(ctx, &depth);
    return rc;
}

static int bad_input(VkcContext *ctx, const uint32_t *spirv, size_t spirv_bytes, VkcBuffer *params, VkcBuffer *in,
                     char *err, size_t err_len) {
    char msg[256];
    uint32_t *words = NULL;
    size_t bytes = 0;
    VkcBuffer empty;
    VkcBinding b[2];
    uint32_t not_spirv[8] = {0};

    memset(b, 0, sizeof b);
    b[0].binding = 0;
    b[0].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    b[0].buffer = params;
    b[1].binding = 0;
    b[1].type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b[1].buffer = in;

    msg[0] = '\0';
    if (expect_failure(vkc_read_file("/nonexistent/selftest.spv", &words, &bytes, msg, sizeof msg),
                       "reading a missing file", msg, err, err_len))
        return 1;
    msg[0] = '\0';
    if (expect_failure(vkc_buffer_create(ctx, 0, &empty, msg, sizeof msg), "a zero-sized buffer", msg, err,
                       err_len))
        return 1;
    vkc_buffer_destroy(ctx, &empty);
    msg[0] = '\0';
    if (expect_failure(vkc_dispatch(ctx, spirv, spirv_bytes - 2, "main", b, 1, 1, 1, 1, msg, sizeof msg),
                       "SPIR-V of a size not a multiple of 4", msg, err, err_len))
        return 1;
    msg[0] = '\0';
    if (expect_failure(vkc_dispatch(ctx, not_spirv, sizeof not_spirv, "main", b, 1, 1, 1, 1, msg, sizeof msg),
                       "words without the SPIR-V magic", msg, err, err_len))
        return 1;
    msg[0] = '\0';
    if (expect_failure(vkc_dispatch(ctx, spirv, spirv_bytes, "main", b, 2, 1, 1, 1, msg, sizeof msg),
                       "a binding number used twice", msg, err, err_len))
        return 1;
    b[1].binding = 1;
    b[1].type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    msg[0] = '\0';
    if (expect_failure(vkc_dispatch(ctx, spirv, spirv_bytes, "main", b, 2, 1, 1, 1, msg, sizeof msg),
                       "an image binding without an image", msg, err, err_len))
        return 1;
    b[1].type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    msg[0] = '\0';
    if (expect_failure(vkc_dispatch(ctx, spirv, spirv_bytes, "main", b, 2, 1, 1, 1, msg, sizeof msg),
                       "an unsupported descriptor type", msg, err, err_len))
        return 1;
    return bad_draws(ctx, spirv, spirv_bytes, in, err, err_len);
}

int main(int argc, char **argv) {
    char err[512];
    VkcContext *ctx = NULL;
    VkcBuffer params, in, out;
    uint32_t *spirv = NULL;
    size_t spirv_bytes = 0;
    uint32_t i;
    double ms;
    int rc = 1;

    memset(&params, 0, sizeof params);
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    err[0] = '\0';

    if (argc != 2) {
        fprintf(stderr, "usage: %s <selftest.spv>\n", argc > 0 ? argv[0] : "vkc_selftest");
        return 2;
    }
    if (vkc_read_file(argv[1], &spirv, &spirv_bytes, err, sizeof err) != 0) goto done;
    if (vkc_create(&ctx, err, sizeof err) != 0) goto done;
    if (vkc_buffer_create(ctx, 16, &params, err, sizeof err) != 0) goto done;
    if (vkc_buffer_create(ctx, N * sizeof(float), &in, err, sizeof err) != 0) goto done;
    if (vkc_buffer_create(ctx, OUT_LEN * sizeof(float), &out, err, sizeof err) != 0) goto done;
    for (i = 0; i < N; i++) ((float *)in.mapped)[i] = input(i);

    /* Twice, so per-dispatch objects are shown to be rebuilt cleanly. */
    if (run_once(ctx, spirv, spirv_bytes, &params, &in, &out, 1.5f, err, sizeof err) != 0) goto done;
    ms = vkc_last_dispatch_ms(ctx);
    if (run_once(ctx, spirv, spirv_bytes, &params, &in, &out, -0.25f, err, sizeof err) != 0) goto done;
    if (bad_input(ctx, spirv, spirv_bytes, &params, &in, err, sizeof err) != 0) goto done;

    if (ms >= 0.0)
        printf("vkc selftest: dispatch of %u invocations took %.3f ms (timestamp queries)\n", N, ms);
    else
        printf("vkc selftest: the queue has no timestamp support\n");
    printf("vkc selftest: %s: ok\n", vkc_device_name(ctx));
    rc = 0;
done:
    if (rc != 0) fprintf(stderr, "vkc selftest: FAILED: %s\n", err);
    vkc_buffer_destroy(ctx, &out);
    vkc_buffer_destroy(ctx, &in);
    vkc_buffer_destroy(ctx, &params);
    vkc_destroy(ctx);
    free(spirv);
    return rc;
}
