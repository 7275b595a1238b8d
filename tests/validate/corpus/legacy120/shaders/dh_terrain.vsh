#version 120
uniform mat4 dhProjection;
void main() {
	gl_Position = dhProjection * gl_ModelViewMatrix * gl_Vertex;
}
