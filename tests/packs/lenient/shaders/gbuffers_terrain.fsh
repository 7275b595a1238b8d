#version 130
// OptiFine's old name for the atlas. From GLSL 1.30 it hides the function texture(): NVIDIA
// compiles the call anyway, Mesa refuses it, Iris renames the sampler to gtexture.
uniform sampler2D texture;
varying vec2 uv;
varying vec4 tint;
void main() {
    gl_FragData[0] = texture(texture, uv) * tint;
}
