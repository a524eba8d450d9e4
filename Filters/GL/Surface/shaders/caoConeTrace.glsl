// caoConeTrace.glsl - the GPU side of cao::ConeTraceAO (caoVoxelConeTracing.cxx),
// in float: per point, the six cones of tangent spheres, each sphere's
// occlusion the set bits over the bits counted in its z-column prisms
// (bitfieldExtract and bitCount per word; occupancy "volume"), the cones'
// front-to-back products, weighted; or (occupancy "rays", vct.apex.y = 1)
// each cone's occlusion the cosine-weighted share of its rays that meet a
// set voxel. The plan (cones, spheres, prism samples) comes from the
// host's VCTPlan.
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_VCT_PARAMS) uniform VCTBlock
{
  VCTParams vct;
};
layout(std430, binding = CAO_BINDING_VX_BITS) readonly buffer BitBlock
{
  uint bits[];
};
layout(std430, binding = CAO_BINDING_VCT_POINTS) readonly buffer PointBlock
{
  vec4 points[];
};
layout(std430, binding = CAO_BINDING_VCT_NORMALS) readonly buffer NormalBlock
{
  vec4 normals[];
};
layout(std430, binding = CAO_BINDING_VCT_AO) writeonly buffer AOBlock
{
  float ao[];
};

/// Set bits in slices [k0, k1] of column (i, j); 0 outside the grid.
int CountBits(int i, int j, int k0, int k1)
{
  if (i < 0 || j < 0 || i >= vct.grid.x || j >= vct.grid.y)
    return 0;
  k0 = max(k0, 0);
  k1 = min(k1, vct.grid.z - 1);
  if (k1 < k0)
    return 0;
  uint column = uint(j * vct.grid.x + i) * uint(vct.grid.w);
  int count = 0;
  for (int w = k0 >> 5; w <= (k1 >> 5); ++w)
  {
    int lo = w == (k0 >> 5) ? (k0 & 31) : 0, hi = w == (k1 >> 5) ? (k1 & 31) : 31;
    count += bitCount(bitfieldExtract(bits[column + uint(w)], lo, hi - lo + 1));
  }
  return count;
}

/// An orthonormal frame (x, y) around the unit vector n (Duff et al. 2017),
/// as the CPU's Frame.
void Frame(vec3 n, out vec3 x, out vec3 y)
{
  float sgn = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sgn + n.z);
  float b = n.x * n.y * a;
  x = vec3(1.0 + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
  y = vec3(b, sgn + n.y * n.y * a, -n.y);
}

bool Bit(int i, int j, int k)
{
  if (i < 0 || j < 0 || k < 0 || i >= vct.grid.x || j >= vct.grid.y || k >= vct.grid.z)
    return false;
  uint word = bits[uint(j * vct.grid.x + i) * uint(vct.grid.w) + uint(k >> 5)];
  return ((word >> uint(k & 31)) & 1u) != 0u;
}

/// cao::RayOcclusion: the cosine-weighted share of the cone's rays (one per
/// prism point, from the first sphere's near side to R) that meet a set voxel.
float RayOcclusion(vec3 apex, vec3 n, vec3 dir, vec3 u, vec3 v)
{
  float invH = vct.origin.w;
  float t0 = vct.spheres[0].x - vct.spheres[0].y;
  float t1 = vct.spheres[vct.counts.y - 1].x + vct.spheres[vct.counts.y - 1].y;
  float blocked = 0.0, all = 0.0;
  for (int k = 0; k < vct.counts.z; ++k)
  {
    vec4 d = vct.disk[k];
    vec3 ray = dir + vct.apex.w * (d.x * u + d.y * v);
    float len = length(ray);
    float weight = max(0.0, dot(ray, n) / len);
    all += weight;
    int steps = max(1, int(ceil((t1 - t0) * len / vct.apex.z)));
    float step = (t1 - t0) / float(steps);
    for (int m = 0; m < steps; ++m)
    {
      float tau = t0 + (float(m) + 0.5) * step;
      vec3 g = floor((apex + tau * ray - vct.origin.xyz) * invH);
      if (Bit(int(g.x), int(g.y), int(g.z)))
      {
        blocked += weight;
        break;
      }
    }
  }
  return all > 0.0 ? blocked / all : 0.0;
}

void main()
{
  int index = int(gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u);
  if (index >= vct.counts.w)
    return;
  if (normals[index].w == 0.0) // no point (a pixel not covered)
  {
    ao[index] = uintBitsToFloat(0x7fc00000u);
    return;
  }
  vec3 p = points[index].xyz, n = normals[index].xyz;
  float invH = vct.origin.w;
  vec3 tx, ty;
  Frame(n, tx, ty);
  vec3 apex = p + vct.apex.x * n;
  float occlusion = 0.0;
  for (int c = 0; c < vct.counts.x; ++c)
  {
    vec4 l = vct.cones[c];
    vec3 dir = l.x * tx + l.y * ty + l.z * n;
    vec3 u, v; // the rays' frame across the cone's axis
    Frame(dir, u, v);
    if (vct.apex.y > 0.5)
    {
      occlusion += l.w * RayOcclusion(apex, n, dir, u, v);
      continue;
    }
    float open = 1.0;
    for (int s = 0; s < vct.counts.y; ++s)
    {
      vec3 centre = apex + vct.spheres[s].x * dir;
      float r = vct.spheres[s].y;
      float gz = (centre.z - vct.origin.z) * invH;
      int set = 0, total = 0;
      for (int k = 0; k < vct.counts.z; ++k)
      {
        vec4 d = vct.disk[k];
        float gx = (centre.x + r * d.x - vct.origin.x) * invH;
        float gy = (centre.y + r * d.y - vct.origin.y) * invH;
        int i = int(floor(gx)), j = int(floor(gy));
        float chord = r * d.z * invH;
        int k0 = int(ceil(gz - chord - 0.5));
        int k1 = int(floor(gz + chord - 0.5));
        if (k1 < k0)
        {
          k0 = int(floor(gz));
          k1 = k0;
        }
        total += k1 - k0 + 1;
        set += CountBits(i, j, k0, k1);
      }
      float occ = total > 0 ? float(set) / float(total) : 0.0;
      open *= 1.0 - occ;
    }
    occlusion += l.w * (1.0 - open);
  }
  ao[index] = 1.0 - occlusion;
}
