#version 120
uniform sampler2D texture;
varying vec2 texcoord;
void main() {
	vec4 albedo = texture2D(texture, texcoord);
/* DRAWBUFFERS:0 */
	gl_FragData[0] = albedo;
	gl_FragData[1] = vec4(0.5, 0.5, 1.0, 1.0);
}
