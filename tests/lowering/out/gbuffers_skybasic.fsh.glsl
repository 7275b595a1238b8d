#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { float viewHeight; float viewWidth; mat4 gbufferProjectionInverse; vec3 fogColor; vec3 skyColor; vec3 upPosition; }; float dot(float x, float y) { return x * y; } float normalize(float x) { return x / abs(x); } layout(location = 1) in vec4 tp_FrontColor; layout(location = 0) out vec4 tp_FragData0; 







layout(location = 0) in float starData;

float fogify(float x, float w) {
	return w / (x * x + w);
}

void main() {
	vec4 pos = gbufferProjectionInverse * vec4(gl_FragCoord.xy / vec2(viewWidth, viewHeight) * 2.0 - 1.0, 1.0, 1.0);
	float upDot = dot(normalize(pos.xyz), normalize(upPosition));
	vec3 color = mix(skyColor, fogColor, fogify(max(upDot, 0.0), 0.25));
	if (starData > 0.5) color = tp_FrontColor.rgb;


	tp_FragData0 = vec4(color, 1.0);
}
