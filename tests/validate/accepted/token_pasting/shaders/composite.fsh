#version 330 compatibility
// Token pasting, which Mesa, glslang (outside ES) and Iris's preprocessor all expand: one macro
// names a buffer's sampler and its weight from one word.
#define BUFFER(n) colortex ## n
#define WEIGHT(n) weight ## n
uniform sampler2D BUFFER(0);
uniform sampler2D BUFFER(1);
const float WEIGHT(0) = 0.75;
const float WEIGHT(1) = 0.25;
in vec2 uv;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 color;
void main() {
    color = texture(BUFFER(0), uv) * WEIGHT(0) + texture(BUFFER(1), uv) * WEIGHT(1);
}
