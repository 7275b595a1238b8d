#version 120
// A local variable named like a struct type hides the type where it is declared.
struct maskData {
	bool terrain;
} mask;
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	float maskData = texture2D(colortex0, texcoord).a;
	mask.terrain = (maskData > 0.125);
	gl_FragData[0] = vec4(float(mask.terrain));
}
