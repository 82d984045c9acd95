#version 450
// vkc's self test: one uniform, one input and one output storage buffer, the
// same shape of binding table as subcone's generated passes.
layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform Params {
    uint n;
    float scale;
} params;

layout(set = 0, binding = 1) readonly buffer Input {
    float values[];
} src;

layout(set = 0, binding = 2) writeonly buffer Output {
    float values[];
} dst;

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The last workgroup runs past n; those invocations must not write.
    if (i >= params.n) {
        return;
    }
    dst.values[i] = src.values[i] * params.scale + float(i);
}
