#version 150 compatibility
// The shadow map's depth over the screen: wgpu draws this step from the shadow map OpenGL drew.
uniform sampler2D shadowtex0;
in vec2 uv;
void main() {
    gl_FragData[0] = vec4(vec3(texture(shadowtex0, uv).r), 1.0);
}
