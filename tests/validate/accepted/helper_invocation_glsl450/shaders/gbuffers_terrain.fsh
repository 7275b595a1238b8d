#version 450 compatibility
// As seilotte/lumina skips the work of helper fragments: gl_HelperInvocation, from GLSL 4.50.
uniform sampler2D gtexture;
in vec2 uv;
layout(location = 0) out vec4 colour;
void main() {
    colour = texture(gtexture, uv);
    if (gl_HelperInvocation) return;
    colour.rgb *= 0.5;
}
