/* What the host's source files share: the host's state, the SRAA frame and
 * its tolerance, the helpers more than one pass calls, and the passes main()
 * runs. The files, by pass family: host_sraa.c (the synthetic SRAA frame,
 * SRAA from storage buffers and from textures), host_sraa_msaa.c (SRAA
 * behind a rasterised 4x MSAA prepass), host_ctss.c (CTSS of the test
 * field), host_post.c (FXAA and TAA); host_common.c (loading SPIR-V, texel
 * conversions); main.c (the order the passes run in). */
#ifndef HOST_H
#define HOST_H

#include <stddef.h>
#include <stdint.h>

#include "subcone.h"
#include "vkc.h"

/* SRAA: |gpu − cpu| ≤ SRAA_REL·max(|gpu|, |cpu|) + SRAA_ABS per channel, the
 * tolerance of the kernels' reconstruction (TOL_RECONSTRUCT in
 * src/vectors/tolerance.rs): both evaluate eq. 1–2 in f32, and the GPU's exp
 * and the order of its adds may differ by a few ulps. */
#define SRAA_REL 1e-4f
#define SRAA_ABS 1e-6f

typedef struct Host {
    VkcContext *vk;
    char err[512];
} Host;

/* host_common.c */

/* A SPIR-V file of the shaders directory. */
int load_spirv(const char *dir, const char *name, uint32_t **words, size_t *bytes, char *err, size_t err_len);

/* `count` colours, `stride` apart in `colors`, as RGBA texels (alpha 1, 4
 * floats each) into `out`. */
void rgba_texels(const SubconeVec3 *colors, size_t count, size_t stride, float *out);

/* `count` binary16 values as floats. */
void halves_to_floats(const void *halves, size_t count, float *out);

/* host_sraa.c: the SRAA frame, shared with host_sraa_msaa.c */

/* The 4x MSAA subsample offsets, SUBPIXEL_OFFSETS. */
extern const float SUB_OFFSETS[4][2];

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

void sraa_data_free(SraaFrameData *d);

/* The frame's arrays, allocated for `width × height` pixels and 1 + `lights`
 * layers. */
int sraa_data_alloc(Host *h, uint32_t width, uint32_t height, uint32_t lights, SraaFrameData *d);

/* The CPU's resolve of the frame (d->cpu) with d->params: layer 0
 * ungated, layer 1 + l gated by light l (eq. 2). */
int sraa_data_resolve(Host *h, SraaFrameData *d);

/* The GPU's resolve (`gpu`, RGBA per pixel) against the CPU's, within
 * `rel` relative + SRAA_ABS per channel. */
int sraa_compare(Host *h, const char *spv, const SraaFrameData *d, const float *gpu, double rel, double ms);

/* The passes, each compared with the CPU: 0 when they agree, 1 when they do
 * not, 2 when the pass cannot run (the reason in h->err). */

/* host_sraa.c */
int run_sraa_buffers(Host *h, const char *dir, const char *spv, uint32_t lights, uint32_t width, uint32_t height);
int run_sraa_packed(Host *h, const char *dir, uint32_t width, uint32_t height);

/* host_sraa_msaa.c */
int run_sraa_msaa(Host *h, const char *dir, const char *prepass_dir, uint32_t lights, uint32_t width, uint32_t height);

/* host_ctss.c */
int run_ctss(Host *h, const char *dir, uint32_t width, uint32_t height, int texture);

/* host_post.c */
int run_fxaa(Host *h, const char *dir, uint32_t width, uint32_t height);
int run_taa(Host *h, const char *dir, uint32_t width, uint32_t height, float exposure);

#endif /* HOST_H */
