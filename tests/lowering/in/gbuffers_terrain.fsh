#version 120

uniform sampler2D texture;
uniform sampler2D lightmap;
uniform int isEyeInWater;
uniform float rainStrength;

varying vec2 texcoord;
varying vec2 lmcoord;
varying vec4 glcolor;
varying vec3 normal;
varying float blockId;
centroid varying vec2 midcoord;

vec4 sampleAtlas(sampler2D atlas, vec2 coord, float bias) {
	return texture2D(atlas, coord, bias);
}

void main() {
	vec4 albedo = sampleAtlas(texture, texcoord, -0.5) * glcolor;
	if (albedo.a < 0.1) discard;
	vec3 light = texture2D(lightmap, lmcoord).rgb;
	if (isEyeInWater == 1) light *= vec3(0.4, 0.6, 1.0);
	light *= 1.0 - 0.3 * rainStrength;

/* DRAWBUFFERS:012 */
	gl_FragData[0] = vec4(albedo.rgb * light, albedo.a);
	gl_FragData[1] = vec4(normal * 0.5 + 0.5, 1.0);
	gl_FragData[2] = vec4(lmcoord, blockId / 255.0, midcoord.x);
}
