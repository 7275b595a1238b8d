#version 120
// The terrain, drawn as the game draws it, and a top-face mark only an `if` writes: elsewhere
// its value is undefined (wgpu has 0; OpenGL is given 0 first). A precision qualifier, a
// reserved word under 1.20 that NVIDIA takes.
varying vec2 uv;
varying vec4 tint;
varying float top;
void main() {
    gl_Position = ftransform();
    uv = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
    tint = gl_Color;
    mediump float up = gl_Normal.y;
    if (up > 0.5) top = 1.0;
}
