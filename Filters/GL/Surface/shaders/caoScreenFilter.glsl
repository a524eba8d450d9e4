// caoScreenFilter.glsl - the GPU side of cao::DepthAwareFilter
// (caoScreenSpaceAO.cxx: FinishHBAO's blur, FinishVolumetricAO's filter), in float,
// one invocation per pixel: the weighted mean of the covered taps of a
// (2r + 1)^2 window whose points lie within the tolerance of the pixel's
// tangent plane (and, ss.finish.w > 0, within that reach of its point;
// weights per axis, multiplied), then (Volumetric AO) clamped to
// [0, 1]. Reads the estimator's AO (NaN: not covered), writes the filtered
// AO (NaN: not covered) where the frame's combine reads it. After
// caoScreenCommon.glsl.
layout(std430, binding = CAO_BINDING_SS_AO) readonly buffer RawBlock
{
  float raw[];
};
layout(std430, binding = CAO_BINDING_SS_FILTERED) writeonly buffer FilteredBlock
{
  float filtered[];
};

float Weight(int tap)
{
  return ss.finishWeights[tap >> 2][tap & 3];
}

void main()
{
  int k = int(gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u);
  int w = ss.image.x, h = ss.image.y;
  if (k >= w * h)
    return;
  float own = raw[k];
  if (!Covered(k) || isnan(own))
  {
    filtered[k] = uintBitsToFloat(0x7fc00000u);
    return;
  }
  int r = int(ss.finish.x);
  float value = own;
  if (r > 0)
  {
    int i = k % w, j = k / w;
    vec3 p = positions[k].xyz, n = normals[k].xyz;
    float sum = 0.0, weight = 0.0;
    for (int dj = -r; dj <= r; ++dj)
      for (int di = -r; di <= r; ++di)
      {
        int ii = i + di, jj = j + dj;
        if (ii < 0 || jj < 0 || ii >= w || jj >= h)
          continue;
        int q = jj * w + ii;
        float a = raw[q];
        if (!Covered(q) || isnan(a))
          continue;
        vec3 d = positions[q].xyz - p;
        if (!(abs(dot(d, n)) <= ss.finish.y) || (ss.finish.w > 0.0 && !(dot(d, d) <= ss.finish.w * ss.finish.w)))
          continue;
        float wt = Weight(di + r) * Weight(dj + r);
        sum += wt * a;
        weight += wt;
      }
    if (weight > 0.0)
      value = sum / weight;
  }
  filtered[k] = ss.finish.z > 0.5 ? clamp(value, 0.0, 1.0) : value;
}
