#version 430 compatibility
uniform sampler2D colortex0;
uniform int isEyeInWater;
in vec2 texcoord;
// A vector made of one bool (0.0 or 1.0 in each component), as zombye/spectrum writes a
// material's translucency: stored, initialising, as an argument and as an operand.
struct Material { vec3 translucency; };
vec3 tinted(vec3 mask, ivec2 texel) { return mask * vec3(texel, 1.0); }
void main() {
	bool translucent = isEyeInWater == 1;
	Material m;
	m.translucency = vec3(translucent);
	vec3 direct = vec3(translucent);
	vec3 scaled = vec3(translucent) * 2.0;
	vec3 tint = tinted(vec3(translucent), ivec2(isEyeInWater > 0));
	vec3 chosen = vec3(translucent ? 0.5 : 1.0);
	gl_FragData[0] = vec4(m.translucency + direct + scaled + tint + chosen, texture(colortex0, texcoord).a);
}
