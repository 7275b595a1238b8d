#version 330 compatibility

uniform float viewHeight;
uniform float viewWidth;
uniform mat4 gbufferProjectionInverse;
uniform vec3 fogColor;
uniform vec3 skyColor;
uniform vec3 upPosition;

in float starData;

float fogify(float x, float w) {
	return w / (x * x + w);
}

void main() {
	vec4 pos = gbufferProjectionInverse * vec4(gl_FragCoord.xy / vec2(viewWidth, viewHeight) * 2.0 - 1.0, 1.0, 1.0);
	float upDot = dot(normalize(pos.xyz), normalize(upPosition));
	vec3 color = mix(skyColor, fogColor, fogify(max(upDot, 0.0), 0.25));
	if (starData > 0.5) color = gl_Color.rgb;

/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
