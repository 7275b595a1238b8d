#include "/lib/common.glsl"

varying vec2 texcoord;
varying vec2 lmcoord;
varying vec4 glcolor;
varying vec3 viewPos;
varying mat3 tbn;
varying float blockId;

#ifdef VSH
attribute vec4 mc_Entity;
attribute vec4 at_tangent;

void main() {
	vec4 pos = gl_ModelViewMatrix * gl_Vertex;
	if (mc_Entity.x == 10008.0) {
		pos.y += sin(frameTimeCounter * WAVE_SPEED + pos.x) * 0.02;
	}
	viewPos = pos.xyz;
	gl_Position = gl_ProjectionMatrix * pos;
	texcoord = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
	lmcoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
	glcolor = gl_Color;
	vec3 n = normalize(gl_NormalMatrix * gl_Normal);
	vec3 t = normalize(gl_NormalMatrix * at_tangent.xyz);
	tbn = mat3(t, cross(t, n) * sign(at_tangent.w), n);
	blockId = mc_Entity.x;
}
#endif

#ifdef FSH
#include "/lib/fog.glsl"

uniform sampler2D texture;
uniform sampler2D lightmap;
uniform sampler2D normals;
uniform sampler2D depthtex1;
uniform sampler2D noisetex;
uniform float viewWidth, viewHeight;

vec3 waterNormal(sampler2D noise, vec2 coord) {
	vec2 a = texture2D(noise, coord + frameTimeCounter * 0.01 * WAVE_SPEED).rg;
	vec2 b = texture2DLod(noise, coord * 2.0, 0.0).rg;
	return normalize(vec3((a + b) - 1.0, 1.0));
}

void main() {
	vec4 albedo = texture2D(texture, texcoord) * glcolor;
	vec3 light = texture2D(lightmap, lmcoord).rgb;
	vec3 n = tbn * waterNormal(noisetex, viewPos.xz * 0.1);
	if (blockId == 10008.0) {
		albedo.rgb = mix(albedo.rgb, vec3(0.1, 0.3, 0.5), 0.5);
		albedo.a = 0.6;
	}
	float opaqueDepth = texture2D(depthtex1, gl_FragCoord.xy / vec2(viewWidth, viewHeight)).r;
	albedo.rgb = applyFog(albedo.rgb * light, length(viewPos)) * (0.5 + 0.5 * opaqueDepth);
#ifdef DEBUG_NORMALS
	albedo.rgb = n * 0.5 + 0.5;
#endif
/* DRAWBUFFERS:02 */
	gl_FragData[0] = albedo;
	gl_FragData[1] = vec4(n * 0.5 + 0.5, 1.0);
}
#endif
