// Posterize
#version 150 compatibility
uniform sampler2D colortex0;
in vec2 texCoord;
layout(location = 0) out vec4 fragColor;
void main() {
	fragColor = floor(texture(colortex0, texCoord) * 8.0) / 8.0;
}
