#version 330 compatibility
uniform sampler2D gtexture;
uniform sampler2D depthtex1;
uniform float viewWidth, viewHeight;
in vec2 texcoord;
in vec4 tint;
in float isWater;
/* RENDERTARGETS: 0,4 */
out vec4 outColor0;
out vec4 outColor1;
void main() {
	vec4 c = texture(gtexture, texcoord) * tint;
	float behind = texelFetch(depthtex1, ivec2(gl_FragCoord.xy), 0).r;
	c.a = mix(c.a, 0.7, isWater) * step(gl_FragCoord.z, behind);
	outColor0 = c;
	outColor1 = vec4(isWater, 0.0, 0.0, 1.0);
}
