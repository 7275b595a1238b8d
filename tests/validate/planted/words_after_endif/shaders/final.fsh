#version 120
// `#endif FOO`: NVIDIA ignores the name after #endif; Mesa refuses the stage.
uniform sampler2D colortex0;
varying vec2 texcoord;
#ifdef FOO
const float k = 1.0;
#else
const float k = 0.5;
#endif FOO
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * k;
}
