// caoVolumeOpacity.glsl - the LAO's opacity at a voxel of the AO engine's
// input: one definition for the programs that read it (the march,
// caoLAOMarch.glsl, and the ray caster's AO samples, caoAOSamples.glsl),
// placed before them in a program's sources.
//   CAO_OPACITY_SOURCE  0: float opacity image (r32f)
//                       1: 8-bit scalars + opacity table
//                       2: 16-bit scalars + opacity table
#ifndef CAO_OPACITY_SOURCE
#define CAO_OPACITY_SOURCE 1
#endif
layout(std430, binding = CAO_BINDING_OPACITY_TABLE) readonly buffer OpacityTableBlock
{
  float opacityTable[];
};
#if CAO_OPACITY_SOURCE == 0
layout(binding = CAO_IMAGE_VOLUME, r32f) uniform readonly image3D volumeImage;
#elif CAO_OPACITY_SOURCE == 1
layout(binding = CAO_IMAGE_VOLUME, r8ui) uniform readonly uimage3D volumeImage;
#else
layout(binding = CAO_IMAGE_VOLUME, r16ui) uniform readonly uimage3D volumeImage;
#endif

/// The unclipped opacity of voxel p, which must be inside the volume.
float VolumeOpacity(ivec3 p)
{
#if CAO_OPACITY_SOURCE == 0
  return imageLoad(volumeImage, p).r;
#else
  return opacityTable[imageLoad(volumeImage, p).r];
#endif
}
