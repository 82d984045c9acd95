#version 450
// The prepass's normal attachment: each triangle's signed unit normal
// (shaders/sraa/msaa* read signed normals), the same on all its samples.
layout(location = 0) flat in vec3 normal;
layout(location = 0) out vec4 out_normal;

void main() {
    out_normal = vec4(normal, 0.0);
}
