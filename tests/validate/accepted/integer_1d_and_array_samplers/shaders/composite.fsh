#version 330 compatibility
// Integer 1D and array textures: a palette and a layered table, as Iris packs read them.
uniform usampler1D colortex6;
uniform isampler2DArray colortex7;
in vec2 texcoord;
void main() {
	uint code = texelFetch(colortex6, int(texcoord.x * 16.0), 0).r;
	int layered = texelFetch(colortex7, ivec3(texcoord * 16.0, 1), 0).g;
	gl_FragData[0] = vec4(float(code) / 255.0, float(layered), 0.0, 1.0);
}
