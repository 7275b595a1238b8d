#version 430 compatibility
// A vector compared with a scalar: arithmetic applies a scalar to each component, but `==` and
// `!=` take operands of one type (Mesa: "operands of `!=' must have the same type").
uniform sampler2D colortex0;
in vec2 uv;
void main() {
    vec2 weight = texture(colortex0, uv).rg * 2.0;
    if (weight != 0) {
        weight /= 2.0;
    }
    gl_FragData[0] = vec4(weight, 0.0, 1.0);
}
