#version 130
// OptiFine's old name for the atlas. From GLSL 1.30 it hides the function texture(): NVIDIA
// compiles the call anyway, Mesa refuses it, Iris renames the sampler to gtexture. The second
// buffer named is never written (undefined: Mesa writes white, wgpu leaves it as it was).
uniform sampler2D texture;
varying vec2 uv;
varying vec4 tint;
varying float top;
/* DRAWBUFFERS:01 */
void main() {
    gl_FragData[0] = texture(texture, uv) * tint * (0.8 + 0.2 * top);
}
