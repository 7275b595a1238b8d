#version 130
// `id` lacks `flat` (GLSL 1.30 4.3.4).
in vec2 uv;
in int id;
void main() {
 gl_FragData[0] = vec4(uv, float(id), 1.0);
}
