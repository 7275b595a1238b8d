#ifdef VERTEX_SHADER
out vec2 texCoord;
void main() {
	gl_Position = ftransform();
	texCoord = gl_MultiTexCoord0.xy;
}
#endif
#ifdef FRAGMENT_SHADER
uniform sampler2D colortex0;
uniform sampler2D depthtex0;
uniform float blindness;
uniform float nightVision;
in vec2 texCoord;
void main() {
	vec3 color = texture2D(colortex0, texCoord).rgb;
	float depth = texture2D(depthtex0, texCoord).r;
	color *= 1.0 - blindness * float(depth > 0.9);
	color = mix(color, sqrt(color), nightVision * 0.5);
	/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
#endif
