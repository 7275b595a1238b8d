#version 120
uniform sampler2D texture;
uniform sampler2D specular;
varying vec2 texcoord;
float shine(float specular) {
	return specular * specular;
}
void main() {
	vec4 texture = texture2D(texture, texcoord);
	float specular = texture2D(specular, texcoord).r;
	gl_FragData[0] = texture * shine(specular);
}
