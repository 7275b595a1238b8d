#version 120
attribute vec4 at_tangent;
varying mat3 tbn;
varying vec2 texcoord;
void main() {
	gl_Position = ftransform();
	vec3 n = normalize(gl_NormalMatrix * gl_Normal);
	vec3 t = normalize(gl_NormalMatrix * at_tangent.xyz);
	tbn = mat3(t, cross(t, n), n);
	texcoord = gl_MultiTexCoord0.xy;
	if (at_tangent.w == 0.0) return;
	gl_FogFragCoord = length((gl_ModelViewMatrix * gl_Vertex).xyz);
}
