#ifdef VERTEX_SHADER
out vec2 texCoord;
out vec2 lightCoord;
out vec4 glColor;
out vec3 normal;
void main() {
	gl_Position = ftransform();
	texCoord = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
	lightCoord = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
	glColor = gl_Color;
	normal = normalize(gl_NormalMatrix * gl_Normal);
}
#endif
#ifdef FRAGMENT_SHADER
uniform sampler2D tex;
uniform sampler2D lightmap;
uniform vec4 entityColor;
in vec2 texCoord;
in vec2 lightCoord;
in vec4 glColor;
in vec3 normal;
void main() {
	vec4 color = texture2D(tex, texCoord) * glColor;
	color.rgb = mix(color.rgb, entityColor.rgb, entityColor.a);
	color.rgb *= texture2D(lightmap, lightCoord).rgb;
	/* DRAWBUFFERS:01 */
	gl_FragData[0] = color;
	gl_FragData[1] = vec4(normal * 0.5 + 0.5, 1.0);
}
#endif
