#version 330 compatibility

#define WAVING_WATER

in vec4 mc_Entity;
in vec4 at_tangent;

uniform sampler2D noisetex;
uniform float frameTimeCounter;
uniform vec3 cameraPosition;
uniform mat4 gbufferModelView;
uniform mat4 gbufferModelViewInverse;

centroid out vec2 texcoord;
out vec2 lmcoord;
smooth out vec4 glcolor;
out vec3 viewPos;
noperspective out vec2 screenPos;
flat out int blockId;

void main() {
	texcoord = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
	lmcoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
	glcolor = gl_Color;
	blockId = int(mc_Entity.x + 0.5);

	vec4 position = gl_ModelViewMatrix * gl_Vertex;
#ifdef WAVING_WATER
	if (blockId == 10008) {
		vec4 worldPos = gbufferModelViewInverse * position;
		vec2 noiseCoord = (worldPos.xz + cameraPosition.xz) / 64.0 + frameTimeCounter * 0.01;
		worldPos.y += (texture2DLod(noisetex, noiseCoord, 0.0).r - 0.5) * 0.1 * at_tangent.w;
		position = gbufferModelView * worldPos;
	}
#endif
	viewPos = position.xyz;
	gl_Position = gl_ProjectionMatrix * position;
	screenPos = gl_Position.xy / gl_Position.w * 0.5 + 0.5;
}
