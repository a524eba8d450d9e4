// caoCopyUnaffected.glsl - the current AO of every voxel of the region that
// is not recomputed (categories a and c) is the precomputed AO, copied as
// the stored 16-bit integer (no conversion, so no rounding).
#ifndef CAO_LOCAL_X
#define CAO_LOCAL_X 8
#define CAO_LOCAL_Y 8
#define CAO_LOCAL_Z 1
#endif
layout(local_size_x = CAO_LOCAL_X, local_size_y = CAO_LOCAL_Y, local_size_z = CAO_LOCAL_Z) in;

layout(binding = CAO_IMAGE_STATE, r8ui) uniform readonly uimage3D stateImage;
layout(binding = CAO_IMAGE_AO_IN, r16ui) uniform readonly uimage3D precomputedImage;
layout(binding = CAO_IMAGE_AO_OUT, r16ui) uniform writeonly uimage3D aoImage;

uniform ivec3 regionMin;
uniform ivec3 regionMax;

void main()
{
  ivec3 p = regionMin + ivec3(gl_GlobalInvocationID);
  if (any(greaterThan(p, regionMax)))
    return;
  int category = int(imageLoad(stateImage, p).r) >> CAO_STATE_CATEGORY_SHIFT;
  if (category != CAO_CATEGORY_AFFECTED)
    imageStore(aoImage, p, imageLoad(precomputedImage, p));
}
