// caoClipDepthMapsVS.glsl - one instance per clip-mesh triangle, drawn as a
// 4-vertex strip: the rectangle of pixels [box.x, box.z] x [box.y, box.w]
// whose centres the triangle may cover (computed in double by the set-up
// pass, as caoClipDepthMaps.cxx does). The rectangle's edges lie on pixel
// borders, half a pixel from every centre, so the fixed-function
// rasteriser produces each of those pixels exactly once (the two halves of
// the strip share their diagonal, which GL assigns to exactly one) whatever
// its subpixel precision. Coverage itself is decided per fragment, exactly,
// in caoClipDepthMaps.glsl. An empty box collapses to a point outside the view.
layout(location = 0) in ivec4 box;

uniform ivec3 mapSize; // width, height, layers

flat out int triangleId;

void main()
{
  triangleId = gl_InstanceID;
  const vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  vec2 pixel = mix(vec2(box.xy), vec2(box.zw + 1), corner);
  if (box.x > box.z || box.y > box.w)
  {
    pixel = vec2(-4.0);
  }
  gl_Position = vec4(pixel / vec2(mapSize.xy) * 2.0 - 1.0, 0.0, 1.0);
}
