#version 150
in vec4 color;
in vec4 coords;
/* RENDERTARGETS: 0 */
out vec4 outColor0;
void main() {
    outColor0 = vec4(color.rgb * 0.5, 0.5);
}
