#version 450
layout(location = 0) out vec4 tp_FragData0; layout(location = 0) in vec4 tp_TexCoord0; void main() {
	tp_FragData0
 = tp_TexCoord0
;
}
