#version 420 compatibility
// Unary minus on unsigned integers, which GLSL takes modulo 2^32 (BruceKnowsHow/Octray's voxel
// march turns a uvec3 mask into -1.0 floats this way).
uniform sampler2D colortex0;
in vec2 uv;
void main() {
    uvec3 mask = uvec3(uv.x > 0.5, uv.y > 0.5, 1u);
    vec3 plane = vec3(-mask);
    uint flipped = -mask.z;
    gl_FragData[0] = texture(colortex0, uv) + vec4(plane * 1e-10, float(flipped) * 1e-12);
}
