/* Checks the C ABI against the golden vectors (`subcone vectors --out DIR`),
 * the way a port would: each file's cases read line by line, each case's
 * inputs passed to the C function, its outputs compared within the file's
 * tolerance. Where the C ABI refuses a case's parameters (a non-finite σ,
 * an out-of-range code), the documented error code must be the answer. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "subcone.h"

typedef struct VectorTally {
    uint32_t files;
    uint32_t cases;
    uint32_t refused;
    uint32_t exact;
    uint32_t failures;
} VectorTally;

int subcone_smoke_vectors(const char *dir, VectorTally *tally, char *log, size_t log_len);

#define MAX_VALUES 64

typedef union {
    uint32_t u;
    float f;
} Bits;

static float f32_of(uint32_t u) {
    Bits b;
    b.u = u;
    return b.f;
}

static uint32_t bits_of(float f) {
    Bits b;
    b.f = f;
    return b.u;
}

static SubconeVec3 vec_at(const uint32_t *in, int i) {
    SubconeVec3 v;
    v.x = f32_of(in[i]);
    v.y = f32_of(in[i + 1]);
    v.z = f32_of(in[i + 2]);
    return v;
}

static SubconeSraaParams params_at(const uint32_t *in) {
    SubconeSraaParams p;
    memset(&p, 0, sizeof p);
    p.sigma_z = f32_of(in[0]);
    p.sigma_n = f32_of(in[1]);
    p.scale = f32_of(in[2]);
    p.packed = in[3];
    p.sigma_s = f32_of(in[4]);
    p.shading = in[5];
    return p;
}

static SubconeGeometry geometry_at(const uint32_t *in, int i) {
    SubconeGeometry g;
    g.normal = vec_at(in, i);
    g.depth = f32_of(in[i + 3]);
    return g;
}

static int finite_params(const uint32_t *in) {
    return isfinite(f32_of(in[0])) && isfinite(f32_of(in[1])) && isfinite(f32_of(in[2])) &&
           isfinite(f32_of(in[4]));
}

/* One kernel through the C ABI: writes its outputs as bits; returns its
 * status. `refuse` is set when the case lies where the ABI documents a
 * refusal (then the status must be the error). */
typedef SubconeStatus (*Call)(const uint32_t *in, uint32_t *out, int *refuse);

static SubconeStatus c_bilateral(const uint32_t *in, uint32_t *out, int *refuse) {
    SubconeSraaParams p = params_at(in);
    SubconeGeometry gi = geometry_at(in, 6), gj = geometry_at(in, 10);
    float w;
    SubconeStatus s = subcone_bilateral_weight(&p, &gi, &gj, &w);
    *refuse = !finite_params(in);
    out[0] = bits_of(w);
    return s;
}

static SubconeStatus c_shadow(const uint32_t *in, uint32_t *out, int *refuse) {
    SubconeSraaParams p = params_at(in);
    SubconeGeometry gi = geometry_at(in, 6), gj = geometry_at(in, 10);
    float w;
    SubconeStatus s = subcone_shadow_gated_weight(&p, &gi, &gj, in[14], in[15], &w);
    *refuse = !finite_params(in);
    out[0] = bits_of(w);
    return s;
}

static SubconeStatus c_reconstruction(const uint32_t *in, uint32_t *out, int *refuse) {
    SubconeSraaParams p = params_at(in);
    SubconeGeometry gi = geometry_at(in, 6), gj = geometry_at(in, 10);
    float w;
    SubconeStatus s = subcone_reconstruction_weight(&p, &gi, &gj, f32_of(in[14]), &w);
    *refuse = !finite_params(in);
    out[0] = bits_of(w);
    return s;
}

static SubconeStatus c_albedo(const uint32_t *in, uint32_t *out, int *refuse) {
    float d;
    SubconeStatus s = subcone_albedo_difference(vec_at(in, 0), vec_at(in, 3), &d);
    *refuse = 0;
    out[0] = bits_of(d);
    return s;
}

static SubconeStatus c_resolve(const uint32_t *in, uint32_t *out, int *refuse) {
    SubconeVec3 c[4], r;
    SubconeStatus s;
    int k;
    for (k = 0; k < 4; k++) c[k] = vec_at(in, 3 * k);
    s = subcone_resolve_pixel(c, &r);
    *refuse = 0;
    out[0] = bits_of(r.x);
    out[1] = bits_of(r.y);
    out[2] = bits_of(r.z);
    return s;
}

static SubconeStatus c_tan_theta(const uint32_t *in, uint32_t *out, int *refuse) {
    float fov = f32_of(in[0]), coverage = f32_of(in[2]), t;
    SubconeStatus s = subcone_cone_tan_theta(fov, in[1], coverage, in[3], &t);
    *refuse = !(fov > 0.0f && fov < 3.14159265358979f) || in[1] == 0 ||
              !(isfinite(coverage) && coverage > 0.0f) || in[3] > 2;
    out[0] = bits_of(t);
    return s;
}

static SubconeStatus c_radius(const uint32_t *in, uint32_t *out, int *refuse) {
    float r;
    SubconeStatus s = subcone_cone_radius(f32_of(in[0]), f32_of(in[1]), &r);
    *refuse = 0;
    out[0] = bits_of(r);
    return s;
}

static SubconeStatus c_occlusion(const uint32_t *in, uint32_t *out, int *refuse) {
    float w;
    SubconeStatus s = subcone_cone_occlusion(f32_of(in[0]), f32_of(in[1]), &w);
    *refuse = 0;
    out[0] = bits_of(w);
    return s;
}

static SubconeStatus c_advance(const uint32_t *in, uint32_t *out, int *refuse) {
    float t;
    SubconeStatus s = subcone_advance(f32_of(in[0]), f32_of(in[1]), f32_of(in[2]), f32_of(in[3]), &t);
    *refuse = 0;
    out[0] = bits_of(t);
    return s;
}

static SubconeStatus c_entry(const uint32_t *in, uint32_t *out, int *refuse) {
    float t;
    SubconeStatus s = subcone_backtrace_cone_entry(f32_of(in[0]), f32_of(in[1]), &t);
    *refuse = 0;
    out[0] = bits_of(t);
    return s;
}

static SubconeStatus c_hard_hit(const uint32_t *in, uint32_t *out, int *refuse) {
    float t;
    SubconeStatus s = subcone_backtrace_hard_hit(f32_of(in[0]), f32_of(in[1]), f32_of(in[2]), &t);
    *refuse = 0;
    out[0] = bits_of(t);
    return s;
}

static SubconeStatus c_project(const uint32_t *in, uint32_t *out, int *refuse) {
    float n[2];
    SubconeStatus s = subcone_project_normal(vec_at(in, 0), vec_at(in, 3), vec_at(in, 6), n);
    *refuse = 0;
    out[0] = bits_of(n[0]);
    out[1] = bits_of(n[1]);
    return s;
}

static SubconeStatus c_mask(const uint32_t *in, uint32_t *out, int *refuse) {
    SubconeStatus s = subcone_visibility_mask(f32_of(in[0]), f32_of(in[1]), f32_of(in[2]), in[3], &out[0]);
    *refuse = in[3] > 2;
    return s;
}

static SubconeStatus c_sample_weight(const uint32_t *in, uint32_t *out, int *refuse) {
    float w, min_weight = f32_of(in[2]);
    SubconeStatus s = subcone_sample_weight(in[0], in[1], min_weight, &w);
    *refuse = in[1] > 1 || !isfinite(min_weight);
    out[0] = bits_of(w);
    return s;
}

static const struct {
    const char *name;
    Call call;
} KERNELS[] = {
    {"bilateral_weight", c_bilateral},   {"shadow_gated_weight", c_shadow},
    {"reconstruction_weight", c_reconstruction}, {"albedo_difference", c_albedo},
    {"resolve_pixel", c_resolve},        {"cone_tan_theta", c_tan_theta},
    {"cone_radius", c_radius},           {"cone_occlusion", c_occlusion},
    {"advance", c_advance},              {"backtrace_cone_entry", c_entry},
    {"backtrace_hard_hit", c_hard_hit},  {"project_normal", c_project},
    {"visibility_mask", c_mask},         {"sample_weight", c_sample_weight},
};

/* The values of one `[...]` list after `key`, as bits or integers. */
static int values_after(const char *line, const char *key, uint32_t *v, int max) {
    const char *p = strstr(line, key);
    int n = 0;
    if (!p) return -1;
    p = strchr(p, '[');
    if (!p) return -1;
    p++;
    while (*p && *p != ']') {
        char *end;
        if (*p == ' ' || *p == ',' || *p == '"') {
            p++;
            continue;
        }
        if (n == max) return -1;
        v[n++] = (uint32_t)strtoul(p, &end, 0);
        if (end == p) return -1;
        p = end;
    }
    return n;
}

/* Monotonic integer of a float's bits, for ulp distances. */
static int64_t ordered(uint32_t u) {
    return (u & 0x80000000u) ? -(int64_t)(u & 0x7fffffffu) : (int64_t)u;
}

static int within(uint32_t want, uint32_t got, int is_float, const char *kind, double value) {
    float a, b;
    int64_t ulps;
    if (!is_float) return want == got;
    a = f32_of(want);
    b = f32_of(got);
    if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
    if (a == b) return 1;
    if ((fpclassify(a) == FP_SUBNORMAL && b == 0.0f) || (fpclassify(b) == FP_SUBNORMAL && a == 0.0f)) return 1;
    ulps = ordered(want) - ordered(got);
    if (ulps < 0) ulps = -ulps;
    if (strcmp(kind, "ulps") == 0) return ulps <= (int64_t)value;
    if (strcmp(kind, "abs") == 0) return fabs((double)a - (double)b) <= value || ulps <= 4;
    if (strcmp(kind, "rel") == 0) {
        double m = fmax(1.0, fmax(fabs((double)a), fabs((double)b)));
        return fabs((double)a - (double)b) <= value * m;
    }
    return 0;
}

/* Where failures are described: no global state, so that checks may run on
 * several threads at once. */
typedef struct Log {
    char *at;
    size_t left;
} Log;

static void note(Log *log, const char *what, const char *name, long line) {
    int n = snprintf(log->at, log->left, "%s: %s (line %ld)\n", name, what, line);
    if (n > 0 && (size_t)n < log->left) {
        log->at += n;
        log->left -= (size_t)n;
    }
}

int subcone_smoke_vectors(const char *dir, VectorTally *t, char *log, size_t log_len) {
    char line[8192];
    size_t k;
    Log notes;
    memset(t, 0, sizeof *t);
    notes.at = log;
    notes.left = log_len;
    if (log_len > 0) log[0] = 0;
    for (k = 0; k < sizeof KERNELS / sizeof KERNELS[0]; k++) {
        char path[4096], kind[16] = "";
        int out_float[MAX_VALUES], n_out_types = 0;
        double value = 0;
        long lineno = 0;
        FILE *f;
        snprintf(path, sizeof path, "%s/%s.json", dir, KERNELS[k].name);
        f = fopen(path, "r");
        if (!f) {
            note(&notes, "cannot open the vector file", KERNELS[k].name, 0);
            t->failures++;
            continue;
        }
        t->files++;
        while (fgets(line, sizeof line, f)) {
            uint32_t in[MAX_VALUES], want[MAX_VALUES], got[MAX_VALUES];
            int n_in, n_want, refuse = 0, i, ok = 1, exact = 1;
            SubconeStatus s;
            lineno++;
            if (strncmp(line, "\"signature\"", 11) == 0) {
                const char *p = strstr(line, "\"out\"");
                while (p && (p = strstr(p, "\"type\": \"")) != NULL && n_out_types < MAX_VALUES) {
                    p += 9;
                    out_float[n_out_types++] = strncmp(p, "f32", 3) == 0;
                }
                continue;
            }
            if (strncmp(line, "\"tolerance\"", 11) == 0) {
                const char *p = strstr(line, "\"kind\": \"");
                const char *q = strstr(line, "\"value\": ");
                if (p) sscanf(p + 9, "%15[a-z]", kind);
                if (q) value = strtod(q + 9, NULL);
                continue;
            }
            if (strncmp(line, "{\"in\"", 5) != 0) continue;
            n_in = values_after(line, "\"in\"", in, MAX_VALUES);
            n_want = values_after(line, "\"out\"", want, MAX_VALUES);
            if (n_in < 0 || n_want < 0 || n_want != n_out_types || kind[0] == 0) {
                note(&notes, "unreadable case", KERNELS[k].name, lineno);
                t->failures++;
                continue;
            }
            t->cases++;
            s = KERNELS[k].call(in, got, &refuse);
            if (refuse) {
                t->refused++;
                if (s != SUBCONE_STATUS_INVALID_ARGUMENT) {
                    note(&notes, "a refused case was not INVALID_ARGUMENT", KERNELS[k].name, lineno);
                    t->failures++;
                }
                continue;
            }
            if (s != SUBCONE_STATUS_OK) {
                note(&notes, "an error on a valid case", KERNELS[k].name, lineno);
                t->failures++;
                continue;
            }
            for (i = 0; i < n_want; i++) {
                ok &= within(want[i], got[i], out_float[i], kind, value);
                exact &= want[i] == got[i] || (out_float[i] && isnan(f32_of(want[i])) && isnan(f32_of(got[i])));
            }
            if (!ok) {
                note(&notes, "outside the tolerance", KERNELS[k].name, lineno);
                t->failures++;
            }
            t->exact += (uint32_t)exact;
        }
        fclose(f);
    }
    return (int)t->failures;
}
