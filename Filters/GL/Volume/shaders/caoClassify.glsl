// caoClassify.glsl (after caoClipTest.glsl) - anti-aliased clipping and
// the three categories, one invocation per voxel of the region [regionMin, regionMax] (the union of
// this pose's and the previous pose's candidate boxes). The GLSL twin of
// caoClassify.cxx: the same projection (float, documented order), the same
// inside test, the same 9 + N samples. It writes the clip state byte
// (category << 6 | coverage count); voxels outside this pose's box get the
// outside state (c in subtraction, a in probing), so that the voxels the
// previous pose touched are restored and nothing else is written.
#ifndef CAO_LOCAL_X
#define CAO_LOCAL_X 8
#define CAO_LOCAL_Y 8
#define CAO_LOCAL_Z 1
#endif
layout(local_size_x = CAO_LOCAL_X, local_size_y = CAO_LOCAL_Y, local_size_z = CAO_LOCAL_Z) in;

layout(std430, binding = CAO_BINDING_COUNTERS) buffer CounterBlock
{
  uint counters[4];
};
layout(binding = CAO_IMAGE_STATE, r8ui) uniform writeonly uimage3D stateImage;

uniform ivec3 regionMin;
uniform ivec3 regionMax;

shared uint localCounts[3];

void main()
{
  if (gl_LocalInvocationIndex == 0u)
  {
    localCounts[0] = 0u;
    localCounts[1] = 0u;
    localCounts[2] = 0u;
  }
  barrier();
  ivec3 p = regionMin + ivec3(gl_GlobalInvocationID);
  bool inVolume = all(lessThanEqual(p, regionMax));
  bool subtract = clip.map.w == CAO_MODE_SUBTRACT;
  int category = subtract ? CAO_CATEGORY_UNAFFECTED : CAO_CATEGORY_CLIPPED;
  int count = 0;
  bool inBox = clip.boxMin.x <= clip.boxMax.x && all(greaterThanEqual(p, clip.boxMin.xyz)) &&
    all(lessThanEqual(p, clip.boxMax.xyz));
  if (inVolume && inBox)
  {
    vec3 c = vec3(p);
    float depth;
    int pixel = Project(c, depth);
    int inside = int(InLayers(0, pixel, depth));
    for (int n = 0; n < 8; ++n)
    {
      vec3 corner = vec3(float(p.x + (n & 1)) - 0.5, float(p.y + ((n >> 1) & 1)) - 0.5,
        float(p.z + ((n >> 2) & 1)) - 0.5);
      inside += int(Inside(corner));
    }
    int total = 9 + clip.aa.x;
    if (inside == 0)
      count = 0;
    else if (inside == 9)
      count = total;
    else
    {
      for (int n = 0; n < clip.aa.x; ++n)
      {
        precise vec3 q = c + clip.aaOffsets[n].xyz;
        inside += int(Inside(q));
      }
      count = inside;
    }
    int layerSize = clip.map.x * clip.map.y * clip.map.z;
    bool candidate = InLayers(2 * layerSize, pixel, depth);
    if (subtract)
      category = count == total ? CAO_CATEGORY_CLIPPED
                                : (candidate ? CAO_CATEGORY_AFFECTED : CAO_CATEGORY_UNAFFECTED);
    else
      category = count == 0 ? CAO_CATEGORY_CLIPPED
                            : (candidate ? CAO_CATEGORY_UNAFFECTED : CAO_CATEGORY_AFFECTED);
  }
  if (inVolume)
  {
    imageStore(stateImage, p, uvec4(uint((category << CAO_STATE_CATEGORY_SHIFT) | count)));
    atomicAdd(localCounts[category], 1u);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u)
  {
    atomicAdd(counters[0], localCounts[0]);
    atomicAdd(counters[1], localCounts[1]);
    atomicAdd(counters[2], localCounts[2]);
  }
}
