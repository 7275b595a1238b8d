#version 150 compatibility
// Halves the colour where something translucent lies in front of the opaque scene: both
// depth buffers must be as the terrain, drawn by OpenGL alone, and the water left them.
uniform sampler2D colortex0;
uniform sampler2D depthtex0;
uniform sampler2D depthtex1;
in vec2 uv;
void main() {
    vec3 colour = texture(colortex0, uv).rgb;
    bool inFront = texture(depthtex0, uv).r < texture(depthtex1, uv).r;
    gl_FragData[0] = vec4(inFront ? 0.5 * colour : colour, 1.0);
}
