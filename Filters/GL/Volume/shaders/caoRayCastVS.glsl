// caoRayCastVS.glsl - one triangle that covers the viewport; the fragment
// shader builds each pixel's ray from its window coordinates. No vertex
// attributes (an empty vertex array is bound).
void main()
{
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(corner, 0.0, 1.0);
}
