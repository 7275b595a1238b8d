#version 330 compatibility
uniform sampler2D colortex0;
in vec2 texcoord;
/* RENDERTARGETS: 0 */
out vec4 outColor0;
void main() {
	vec4 sum = vec4(0.0);
	for (int i = -1; i <= 1; i++)
		sum += textureOffset(colortex0, texcoord, ivec2(i, 0));
	outColor0 = sum / 3.0;
}
