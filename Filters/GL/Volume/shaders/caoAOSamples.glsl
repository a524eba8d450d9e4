// caoAOSamples.glsl - the volume the ray caster samples its AO from, one
// voxel per invocation over [regionMin, regionMax]. Per voxel, with keep = 0
// where the clip removed it (`clipped`: the state's category a) and 1
// otherwise:
//   r: keep * AO, g: keep, b: keep * the LAO's opacity, a: keep * (opacity > 0).
// Each channel is linear in the voxel's weight, so one linearly filtered
// fetch gives at any point the four trilinear sums the ray caster's VoxelAO
// needs: the AO and the weight of the voxels the clip leaves, and of those,
// the opacity and the weight of the ones that hold matter. It replaces the
// 8 voxels' state, AO, scalar and table reads per sample (32 fetches) and
// is redone only where the engine's state or AO changed (RayCaster).
#ifndef CAO_LOCAL_X
#define CAO_LOCAL_X 8
#define CAO_LOCAL_Y 8
#define CAO_LOCAL_Z 1
#endif
layout(local_size_x = CAO_LOCAL_X, local_size_y = CAO_LOCAL_Y, local_size_z = CAO_LOCAL_Z) in;

// (after caoVolumeOpacity.glsl: the LAO's own opacity, VolumeOpacity, as
// the march reads it; the AO engine's, not the ray cast's table, so that a
// colour, lighting or sample-distance change leaves the samples as they are)
layout(binding = CAO_UNIT_AO) uniform sampler3D aoTexture;
layout(binding = CAO_UNIT_STATE) uniform usampler3D stateTexture;
layout(binding = CAO_IMAGE_AO_SAMPLES, rgba16) uniform writeonly image3D samplesImage;

uniform ivec3 regionMin;
uniform ivec3 regionMax;
uniform int clipped;

void main()
{
  ivec3 v = regionMin + ivec3(gl_GlobalInvocationID);
  if (any(greaterThan(v, regionMax)))
    return;
  if (clipped != 0 &&
    (int(texelFetch(stateTexture, v, 0).r) >> CAO_STATE_CATEGORY_SHIFT) == CAO_CATEGORY_CLIPPED)
  {
    imageStore(samplesImage, v, vec4(0.0));
    return;
  }
  float a = clamp(VolumeOpacity(v), 0.0, 1.0);
  imageStore(samplesImage, v, vec4(texelFetch(aoTexture, v, 0).r, 1.0, a, a > 0.0 ? 1.0 : 0.0));
}
