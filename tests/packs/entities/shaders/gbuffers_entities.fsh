#version 120
// Red for the entity entity.properties lists (2000), green for one it does not (-1).
uniform int entityId;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(entityId == 2000 ? 1.0 : 0.0, entityId == -1 ? 1.0 : 0.0, 0.0, 1.0);
}
