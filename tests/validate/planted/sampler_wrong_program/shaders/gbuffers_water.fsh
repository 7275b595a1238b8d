#version 120
uniform sampler2D gtexture;
uniform sampler2D colortex1;
varying vec2 texcoord;
void main() {
	vec4 albedo = texture2D(gtexture, texcoord);
	gl_FragData[0] = albedo * texture2D(colortex1, texcoord).a;
}
