#version 330 compatibility
#include "/lib/uniforms.glsl"
in vec4 mc_Entity;
in vec4 at_tangent;
out vec2 texcoord;
out vec2 lmcoord;
out vec4 tint;
out vec3 viewNormal;
flat out int blockId;
void main() {
	gl_Position = ftransform();
	texcoord = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
	lmcoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
	tint = gl_Color;
	viewNormal = normalize(gl_NormalMatrix * gl_Normal) + 0.0 * at_tangent.xyz;
	blockId = int(mc_Entity.x + 0.5);
}
