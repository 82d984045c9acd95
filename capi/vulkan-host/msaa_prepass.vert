#version 450
// The host's rasterised G-buffer prepass that shaders/sraa/msaa*.spv read:
// four triangles in view space (right-handed, looking down -z, +y up),
// projected by the host's matrix (a push constant; host_sraa_msaa.c passes
// the same matrix to subcone_sraa_pass_uniform). A tilted wall whose top
// edge leaves the top of the image empty (a miss), and two triangles in
// front of it crossing each other (depth edges, a crease, slanted
// silhouettes).
layout(push_constant) uniform Prepass {
    mat4 projection;
} prepass;

layout(location = 0) flat out vec3 normal;

const vec3 POSITIONS[12] = vec3[12](
    // The wall: two triangles, z from -8 (left) to -12 (right), y up to 2.
    vec3(-20.0, -20.0, -8.0), vec3(20.0, -20.0, -12.0), vec3(20.0, 2.0, -12.0),
    vec3(-20.0, -20.0, -8.0), vec3(20.0, 2.0, -12.0), vec3(-20.0, 2.0, -8.0),
    // Two triangles in front, crossing.
    vec3(-3.0, -2.0, -4.0), vec3(2.5, -1.5, -3.5), vec3(-0.5, 2.5, -5.0),
    vec3(0.0, -3.0, -3.0), vec3(3.0, 0.3, -6.0), vec3(0.7, 3.1, -4.2));

void main() {
    const int first = gl_VertexIndex / 3 * 3;
    const vec3 a = POSITIONS[first], b = POSITIONS[first + 1], c = POSITIONS[first + 2];
    // The triangle's unit normal, facing the eye (at the origin).
    vec3 n = normalize(cross(b - a, c - a));
    normal = dot(n, a) > 0.0 ? -n : n;
    gl_Position = prepass.projection * vec4(POSITIONS[gl_VertexIndex], 1.0);
}
