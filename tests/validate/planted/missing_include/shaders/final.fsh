#version 120
#include "/lib/post.glsl"
varying vec2 texcoord;
void main() {
	gl_FragColor = vec4(post(texcoord), 1.0);
}
