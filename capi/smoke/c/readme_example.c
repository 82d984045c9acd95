#include <math.h>
#include <stdio.h>
#include <string.h>

#include "subcone.h"

int subcone_readme_example(void);

/* README: begin */
/* A unit sphere 5 units down +z: the host's distance function. */
static SubconeFieldSample ball(void *user, SubconeVec3 p) {
    SubconeFieldSample s;
    (void)user;
    s.distance = sqrtf(p.x * p.x + p.y * p.y + (p.z - 5) * (p.z - 5)) - 1;
    s.step = s.distance;
    s.object = 0;
    return s;
}

static SubconeVec3 white(void *user, SubconeVec3 p, SubconeVec3 n, SubconeVec3 dir) {
    SubconeVec3 c = {1, 1, 1};
    (void)user, (void)p, (void)n, (void)dir;
    return c;
}

/* Whether a call failed; if so, says why (the library's message names the
 * function, the parameter and its value). */
static int failed(SubconeStatus s) {
    if (s == SUBCONE_STATUS_OK) return 0;
    fprintf(stderr, "subcone error %d: %s\n", (int)s, subcone_last_error_message());
    return 1;
}

int subcone_readme_example(void) {
    float tan_theta;
    SubconeCtssParams params;
    SubconeCtssResult pixel;
    SubconeVec3 origin = {0, 0, 0}, dir = {0.2041241f, 0, 1}, up = {0, 1, 0}, black = {0, 0, 0};

    if (subcone_version() >> 16 != SUBCONE_VERSION_MAJOR) return 1;
    /* The cone of one pixel of a 720-pixel-high image, 45° field of view. */
    if (failed(subcone_cone_tan_theta(0.785398f, 720, 1.0f, 0, &tan_theta))) return 2;
    if (failed(subcone_ctss_params_default(tan_theta, &params))) return 3;
    if (failed(subcone_ctss_trace(&params, origin, dir, up, ball, NULL, white, NULL, black, &pixel))) return 4;
    /* The ray grazes the sphere: the pixel is partly white, partly black. */
    if (!(pixel.color.x > 0 && pixel.color.x < 1)) return 5;
    /* A zero direction is refused, and the message says so:
     * "subcone_ctss_trace: dir is (0, 0, 0); it must not be zero". */
    if (subcone_ctss_trace(&params, origin, black, up, ball, NULL, white, NULL, black, &pixel)
        != SUBCONE_STATUS_INVALID_ARGUMENT) return 6;
    return strstr(subcone_last_error_message(), "dir is (0, 0, 0)") != NULL ? 0 : 7;
}
/* README: end */
