#version 330 compatibility
uniform sampler2D colortex0;
in vec2 texcoord;
flat in vec3 tint;
void main() {
	gl_FragData[0] = texture(colortex0, texcoord) * vec4(tint, 1.0);
}
