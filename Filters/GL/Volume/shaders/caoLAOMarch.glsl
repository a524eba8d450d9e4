// caoLAOMarch.glsl - the LAO ray march (Hernell et al.), one invocation per
// voxel of a box [regionMin, regionMax]. The GLSL twin of caoLAO.cxx: the
// same taps, the same trilinear blend (x, then y, then z; a + t * (b - a)),
// the same loop order; `precise` forbids FMA contraction and reassociation.
//
// After caoVolumeOpacity.glsl (the input's opacity, VolumeOpacity).
// Specialisation (prepended #defines; the defaults let the file compile alone):
//   CAO_OPACITY_SOURCE  see caoVolumeOpacity.glsl
//   CAO_CLIPPED         0: unclipped opacity (the precompute)
//                       1: opacity * clipFactor[coverage count] (the clipped volume)
//   CAO_SELECT          0: every voxel of the box
//                       1: only category-b voxels (the CAO recompute)
//                       2: every voxel not in category a (the full recompute)
//                       3: verification of every voxel not in category a:
//                          the clipped march against the stored current AO,
//                          and, for category c, the clipped march against the
//                          unclipped one in float, bit for bit (counters)
//   CAO_LOCAL_X/Y/Z     workgroup size
#ifndef CAO_OPACITY_SOURCE
#define CAO_OPACITY_SOURCE 1
#endif
#ifndef CAO_CLIPPED
#define CAO_CLIPPED 0
#endif
#ifndef CAO_SELECT
#define CAO_SELECT 0
#endif
#ifndef CAO_LOCAL_X
#define CAO_LOCAL_X 8
#define CAO_LOCAL_Y 8
#define CAO_LOCAL_Z 1
#endif

layout(local_size_x = CAO_LOCAL_X, local_size_y = CAO_LOCAL_Y, local_size_z = CAO_LOCAL_Z) in;

layout(std140, binding = CAO_BINDING_LAO_MARCH) uniform LAOBlock
{
  LAOMarchBlock lao;
};
layout(std430, binding = CAO_BINDING_TAPS) readonly buffer TapBlock
{
  LAOTap taps[];
};
layout(std430, binding = CAO_BINDING_CLIP_FACTORS) readonly buffer ClipFactorBlock
{
  float clipFactor[];
};

#if CAO_CLIPPED || CAO_SELECT != 0
layout(binding = CAO_IMAGE_STATE, r8ui) uniform readonly uimage3D stateImage;
#endif
#if CAO_SELECT == 3
layout(binding = CAO_IMAGE_AO_OUT, r16ui) uniform readonly uimage3D aoImage;
layout(std430, binding = CAO_BINDING_COUNTERS) buffer CounterBlock
{
  uint counters[4]; // stored mismatches, float mismatches, max |float diff| bits
};
#else
layout(binding = CAO_IMAGE_AO_OUT, r16ui) uniform writeonly uimage3D aoImage;
#endif

uniform ivec3 regionMin;
uniform ivec3 regionMax;

/// Opacity at a voxel; 0 outside the volume (as the CPU march).
float OpacityAt(ivec3 p, bool clippedOpacity)
{
  if (any(lessThan(p, ivec3(0))) || any(greaterThanEqual(p, lao.dims.xyz)))
    return 0.0;
  float a = VolumeOpacity(p);
#if CAO_CLIPPED
  if (clippedOpacity)
  {
    precise float clipped = a * clipFactor[imageLoad(stateImage, p).r & uint(CAO_STATE_COUNT_MASK)];
    return clipped;
  }
#endif
  return a;
}

float Lerp(float a, float b, float t)
{
  precise float r = a + t * (b - a);
  return r;
}

/// The LAO of voxel p on the clipped (or unclipped) opacity.
float March(ivec3 p, bool clippedOpacity)
{
  const int rays = lao.rays.x;
  const int samples = lao.rays.y;
  const int tapsPerRay = lao.rays.z;
  // Interleaved variation: the variant is the parity of the global voxel
  // index (the origin's parity bits are in dims.w), as VariantOf in caoLAO.cxx.
  int variant = 0;
  if (lao.rays.w != 1)
  {
    ivec3 parity = (p ^ ivec3(lao.dims.w, lao.dims.w >> 1, lao.dims.w >> 2)) & 1;
    variant = parity.x | (parity.y << 1) | (parity.z << 2);
  }
  const int variantBase = variant * rays * tapsPerRay;
  precise float total = 0.0;
  for (int r = 0; r < rays; ++r)
  {
    precise float transmittance = 1.0;
    precise float sum = 0.0;
    for (int m = 0; m < samples; ++m)
    {
      sum += transmittance;
      if (m == tapsPerRay)
        break;
      LAOTap t = taps[variantBase + r * tapsPerRay + m];
      ivec3 c = p + t.cell.xyz;
      bool k = clippedOpacity;
      float c00 = Lerp(OpacityAt(c, k), OpacityAt(c + ivec3(1, 0, 0), k), t.frac.x);
      float c10 = Lerp(OpacityAt(c + ivec3(0, 1, 0), k), OpacityAt(c + ivec3(1, 1, 0), k), t.frac.x);
      float c01 = Lerp(OpacityAt(c + ivec3(0, 0, 1), k), OpacityAt(c + ivec3(1, 0, 1), k), t.frac.x);
      float c11 = Lerp(OpacityAt(c + ivec3(0, 1, 1), k), OpacityAt(c + ivec3(1, 1, 1), k), t.frac.x);
      float alpha = Lerp(Lerp(c00, c10, t.frac.y), Lerp(c01, c11, t.frac.y), t.frac.z);
      transmittance = transmittance * (1.0 - alpha);
      if (transmittance == 0.0)
        break; // every later term adds exactly 0
    }
    total += sum;
  }
  precise float ao = total / lao.norm.x;
  return ao;
}

uint Quantize(float ao)
{
  precise float scaled = ao * float(CAO_AO_SCALE) + 0.5;
  return uint(scaled);
}

void main()
{
  ivec3 p = regionMin + ivec3(gl_GlobalInvocationID);
  if (any(greaterThan(p, regionMax)))
    return;
#if CAO_SELECT != 0
  int category = int(imageLoad(stateImage, p).r) >> CAO_STATE_CATEGORY_SHIFT;
#if CAO_SELECT == 1
  if (category != CAO_CATEGORY_AFFECTED)
    return;
#else
  if (category == CAO_CATEGORY_CLIPPED)
    return;
#endif
#endif
#if CAO_SELECT == 3
  float full = March(p, true);
  if (Quantize(full) != imageLoad(aoImage, p).r)
    atomicAdd(counters[0], 1u);
  if (category == CAO_CATEGORY_UNAFFECTED)
  {
    float unclipped = March(p, false);
    if (floatBitsToUint(unclipped) != floatBitsToUint(full))
    {
      atomicAdd(counters[1], 1u);
      atomicMax(counters[2], floatBitsToUint(abs(unclipped - full)));
    }
  }
#else
  imageStore(aoImage, p, uvec4(Quantize(March(p, CAO_CLIPPED != 0))));
#endif
}
