#version 430 compatibility
layout(std430, binding = 0) buffer lightCounts {
    uint counted[];
};
uniform sampler2D gtexture;
in vec2 texcoord;
in vec4 tint;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 color;
void main() {
    color = texture(gtexture, texcoord) * tint * (1.0 + float(counted[1]));
}
