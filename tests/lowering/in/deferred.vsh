#version 330 compatibility

uniform vec3 sunPosition;
uniform vec3 upPosition;

out vec2 texcoord;
flat out float sunVisibility;

void main() {
	gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
	texcoord = gl_MultiTexCoord0.st;
	sunVisibility = clamp(dot(normalize(sunPosition), normalize(upPosition)) * 4.0, 0.0, 1.0);
}
