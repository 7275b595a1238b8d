#version 430 compatibility
// GLSL lets a stage redeclare gl_FragDepth (4.20 adds a depth layout to the redeclaration).
layout(depth_greater) out float gl_FragDepth;
uniform sampler2D gtexture;
in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    color = texture(gtexture, uv);
    gl_FragDepth = gl_FragCoord.z + 0.001;
}
