#version 330
void main() {
	gl_Position = ftransform();
}
