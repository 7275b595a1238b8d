#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { float frameTimeCounter; vec3 cameraPosition; mat4 gbufferModelView; mat4 gbufferModelViewInverse; mat4 tp_TextureMatrix[8]; mat4 tp_ModelViewMatrix; mat4 tp_ProjectionMatrix; }; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 4) in vec4 tp_MultiTexCoord1; layout(location = 1) in vec4 tp_Color; layout(location = 0) in vec4 tp_Vertex; 


layout(location = 8) in vec4 mc_Entity;
layout(location = 9) in vec4 at_tangent;

layout(set = 0, binding = 1) uniform texture2D noisetex; layout(set = 0, binding = 2) uniform sampler tp_sampler_noisetex;





layout(location = 4) centroid out vec2 texcoord;
layout(location = 2) out vec2 lmcoord;
layout(location = 1) smooth out vec4 glcolor;
layout(location = 5) out vec3 viewPos;
layout(location = 3) noperspective out vec2 screenPos;
layout(location = 0) flat out int blockId;

void main() {
	texcoord = (tp_TextureMatrix[0] * tp_MultiTexCoord0).xy;
	lmcoord = (tp_TextureMatrix[1] * tp_MultiTexCoord1).xy;
	glcolor = tp_Color;
	blockId = int(mc_Entity.x + 0.5);

	vec4 position = tp_ModelViewMatrix * tp_Vertex;

	if (blockId == 10008) {
		vec4 worldPos = gbufferModelViewInverse * position;
		vec2 noiseCoord = (worldPos.xz + cameraPosition.xz) / 64.0 + frameTimeCounter * 0.01;
		worldPos.y += (textureLod(sampler2D(noisetex, tp_sampler_noisetex), noiseCoord, 0.0).r - 0.5) * 0.1 * at_tangent.w;
		position = gbufferModelView * worldPos;
	}

	viewPos = position.xyz;
	gl_Position = tp_ProjectionMatrix * position;
	screenPos = gl_Position.xy / gl_Position.w * 0.5 + 0.5;
}
