#version 400 compatibility
// textureQueryLod (GLSL 4.00) on a 2D sampler: the mip level a lookup would use.
uniform sampler2D colortex0;
in vec2 uv;
void main() {
	vec2 lod = textureQueryLod(colortex0, uv);
	gl_FragData[0] = textureLod(colortex0, uv, lod.y);
}
