#version 120
#define QUALITY 1 // [1 2] Quality
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	vec3 c = texture2D(colortex0, texcoord).rgb;
#if QUALITY == 2
	c = sharpen(c);
#endif
	gl_FragColor = vec4(c, 1.0);
}
