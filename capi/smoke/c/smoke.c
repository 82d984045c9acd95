/* The C smoke test: every function of include/subcone.h called from C with
 * fixed inputs (the Rust test compares the results with the kernels) and
 * with bad input (each must give its documented error code). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "subcone.h"

typedef struct SmokeOutputs {
    uint32_t version;
    float bilateral;
    float shadow_same;
    float shadow_differ;
    float reconstruction;
    float albedo;
    SubconeVec3 resolved;
    float tan_theta;
    float radius;
    float occlusion;
    float advanced;
    float entry;
    float hard_hit;
    float projected[2];
    uint32_t mask;
    float sample_weight;
    SubconeVec3 sraa[6];
    SubconeCtssResult ctss;
} SmokeOutputs;

int subcone_smoke_run(SmokeOutputs *out, char *log, size_t log_len);

static SubconeVec3 v3(float x, float y, float z) {
    SubconeVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

/* A unit sphere at (0, 0, 5), object 3. */
static SubconeFieldSample sphere(void *user, SubconeVec3 p) {
    SubconeFieldSample s;
    float dx = p.x - 0.0f, dy = p.y - 0.0f, dz = p.z - 5.0f;
    (void)user;
    s.distance = sqrtf(dx * dx + dy * dy + dz * dz) - 1.0f;
    s.step = s.distance;
    s.object = 3;
    return s;
}

/* The normal as a colour; counts the calls through `user`. */
static SubconeVec3 shade(void *user, SubconeVec3 p, SubconeVec3 n, SubconeVec3 dir) {
    (void)p;
    (void)dir;
    *(int *)user += 1;
    return v3(n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f);
}

/* The failures so far and where they are described (no global state). */
typedef struct Check {
    int failures;
    char *at;
    size_t left;
} Check;

static void expect(Check *c, SubconeStatus got, SubconeStatus want, const char *what) {
    if (got != want) {
        int n = snprintf(c->at, c->left, "%s: status %d, expected %d\n", what, (int)got, (int)want);
        if (n > 0 && (size_t)n < c->left) {
            c->at += n;
            c->left -= (size_t)n;
        }
        c->failures++;
    }
}

#define OK(call) expect(check, (call), SUBCONE_STATUS_OK, #call)

/* The last error message holds `part` (or, for NULL, is empty). */
static void expect_message(Check *c, const char *part, const char *what) {
    const char *m = subcone_last_error_message();
    if (m == NULL || (part == NULL ? m[0] != 0 : strstr(m, part) == NULL)) {
        int n = snprintf(c->at, c->left, "%s: last error message \"%s\", expected %s%s\n", what,
                         m == NULL ? "(NULL)" : m, part == NULL ? "none" : "one naming ", part == NULL ? "" : part);
        if (n > 0 && (size_t)n < c->left) {
            c->at += n;
            c->left -= (size_t)n;
        }
        c->failures++;
    }
}

/* What the phases share: the SRAA parameters, two geometries and four
 * colours, the 3×2 frame and the arrays it points into, the CTSS
 * parameters, and the shade callback's count. */
typedef struct SmokeInputs {
    SubconeSraaParams params;
    SubconeGeometry gi, gj;
    SubconeVec3 colours4[4];
    SubconeCtssParams ctss;
    SubconeSraaFrame frame;
    SubconeVec3 colors[12];
    SubconeGeometry geometry[6], subgeometry[24];
    uint32_t shadow[6], subshadow[24];
    int8_t gates[2];
    int shaded;
} SmokeInputs;

/* SRAA weights (eq. 1, eq. 2, the spatial term) and one pixel's resolve. */
static void smoke_sraa_weights(Check *check, SmokeInputs *in, SmokeOutputs *o) {
    SubconeSraaParams params;
    SubconeGeometry gi, gj;
    SubconeVec3 colours4[4];
    OK(subcone_sraa_params_default(&params));
    gi.normal = v3(0.0f, 0.0f, 1.0f);
    gi.depth = 2.0f;
    gj.normal = v3(0.6f, 0.0f, 0.8f);
    gj.depth = 2.1f;
    OK(subcone_bilateral_weight(&params, &gi, &gj, &o->bilateral));
    OK(subcone_shadow_gated_weight(&params, &gi, &gj, 1, 1, &o->shadow_same));
    OK(subcone_shadow_gated_weight(&params, &gi, &gj, 0, 1, &o->shadow_differ));
    OK(subcone_reconstruction_weight(&params, &gi, &gj, 0.5f, &o->reconstruction));
    OK(subcone_albedo_difference(v3(0.2f, 0.4f, 0.6f), v3(0.3f, 0.1f, 0.6f), &o->albedo));
    colours4[0] = v3(1, 0, 0);
    colours4[1] = v3(0, 1, 0);
    colours4[2] = v3(0, 0, 1);
    colours4[3] = v3(1, 1, 1);
    OK(subcone_resolve_pixel(colours4, &o->resolved));
    in->params = params;
    in->gi = gi;
    in->gj = gj;
    memcpy(in->colours4, colours4, sizeof colours4);
}

/* The CTSS kernels, each on fixed inputs. */
static void smoke_ctss_kernels(Check *check, SmokeOutputs *o) {
    OK(subcone_cone_tan_theta(0.8f, 720, 0.6f, 0, &o->tan_theta));
    OK(subcone_cone_radius(3.0f, o->tan_theta, &o->radius));
    OK(subcone_cone_occlusion(0.001f, o->radius, &o->occlusion));
    OK(subcone_advance(3.0f, 0.001f, 0.5f, o->radius, &o->advanced));
    OK(subcone_backtrace_cone_entry(3.0f, o->tan_theta, &o->entry));
    OK(subcone_backtrace_hard_hit(2.9f, 0.05f, 3.0f, &o->hard_hit));
    OK(subcone_project_normal(v3(0.3f, 0.4f, 0.5f), v3(1, 0, 0), v3(0, 1, 0), o->projected));
    OK(subcone_visibility_mask(0.3f, 0.6f, 0.8f, 0, &o->mask));
    OK(subcone_sample_weight(0x0000FFFFu, 0, 0.0f, &o->sample_weight));
}

/* A 3×2 SRAA frame, two layers (ungated, gated by light 0), and its
 * resolve. */
static void smoke_sraa_frame(Check *check, SmokeInputs *in, SmokeOutputs *o) {
    const SubconeSraaParams params = in->params;
    SubconeSraaFrame frame;
    int j, k;
    for (j = 0; j < 6; j++) {
        in->colors[2 * j] = v3((float)(j + 1) * 0.1f, 0.0f, 0.25f);
        in->colors[2 * j + 1] = v3((float)(j + 1) * 0.1f, 0.5f, 0.25f);
        in->geometry[j].normal = v3(0, 0, 1);
        in->geometry[j].depth = 2.0f + (float)(j % 3) * 0.5f;
        in->shadow[j] = (uint32_t)(j % 2);
        for (k = 0; k < 4; k++) {
            in->subgeometry[4 * j + k].normal = v3(0, 0, 1);
            in->subgeometry[4 * j + k].depth = 2.0f + (float)(j % 3) * 0.5f + (float)k * 0.01f;
            in->subshadow[4 * j + k] = (uint32_t)((j + k) % 2);
        }
    }
    memset(&frame, 0, sizeof frame);
    frame.size = sizeof frame;
    frame.width = 3;
    frame.height = 2;
    frame.layers = 2;
    frame.colors = in->colors;
    frame.colors_len = 12;
    frame.layer_lights = in->gates;
    frame.shaded_geometry = in->geometry;
    frame.shaded_geometry_len = 6;
    frame.shaded_shadow = in->shadow;
    frame.shaded_shadow_len = 6;
    frame.subsample_geometry = in->subgeometry;
    frame.subsample_geometry_len = 24;
    frame.subsample_shadow = in->subshadow;
    frame.subsample_shadow_len = 24;
    OK(subcone_sraa_resolve(&params, &frame, o->sraa, 6));
    expect_message(check, NULL, "after a success");
    in->frame = frame;
}

/* One CTSS trace through C callbacks: a ray past the sphere's edge. */
static void smoke_ctss_trace(Check *check, SmokeInputs *in, SmokeOutputs *o) {
    SubconeCtssParams ctss;
    int shaded = in->shaded;
    OK(subcone_ctss_params_default(o->tan_theta, &ctss));
    OK(subcone_ctss_trace(&ctss, v3(0, 0, 0), v3(0.2041241f, 0.0f, 1.0f), v3(0, 1, 0), sphere, NULL, shade,
                          &shaded, v3(0.1f, 0.2f, 0.3f), &o->ctss));
    if ((uint32_t)shaded != o->ctss.samples) {
        expect(check, SUBCONE_STATUS_PANIC, SUBCONE_STATUS_OK, "shade callback calls differ from samples");
    }
    in->ctss = ctss;
    in->shaded = shaded;
}

/* Bad input to the weights and kernels: error codes, never a crash. */
static void smoke_bad_kernels(Check *check, SmokeInputs *in) {
    const SubconeSraaParams params = in->params;
    const SubconeGeometry gi = in->gi, gj = in->gj;
    SubconeSraaParams bad;
    SubconeCtssParams ctss = in->ctss;
    float f;
    uint32_t u;
    expect(check, subcone_bilateral_weight(&params, &gi, NULL, &f), SUBCONE_STATUS_NULL_POINTER, "null gj");
    expect(check, subcone_bilateral_weight(&params, &gi, &gj, NULL), SUBCONE_STATUS_NULL_POINTER, "null out");
    expect(check, subcone_bilateral_weight(NULL, &gi, &gj, &f), SUBCONE_STATUS_NULL_POINTER, "null params");
    bad = params;
    bad.sigma_z = NAN;
    expect(check, subcone_bilateral_weight(&bad, &gi, &gj, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "NaN sigma_z");
    bad = params;
    bad.sigma_s = INFINITY;
    expect(check, subcone_shadow_gated_weight(&bad, &gi, &gj, 0, 0, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "inf sigma_s");
    expect(check, subcone_cone_tan_theta(NAN, 720, 1.0f, 0, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "NaN fov");
    expect(check, subcone_cone_tan_theta(0.8f, 0, 1.0f, 0, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "zero height");
    expect(check, subcone_cone_tan_theta(0.8f, 720, 1.0f, 9, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "footprint 9");
    expect(check, subcone_visibility_mask(0.5f, 1, 0, 7, &u), SUBCONE_STATUS_INVALID_ARGUMENT, "placement 7");
    expect(check, subcone_sample_weight(1, 5, 0.0f, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "weighting 5");
    expect(check, subcone_sample_weight(1, 0, NAN, &f), SUBCONE_STATUS_INVALID_ARGUMENT, "NaN min weight");
    expect(check, subcone_resolve_pixel(NULL, &in->colours4[0]), SUBCONE_STATUS_NULL_POINTER, "null subsamples");
    expect(check, subcone_ctss_params_default(-1.0f, &ctss), SUBCONE_STATUS_INVALID_ARGUMENT, "negative tan");
    expect(check, subcone_sraa_params_paper(NULL), SUBCONE_STATUS_NULL_POINTER, "null params out");
    in->ctss = ctss;
}

/* Bad frames and outputs to the SRAA resolve. */
static void smoke_bad_frame(Check *check, const SmokeInputs *in, SmokeOutputs *o) {
    const SubconeSraaParams params = in->params;
    const SubconeSraaFrame frame = in->frame;
    SubconeSraaFrame b = frame;
    b.width = 0;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_SIZE_MISMATCH, "zero width");
    b = frame;
    b.colors_len = 11;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_SIZE_MISMATCH, "short colours");
    b = frame;
    b.colors = NULL;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_NULL_POINTER, "null colours");
    expect_message(check, "frame->colors", "null colours");
    b = frame;
    b.layers = 17;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_SIZE_MISMATCH, "17 layers");
    expect_message(check, "frame->layers is 17", "17 layers");
    b = frame;
    b.size = (uint32_t)sizeof frame - 8;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_STRUCT_SIZE, "short frame size");
    expect_message(check, "sizeof(SubconeSraaFrame)", "short frame size");
    b.size = 0;
    expect(check, subcone_sraa_resolve(&params, &b, o->sraa, 6), SUBCONE_STATUS_STRUCT_SIZE, "zero frame size");
    expect(check, subcone_sraa_resolve(&params, &frame, o->sraa, 5), SUBCONE_STATUS_SIZE_MISMATCH, "short out");
    expect(check, subcone_sraa_resolve(&params, &frame, NULL, 6), SUBCONE_STATUS_NULL_POINTER, "null out");
    expect(check, subcone_sraa_resolve(&params, NULL, o->sraa, 6), SUBCONE_STATUS_NULL_POINTER, "null frame");
}

/* Bad rays, callbacks and parameters to the CTSS trace. */
static void smoke_bad_trace(Check *check, SmokeInputs *in) {
    const SubconeCtssParams ctss = in->ctss;
    SubconeCtssResult r;
    int shaded = in->shaded;
    expect(check, subcone_ctss_trace(&ctss, v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), NULL, NULL, shade, &shaded,
                              v3(0, 0, 0), &r),
           SUBCONE_STATUS_NULL_POINTER, "null distance");
    expect(check, subcone_ctss_trace(&ctss, v3(NAN, 0, 0), v3(0, 0, 1), v3(0, 1, 0), sphere, NULL, shade, &shaded,
                              v3(0, 0, 0), &r),
           SUBCONE_STATUS_INVALID_ARGUMENT, "NaN origin");
    expect(check, subcone_ctss_trace(&ctss, v3(0, 0, 0), v3(0, 0, 0), v3(0, 1, 0), sphere, NULL, shade, &shaded,
                              v3(0, 0, 0), &r),
           SUBCONE_STATUS_INVALID_ARGUMENT, "zero direction");
    {
        SubconeCtssParams b = ctss;
        b.t_max = NAN;
        expect(check, subcone_ctss_trace(&b, v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), sphere, NULL, shade, &shaded,
                                  v3(0, 0, 0), &r),
               SUBCONE_STATUS_INVALID_ARGUMENT, "NaN t_max");
    }
    in->shaded = shaded;
}

int subcone_smoke_run(SmokeOutputs *o, char *log, size_t log_len) {
    SmokeInputs in;
    Check check;
    check.failures = 0;
    check.at = log;
    check.left = log_len;
    if (log_len > 0) log[0] = 0;
    memset(o, 0, sizeof *o);
    memset(&in, 0, sizeof in);
    in.gates[0] = -1;
    in.gates[1] = 0;

    o->version = subcone_version();
    if (o->version != ((SUBCONE_VERSION_MAJOR << 16) | (SUBCONE_VERSION_MINOR << 8) | SUBCONE_VERSION_PATCH)) {
        expect(&check, SUBCONE_STATUS_PANIC, SUBCONE_STATUS_OK, "version macros differ from subcone_version()");
    }
    smoke_sraa_weights(&check, &in, o);
    smoke_ctss_kernels(&check, o);
    smoke_sraa_frame(&check, &in, o);
    smoke_ctss_trace(&check, &in, o);
    /* Bad input: error codes, never a crash. */
    smoke_bad_kernels(&check, &in);
    smoke_bad_frame(&check, &in, o);
    smoke_bad_trace(&check, &in);
    return check.failures;
}
