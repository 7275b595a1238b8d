#version 430 compatibility
uniform sampler2D colortex0;
uniform int isEyeInWater;
in vec2 texcoord;
struct Material { vec3 albedo; float roughness; };
// Control can reach the end without a `return`: drivers compile it, the value is undefined there.
Material underwaterMaterial(vec3 colour) {
	if (isEyeInWater == 1) {
		return Material(colour * 0.5, 0.1);
	}
}
void main() {
	Material m = underwaterMaterial(texture(colortex0, texcoord).rgb);
	gl_FragData[0] = vec4(m.albedo * m.roughness, 1.0);
}
