#version 330 compatibility

uniform sampler2D colortex0;
uniform sampler2D colortex3;
uniform float viewWidth, viewHeight;
uniform int frameCounter;
uniform ivec2 eyeBrightnessSmooth;
uniform vec3 sunPosition;
uniform vec4 entityColor;
uniform mat4 gbufferProjection;
uniform float exposureCurve[4];
uniform vec2 taaOffsets[8];

in vec2 texcoord;

out vec4 fragColor;

vec3 tonemap(vec3 x) {
	float exposure = exposureCurve[eyeBrightnessSmooth.y / 60];
	x *= exposure;
	return x / (1.0 + x);
}

void main() {
	ivec2 pixel = ivec2(gl_FragCoord.xy);
	vec3 color = texelFetch(colortex0, pixel, 0).rgb;
	vec2 jitter = taaOffsets[frameCounter % 8] / vec2(viewWidth, viewHeight);
	vec2 size = vec2(textureSize(colortex3, 0));
	color += texture(colortex3, texcoord + jitter).rgb / size.x;
	vec4 sunClip = gbufferProjection * vec4(sunPosition, 1.0);
	color += entityColor.rgb * entityColor.a * step(0.0, sunClip.w);
	fragColor = vec4(tonemap(color), 1.0);
}
