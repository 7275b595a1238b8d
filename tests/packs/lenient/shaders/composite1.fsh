#version 130
// More of what NVIDIA compiles and Mesa refuses: a `const` initialised from a uniform and a
// lookup of a sampler chosen by `?:`.
uniform sampler2D colortex0;
uniform sampler2D colortex2;
uniform float viewWidth;
const float texel = 1.0 / viewWidth;
in vec2 texcoord;
void main() {
    vec3 color = texture(texcoord.x < 0.5 ? colortex0 : colortex2, texcoord + texel).rgb;
    gl_FragData[0] = vec4(color, 1.0);
}
