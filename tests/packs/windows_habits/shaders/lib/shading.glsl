// Each face a colour of its own: the normal's axes as red, green and blue.
vec3 shade(vec3 normal) {
    return abs(normal);
}
