#version 330 compatibility
uniform usampler2D colortex6;
in vec2 texcoord;
void main() {
	float depth = uintBitsToFloat(textureLod(colortex6, texcoord, 0.0).x);
	gl_FragData[0] = vec4(depth);
}
