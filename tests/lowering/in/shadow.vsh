#version 120
#extension GL_EXT_gpu_shader4 : enable

#define SHADOW_DISTORTION 0.85
#define DISTORT(p) ((p) / mix(1.0, length((p).xy), SHADOW_DISTORTION))

attribute vec4 mc_Entity;

varying vec2 texcoord;
varying vec4 glcolor;

void main() {
	vec4 position = gl_ModelViewMatrix * gl_Vertex;
	gl_Position = gl_ProjectionMatrix * position;
	gl_Position.xyz = DISTORT(gl_Position.xyz);
	texcoord = gl_MultiTexCoord0.xy;
	glcolor = gl_Color;
	if (mc_Entity.x == 10008.0) gl_Position.w = -1.0;
}
