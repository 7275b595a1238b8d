#version 120
#include "/lib/color.glsl"
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	gl_FragData[0] = vec4(grade(texture2D(colortex0, texcoord).rgb), 1.0);
}
