uniform sampler2D colortex0;
vec4 shade(vec2 uv) {
    return texture(colortex0, uv) * tint;
}
