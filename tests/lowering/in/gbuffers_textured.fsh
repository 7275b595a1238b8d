#version 120

#define FOG

uniform sampler2D lightmap;
uniform sampler2D texture;
uniform vec3 fogColor;
uniform float fogStart;
uniform float fogEnd;

varying vec2 lmcoord;
varying vec2 texcoord;
varying vec4 glcolor;

void main() {
	vec4 color = texture2D(texture, texcoord) * glcolor;
	color *= texture2D(lightmap, lmcoord);
#ifdef FOG
	float fog = clamp((gl_FragCoord.z / gl_FragCoord.w - fogStart) / (fogEnd - fogStart), 0.0, 1.0);
	color.rgb = mix(color.rgb, fogColor, fog);
#endif

/* DRAWBUFFERS:0 */
	gl_FragData[0] = color; //gcolor
}
