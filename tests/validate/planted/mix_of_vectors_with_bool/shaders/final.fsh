#version 130
uniform sampler2D colortex0;
uniform float sunAngle;
varying vec2 texcoord;
void main() {
	vec3 light = mix(vec3(0.1), vec3(1.0), sunAngle < 0.5);
	gl_FragData[0] = texture2D(colortex0, texcoord) * vec4(light, 1.0);
}
