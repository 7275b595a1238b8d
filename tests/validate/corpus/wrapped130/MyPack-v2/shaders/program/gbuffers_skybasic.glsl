#ifdef VERTEX_SHADER
out vec4 starData;
void main() {
	gl_Position = ftransform();
	starData = vec4(gl_Color.rgb, float(gl_Color.r == gl_Color.g && gl_Color.g == gl_Color.b && gl_Color.r > 0.0));
}
#endif
#ifdef FRAGMENT_SHADER
#include "/lib/sky.glsl"
in vec4 starData;
void main() {
	vec4 ndc = vec4(gl_FragCoord.xy / vec2(viewWidth, viewHeight) * 2.0 - 1.0, 1.0, 1.0);
	vec4 view = gbufferProjectionInverse * ndc;
	vec3 color = starData.a > 0.5 ? starData.rgb : skyGradient(normalize(view.xyz));
	/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
#endif
