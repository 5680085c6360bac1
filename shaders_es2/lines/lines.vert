// Points and lines (effects/lines/LinesEffect.h): placed by one matrix per instance, coloured per vertex (the
// material's base colour factor times COLOR_0). Points are u_pointSize pixels wide.
attribute vec3 a_position;
attribute vec4 a_color;

uniform mat4 u_modelViewProjection;  // projection (jittered as the G-buffer's) x view x the instance's world
uniform float u_pointSize;

varying vec4 v_color;

void main() {
  v_color = a_color;
  gl_Position = u_modelViewProjection * vec4(a_position, 1.0);
  gl_PointSize = u_pointSize;
}
