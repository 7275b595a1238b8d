#version 130
// A sampler named `texture` hides the function texture() from GLSL 1.30 on. Iris's transformer
// names it `gtexture` before the driver compiles the stage (Septonious/Solas-Shader's dh_terrain).
uniform sampler2D texture, noisetex;
in vec2 uv;
void main() {
    gl_FragData[0] = texture2D(texture, uv) * texture(noisetex, uv * 0.5).r;
}
