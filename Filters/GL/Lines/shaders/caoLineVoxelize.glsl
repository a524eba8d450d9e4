// caoLineVoxelize.glsl - the GPU side of cao::VoxelizeLines (caoLineAO.cxx),
// in float, one invocation per segment: the segment is cut into pieces at
// most LineVoxelizeParams.tube.z voxels long, and every voxel of a piece's
// box (grown by the tube radius and a voxel) is set when the piece passes
// through its closed cube (the supercover) or its centre lies within the
// tube radius of the piece, as the CPU twin decides it in double. The
// host maps the ends to voxel units (grid frame, origin 0) in double, or
// (CAO_LV_WORLD) this shader does, in double, from the world segments.
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_LV_PARAMS) uniform LineVoxelizeBlock
{
  LineVoxelizeParams lv;
};
#ifdef CAO_LV_WORLD
// The world segments the G-buffer reads (two dvec4 a segment), mapped to
// voxel units here in double as the host maps them (caoLineGridMap.glsl,
// included before this file), then rounded to float.
layout(std140, binding = CAO_BINDING_LV_MAP) uniform LineGridMapBlock
{
  LineGridMap map;
};
layout(std430, binding = CAO_BINDING_LV_ENDS) readonly buffer EndsBlock
{
  dvec4 worldEnds[];
};
vec3 End(int e)
{
  return vec3(GridVoxels(map, worldEnds[e].xyz));
}
#else
layout(std430, binding = CAO_BINDING_LV_ENDS) readonly buffer EndsBlock
{
  vec4 ends[];
};
vec3 End(int e)
{
  return ends[e].xyz;
}
#endif
layout(std430, binding = CAO_BINDING_LV_BITS) buffer BitsBlock
{
  uint bits[];
};

/// Whether p0 + s d, s in [0, 1], meets the closed box [lo, hi]
/// (the twin's ClipToBox).
bool ClipToBox(vec3 p0, vec3 d, vec3 lo, vec3 hi)
{
  float s0 = 0.0, s1 = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (p0[a] < lo[a] || p0[a] > hi[a])
        return false;
      continue;
    }
    float t0 = (lo[a] - p0[a]) / d[a], t1 = (hi[a] - p0[a]) / d[a];
    if (t0 > t1)
    {
      const float t = t0;
      t0 = t1;
      t1 = t;
    }
    s0 = max(s0, t0);
    s1 = min(s1, t1);
    if (s0 > s1)
      return false;
  }
  return true;
}

/// The squared distance from q to the segment [p0, p0 + d] (the twin's
/// SegmentDistance2).
float SegmentDistance2(vec3 q, vec3 p0, vec3 d)
{
  const float dd = dot(d, d);
  const float s = dd > 0.0 ? clamp(dot(q - p0, d) / dd, 0.0, 1.0) : 0.0;
  const vec3 e = q - (p0 + s * d);
  return dot(e, e);
}

void main()
{
  // (DispatchLinear spreads more than 65 535 groups over y.)
  const int segment = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (segment >= lv.counts.x)
    return;
  const vec3 a = End(2 * segment), b = End(2 * segment + 1);
  const vec3 d = b - a;
  const float rho = lv.tube.x, rho2 = lv.tube.y;
  const ivec3 dims = lv.grid.xyz;
  const int pieces = max(1, int(ceil(length(d) / lv.tube.z)));
  for (int p = 0; p < pieces; ++p)
  {
    const vec3 p0 = a + d * (float(p) / float(pieces));
    const vec3 p1 = p + 1 == pieces ? b : a + d * (float(p + 1) / float(pieces));
    const vec3 pd = p1 - p0;
    // The piece's box, a voxel and the tube radius around it, clamped to
    // the grid before the cast.
    const vec3 first = max(vec3(0.0), floor(min(p0, p1) - rho) - 1.0);
    const vec3 last = min(vec3(dims) - 1.0, floor(max(p0, p1) + rho) + 1.0);
    if (any(greaterThan(first, last)))
      continue;
    const ivec3 lo = ivec3(first), hi = ivec3(last);
    for (int k = lo.z; k <= hi.z; ++k)
      for (int j = lo.y; j <= hi.y; ++j)
        for (int i = lo.x; i <= hi.x; ++i)
        {
          const vec3 cell = vec3(i, j, k);
          bool set = ClipToBox(p0, pd, cell, cell + 1.0);
          if (!set && rho > 0.0)
            set = SegmentDistance2(cell + 0.5, p0, pd) <= rho2;
          if (set)
            atomicOr(bits[(j * dims.x + i) * lv.grid.w + (k >> 5)], 1u << uint(k & 31));
        }
  }
}
