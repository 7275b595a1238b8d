#version 120
// `fog` is read and never given a value; `tint` is given one in a branch, `light` by a call.
uniform sampler2D colortex0;
uniform float rainStrength;
varying vec2 texcoord;
void lighting(out vec3 light) { light = vec3(1.0); }
void main() {
	vec3 fog;
	vec3 tint;
	vec3 light;
	if (rainStrength > 0.5) {
		tint = vec3(0.8);
	}
	lighting(light);
	vec3 color = texture2D(colortex0, texcoord).rgb * tint * light;
	gl_FragData[0] = vec4(color + fog, 1.0);
}
