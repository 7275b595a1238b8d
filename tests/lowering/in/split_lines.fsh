#version 120
void main() {
	gl_FragData
	[0] = gl_TexCoord[0
	];
}
