#version 120
uniform sampler2D colortex0;
varying vec4 v0;
varying vec4 v1;
varying vec4 v2;
varying vec4 v3;
varying vec4 v4;
varying vec4 v5;
varying vec4 v6;
varying vec4 v7;
varying vec4 v8;
varying vec4 v9;
varying vec4 v10;
varying vec4 v11;
varying vec4 v12;
varying vec4 v13;
varying vec4 v14;
varying vec4 v15;
varying vec4 v16;
varying vec4 v17;
varying vec4 v18;
varying vec4 v19;
varying vec4 v20;
varying vec4 v21;
varying vec4 v22;
varying vec4 v23;
varying vec4 v24;
varying vec4 v25;
varying vec4 v26;
varying vec4 v27;
varying vec4 v28;
varying vec4 v29;
varying vec4 v30;
varying vec4 v31;
void main() {
    vec4 sum = v0 + v1 + v2 + v3 + v4 + v5 + v6 + v7 + v8 + v9 + v10 + v11 + v12 + v13 + v14 + v15 + v16 + v17 + v18 + v19 + v20 + v21 + v22 + v23 + v24 + v25 + v26 + v27 + v28 + v29 + v30 + v31;
    gl_FragData[0] = vec4(sum.x, texture2D(colortex0, gl_TexCoord[0].st).g, 0.0, 1.0);
}
