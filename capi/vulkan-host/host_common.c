/* Helpers more than one pass uses: loading SPIR-V, colours as RGBA texels,
 * binary16 read-backs. */
#include "host.h"

#include <math.h>
#include <stdio.h>

int load_spirv(const char *dir, const char *name, uint32_t **words, size_t *bytes, char *err, size_t err_len) {
    char path[1024];
    if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int)sizeof path) {
        snprintf(err, err_len, "path too long: %s/%s", dir, name);
        return 1;
    }
    return vkc_read_file(path, words, bytes, err, err_len);
}

void rgba_texels(const SubconeVec3 *colors, size_t count, size_t stride, float *out) {
    for (size_t i = 0; i < count; i++) {
        const SubconeVec3 c = colors[i * stride];
        out[4 * i] = c.x;
        out[4 * i + 1] = c.y;
        out[4 * i + 2] = c.z;
        out[4 * i + 3] = 1.0f;
    }
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

void halves_to_floats(const void *halves, size_t count, float *out) {
    const uint16_t *h = halves;
    for (size_t i = 0; i < count; i++) out[i] = half_to_float(h[i]);
}
