#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
#include "/lib/noise.glsl"
#include "/lib/sky.glsl"
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) + vec4(sky(texcoord), 0.0) * hash(texcoord);
}
