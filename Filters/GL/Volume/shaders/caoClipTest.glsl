// caoClipTest.glsl - the shadow test against the clip mesh's depth maps,
// shared by the classifier (caoClassify.glsl) and the ray caster
// (caoRayCastFS.glsl), so that the two cannot disagree on what is inside:
// a point in voxel-index space is projected into the clipping camera with
// the per-pose ClipParams (float, in the documented order of caoGPULayout.h)
// and is inside when its depth lies in one of the L peeled intervals of
// its map pixel. The twin of cao::Inside in caoClassify.cxx.
layout(std140, binding = CAO_BINDING_CLIP_PARAMS) uniform ClipBlock
{
  ClipParams clip;
};
// Four maps of width * height * layers floats each, pixel-major with the
// layers of a pixel adjacent: front, back, candidate front, candidate back.
layout(std430, binding = CAO_BINDING_MAPS) readonly buffer MapBlock
{
  float maps[];
};
/// Returns the map pixel index, or -1 when the point projects outside the map.
int Project(vec3 q, out float depth)
{
  precise float u = ((clip.toCamera[0].x * q.x + clip.toCamera[0].y * q.y) +
                      clip.toCamera[0].z * q.z) + clip.toCamera[0].w;
  precise float v = ((clip.toCamera[1].x * q.x + clip.toCamera[1].y * q.y) +
                      clip.toCamera[1].z * q.z) + clip.toCamera[1].w;
  precise float d = ((clip.toCamera[2].x * q.x + clip.toCamera[2].y * q.y) +
                      clip.toCamera[2].z * q.z) + clip.toCamera[2].w;
  depth = d;
  // Written so that NaN fails the test.
  if (u >= 0.0 && v >= 0.0 && u < float(clip.map.x) && v < float(clip.map.y))
  {
    int px = min(int(u), clip.map.x - 1);
    int py = min(int(v), clip.map.y - 1);
    return py * clip.map.x + px;
  }
  return -1;
}

bool InLayers(int mapOffset, int pixel, float depth)
{
  if (pixel < 0)
    return false;
  int base = mapOffset + pixel * clip.map.z;
  int layerSize = clip.map.x * clip.map.y * clip.map.z;
  for (int l = 0; l < clip.map.z; ++l)
  {
    if (maps[base + l] <= depth && depth <= maps[base + layerSize + l])
      return true;
  }
  return false;
}

bool Inside(vec3 q)
{
  float depth;
  int pixel = Project(q, depth);
  return InLayers(0, pixel, depth);
}

