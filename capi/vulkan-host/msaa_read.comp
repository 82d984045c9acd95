#version 450
// Reads every sample of the prepass's multisampled attachments into a
// buffer, (normal.xyz, hardware depth) per sample, pixel by pixel: the
// geometry host_sraa_msaa.c's CPU resolve is given, the very values the
// resolve shader samples.
#extension GL_EXT_samplerless_texture_functions : require
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform texture2DMS prepass_depth;
layout(set = 0, binding = 1) uniform texture2DMS prepass_normal;
layout(set = 0, binding = 2, std430) writeonly buffer Samples {
    vec4 samples[];
};

void main() {
    const ivec2 size = textureSize(prepass_depth);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= size.y) return;
    for (int k = 0; k < 4; k++) {
        samples[4 * (p.y * size.x + p.x) + k] =
            vec4(texelFetch(prepass_normal, p, k).xyz, texelFetch(prepass_depth, p, k).r);
    }
}
