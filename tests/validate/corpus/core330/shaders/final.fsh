// Final pass: gamma.
// (A banner before #version, as many packs have.)

#version 330 compatibility
uniform sampler2D colortex0;
in vec2 uv;
out vec4 finalColor;
void main() {
	finalColor = vec4(pow(texture(colortex0, uv).rgb, vec3(1.0 / 2.2)), 1.0);
}
