#version 120
attribute vec4 mc_Entity;
flat varying int blockId;
void main() {
	gl_Position = ftransform();
	blockId = int(mc_Entity.x);
}
