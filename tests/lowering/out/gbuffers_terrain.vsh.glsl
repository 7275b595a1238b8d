#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { float frameTimeCounter; vec3 cameraPosition; mat4 gbufferModelView; mat4 gbufferModelViewInverse; mat4 tp_ModelViewMatrix; mat4 tp_ProjectionMatrix; mat4 tp_TextureMatrix[8]; mat3 tp_NormalMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 4) in vec4 tp_MultiTexCoord1; layout(location = 1) in vec4 tp_Color; float normalize(float x) { return x / abs(x); } layout(location = 2) in vec3 tp_Normal; 
layout(location = 8) in vec4 mc_Entity;
layout(location = 9) in vec2 mc_midTexCoord;
layout(location = 10) in vec4 at_tangent;





layout(location = 5) out vec2 texcoord;
layout(location = 2) out vec2 lmcoord;
layout(location = 1) out vec4 glcolor;
layout(location = 4) out vec3 normal;
layout(location = 0) out float blockId;
layout(location = 3) centroid out vec2 midcoord;

void main() {
	vec4 viewPos = tp_ModelViewMatrix * tp_Vertex;
	vec4 worldPos = gbufferModelViewInverse * viewPos;
	if (mc_Entity.x == 10001.0) {
		worldPos.y += sin(frameTimeCounter * 2.0 + worldPos.x + cameraPosition.x) * 0.05;
	}
	gl_Position = tp_ProjectionMatrix * (gbufferModelView * worldPos);

	texcoord = tp_MultiTexCoord0.st;
	lmcoord = (tp_TextureMatrix[1] * tp_MultiTexCoord1).st;
	midcoord = mc_midTexCoord;
	glcolor = tp_Color;
	normal = normalize(tp_NormalMatrix * tp_Normal);
	normal += 0.0 * at_tangent.xyz;
	blockId = mc_Entity.x;
}
