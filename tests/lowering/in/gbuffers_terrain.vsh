#version 120

attribute vec4 mc_Entity;
attribute vec2 mc_midTexCoord;
attribute vec4 at_tangent;

uniform float frameTimeCounter;
uniform vec3 cameraPosition;
uniform mat4 gbufferModelView, gbufferModelViewInverse;

varying vec2 texcoord;
varying vec2 lmcoord;
varying vec4 glcolor;
varying vec3 normal;
varying float blockId;
centroid varying vec2 midcoord;

void main() {
	vec4 viewPos = gl_ModelViewMatrix * gl_Vertex;
	vec4 worldPos = gbufferModelViewInverse * viewPos;
	if (mc_Entity.x == 10001.0) {
		worldPos.y += sin(frameTimeCounter * 2.0 + worldPos.x + cameraPosition.x) * 0.05;
	}
	gl_Position = gl_ProjectionMatrix * (gbufferModelView * worldPos);

	texcoord = gl_MultiTexCoord0.st;
	lmcoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).st;
	midcoord = mc_midTexCoord;
	glcolor = gl_Color;
	normal = normalize(gl_NormalMatrix * gl_Normal);
	normal += 0.0 * at_tangent.xyz;
	blockId = mc_Entity.x;
}
