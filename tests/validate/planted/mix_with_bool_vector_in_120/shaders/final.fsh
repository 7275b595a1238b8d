#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	vec3 colour = texture2D(colortex0, texcoord).rgb;
	vec3 bright = colour * 2.0;
	gl_FragData[0] = vec4(mix(colour, bright, greaterThan(colour, vec3(0.5))), 1.0);
}
