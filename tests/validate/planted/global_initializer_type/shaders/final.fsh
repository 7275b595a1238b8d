#version 120
uniform sampler2D colortex0;
uniform float viewWidth;
varying vec2 texcoord;
vec3 pixel = vec2(1.0 / viewWidth);
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord + pixel.xy);
}
