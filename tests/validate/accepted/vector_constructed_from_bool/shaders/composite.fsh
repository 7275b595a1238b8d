#version 430 compatibility
uniform sampler2D colortex0;
uniform int isEyeInWater;
in vec2 texcoord;
// A vector made of one bool (0.0 or 1.0 in each component), as zombye/spectrum writes a
// material's translucency.
struct Material { vec3 translucency; };
void main() {
	bool translucent = isEyeInWater == 1;
	Material m;
	m.translucency = vec3(translucent);
	vec3 direct = vec3(translucent);
	gl_FragData[0] = vec4(m.translucency + direct, 1.0);
}
