#version 420 compatibility
// From GLSL 4.20 a scalar takes the swizzle `.x`, also as the target of an assignment, here a
// float member of a struct.
struct Surface {
    float depth;
    vec3 normal;
};
uniform sampler2D depthtex1;
in vec2 texcoord;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 colour;
void main() {
    Surface surface;
    surface.depth.x = texture(depthtex1, texcoord).r;
    surface.normal = vec3(0.0, 1.0, 0.0);
    colour = vec4(surface.normal * surface.depth, 1.0);
}
