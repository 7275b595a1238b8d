#version 120
uniform sampler2D normals;
uniform bool isNight;
uniform float fogEnd = 100.0;
varying mat3 tbn;
varying vec2 texcoord;
void main() {
	vec3 n = tbn * (texture2D(normals, texcoord).xyz * 2.0 - 1.0);
	float fog = clamp((gl_Fog.end - gl_FogFragCoord) * gl_Fog.scale, 0.0, 1.0);
	vec3 color = mix(gl_Fog.color.rgb, n * 0.5 + 0.5, fog);
	if (isNight) color *= 0.5;
/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color * fogEnd / 100.0, 1.0);
}
