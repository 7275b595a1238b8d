#version 150
in vec4 color;
in vec4 coords;
/* RENDERTARGETS: 0,1 */
out vec4 outColor0;
out vec4 outColor1;
void main() {
    outColor0 = color;
    outColor1 = coords;
}
