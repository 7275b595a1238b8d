#ifdef VERTEX_SHADER
out vec2 texCoord;
out vec4 glColor;
void main() {
	gl_Position = ftransform();
	texCoord = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
	glColor = gl_Color;
}
#endif
#ifdef FRAGMENT_SHADER
uniform sampler2D tex;
in vec2 texCoord;
in vec4 glColor;
void main() {
	vec4 color = texture2D(tex, texCoord) * glColor;
#ifdef END
	color.rgb *= vec3(0.8, 0.7, 1.0);
#endif
	/* DRAWBUFFERS:0 */
	gl_FragData[0] = color;
}
#endif
