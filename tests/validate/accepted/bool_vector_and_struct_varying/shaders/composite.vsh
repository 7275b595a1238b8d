#version 400 compatibility
// A struct passed as one varying takes a location per member; the vec2 after it must not
// overlap them.
struct Fog { vec3 color; float density; mat2 swirl; };
flat out Fog fog;
out vec2 uv;

void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.st;
    fog = Fog(vec3(0.5), 0.1, mat2(1.0));
}
