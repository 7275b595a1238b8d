#version 330 compatibility
uniform sampler2D gtexture;
uniform sampler2D lightmap;
in vec2 texcoord;
in vec2 lmcoord;
in vec4 tint;
in vec3 viewNormal;
flat in int blockId;
/* RENDERTARGETS: 0,1,2 */
layout(location = 0) out vec4 outColor0;
layout(location = 1) out vec4 outColor1;
layout(location = 2) out vec4 outColor2;
void main() {
	vec4 albedo = texture(gtexture, texcoord) * tint;
	if (albedo.a < 0.1) discard;
	outColor0 = vec4(albedo.rgb * texture(lightmap, lmcoord).rgb, albedo.a);
	outColor1 = vec4(viewNormal * 0.5 + 0.5, 1.0);
	outColor2 = vec4(lmcoord, float(blockId & 255) / 255.0, 1.0);
}
