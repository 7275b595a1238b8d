#version 120
#extension GL_EXT_gpu_shader4 : enable
#include "/lib/common.glsl"
attribute vec4 mc_Entity;
attribute vec2 mc_midTexCoord;
varying vec2 texcoord;
varying vec2 lmcoord;
varying vec4 glcolor;
varying vec3 normal;
flat varying int material;
void main() {
	vec4 pos = gl_ModelViewMatrix * gl_Vertex;
	gl_Position = gl_ProjectionMatrix * pos;
	texcoord = gl_MultiTexCoord0.st;
	lmcoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).st;
	glcolor = gl_Color;
	normal = gl_NormalMatrix * gl_Normal;
	material = int(mc_Entity.x + 0.5);
	texcoord += 0.0 * mc_midTexCoord;
}
