#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { float viewWidth; float viewHeight; int frameCounter; ivec2 eyeBrightnessSmooth; vec3 sunPosition; vec4 entityColor; mat4 gbufferProjection; float exposureCurve[4]; vec2 taaOffsets[8]; }; 
layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0;
layout(set = 1, binding = 3) uniform texture2D colortex3; layout(set = 1, binding = 4) uniform sampler tp_sampler_colortex3;









layout(location = 0) in vec2 texcoord;

layout(location = 0) out vec4 fragColor;

vec3 tonemap(vec3 x) {
	float exposure = exposureCurve[eyeBrightnessSmooth.y / 60];
	x *= exposure;
	return x / (1.0 + x);
}

void main() {
	ivec2 pixel = ivec2(gl_FragCoord.xy);
	vec3 color = texelFetch(sampler2D(colortex0, tp_sampler_colortex0), pixel, 0).rgb;
	vec2 jitter = taaOffsets[frameCounter % 8] / vec2(viewWidth, viewHeight);
	vec2 size = vec2(textureSize(sampler2D(colortex3, tp_sampler_colortex3), 0));
	color += texture(sampler2D(colortex3, tp_sampler_colortex3), texcoord + jitter).rgb / size.x;
	vec4 sunClip = gbufferProjection * vec4(sunPosition, 1.0);
	color += entityColor.rgb * entityColor.a * step(0.0, sunClip.w);
	fragColor = vec4(tonemap(color), 1.0);
}
