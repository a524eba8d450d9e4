// caoConeTrace.glsl - the GPU side of cao::ConeTraceAO (caoVoxelConeTracing.cxx),
// in float: per point, the six cones of tangent spheres, each sphere's
// occlusion the set bits over the bits counted in its z-column prisms
// (bitfieldExtract and bitCount per word; occupancy "volume"), the cones'
// front-to-back products, weighted; or (occupancy "rays", vct.apex.y = 1)
// each cone's occlusion the cosine-weighted share of its rays that meet a
// set voxel. The plan (cones, spheres, prism samples) comes from the
// host's VCTPlan. Occluding volumes (vct.volumeCount.x of them): each
// sphere also sees a volume's mean opacity at its centre and prism points,
// over its diameter (cao::SphereOpacity's twin, trilinear by hand as the
// CPU's OpacityVolume::Sample, so both read the same values).
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
layout(std430, binding = CAO_BINDING_VCT_OPACITY) readonly buffer OpacityBlock
{
  float opacity[];
};
layout(std430, binding = CAO_BINDING_VCT_COLUMNS) readonly buffer ColumnBlock
{
  vec2 columns[]; // the frustum grid's: per column near depth, slices per depth
};

/// The frustum grid (vct.frustum[4].x = 1): BitGrid::FrustumCell's twin,
/// point g (the grid's frame) to column (i, j) and slice coordinate s;
/// false off the screen or behind the eye.
bool FrustumCell(vec3 g, out int i, out int j, out float s)
{
  vec4 c = vec4(dot(vct.frustum[0].xyz, g) + vct.frustum[0].w, dot(vct.frustum[1].xyz, g) + vct.frustum[1].w,
    dot(vct.frustum[2].xyz, g) + vct.frustum[2].w, dot(vct.frustum[3].xyz, g) + vct.frustum[3].w);
  bool perspective = vct.frustum[4].y > 0.5;
  i = 0;
  j = 0;
  s = -1.0;
  if (perspective && !(c.w > 0.0))
    return false;
  float x = (c.x / c.w + 1.0) * 0.5 * float(vct.grid.x), y = (c.y / c.w + 1.0) * 0.5 * float(vct.grid.y);
  if (!(x >= 0.0 && y >= 0.0 && x < float(vct.grid.x) && y < float(vct.grid.y)))
    return false;
  i = int(x);
  j = int(y);
  vec2 column = columns[j * vct.grid.x + i];
  s = ((perspective ? c.w : c.z / c.w) - column.x) * column.y;
  return true;
}

/// BitGrid::FrustumVoxel(g, larger = true): the larger of a pixel's width
/// and its column's slice at g (world units).
float FrustumVoxel(vec3 g)
{
  float w = dot(vct.frustum[3].xyz, g) + vct.frustum[3].w;
  float x = dot(vct.frustum[0].xyz, g) + vct.frustum[0].w;
  float rate = abs((vct.frustum[0].x * w - x * vct.frustum[3].x) / (w * w));
  float voxel = 1.0 / vct.origin.w;
  float pixel = rate > 0.0 ? 2.0 / (float(vct.grid.x) * rate) : voxel;
  int i, j;
  float s;
  float slice = voxel;
  if (FrustumCell(g, i, j, s))
    slice = vct.frustum[4].z / columns[j * vct.grid.x + i].y;
  float v = max(pixel, slice);
  return v > 0.0 && !isinf(v) && !isnan(v) ? v : voxel;
}

/// Volume v's trilinear opacity at g (the grid's frame); 0 outside it.
float VolumeSample(int v, vec3 g)
{
  VCTVolume vol = vct.volumes[v];
  vec3 x = vec3(dot(vol.toIndex[0].xyz, g) + vol.toIndex[0].w, dot(vol.toIndex[1].xyz, g) + vol.toIndex[1].w,
    dot(vol.toIndex[2].xyz, g) + vol.toIndex[2].w);
  ivec3 dims = vol.dims.xyz;
  if (!(x.x >= 0.0 && x.y >= 0.0 && x.z >= 0.0) || x.x > float(dims.x - 1) || x.y > float(dims.y - 1) ||
    x.z > float(dims.z - 1))
    return 0.0;
  ivec3 i0 = min(ivec3(x), max(ivec3(0), dims - 2));
  vec3 f = x - vec3(i0);
  ivec3 stride = ivec3(dims.x > 1 ? 1 : 0, dims.y > 1 ? dims.x : 0, dims.z > 1 ? dims.x * dims.y : 0);
  int base = vol.dims.w + i0.x + i0.y * dims.x + i0.z * dims.x * dims.y;
  float value = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
    float w = (bx != 0 ? f.x : 1.0 - f.x) * (by != 0 ? f.y : 1.0 - f.y) * (bz != 0 ? f.z : 1.0 - f.z);
    if (w > 0.0)
      value += w * opacity[base + bx * stride.x + by * stride.y + bz * stride.z];
  }
  return value;
}

/// cao::SphereOpacity: the mean opacity at the centre and the prism points
/// (the sphere's disk across the grid's z axis), over the diameter
/// (cao::CorrectOpacity).
float SphereOpacity(int v, vec3 centre, float r)
{
  float sum = VolumeSample(v, centre);
  for (int k = 0; k < vct.counts.z; ++k)
    sum += VolumeSample(v, centre + r * vec3(vct.disk[k].xy, 0.0));
  float mean = sum / float(vct.counts.z + 1);
  if (!(mean > 0.0))
    return 0.0;
  if (mean >= 1.0)
    return 1.0;
  return 1.0 - pow(1.0 - mean, 2.0 * r * vct.volumes[v].scalars.x);
}

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

/// (x, y) turned in their plane: x c + y s, y c - x s (cao's Turn).
void Turn(float c, float s, inout vec3 x, inout vec3 y)
{
  vec3 a = x;
  x = a * c + y * s;
  y = y * c - a * s;
}

bool Bit(int i, int j, int k)
{
  if (i < 0 || j < 0 || k < 0 || i >= vct.grid.x || j >= vct.grid.y || k >= vct.grid.z)
    return false;
  uint word = bits[uint(j * vct.grid.x + i) * uint(vct.grid.w) + uint(k >> 5)];
  return ((word >> uint(k & 31)) & 1u) != 0u;
}

/// cao::RayOcclusion: the cosine-weighted share of the cone's rays (one per
/// prism point, from the first sphere's near side, or 3 voxels out if that
/// is nearer on a world or eye grid, to R) that meet a set voxel; on a world
/// or eye grid only the steps that can be inside the grid are visited.
float RayOcclusion(vec3 apex, vec3 n, vec3 dir, vec3 u, vec3 v, float rayStep)
{
  bool frustum = vct.frustum[4].x > 0.5;
  float invH = vct.origin.w;
  float nearSide = vct.spheres[0].x - vct.spheres[0].y;
  float t0 = frustum ? nearSide : min(nearSide, 3.0 / invH);
  float t1 = vct.spheres[vct.counts.y - 1].x + vct.spheres[vct.counts.y - 1].y;
  vec3 boxLo = vct.origin.xyz, boxHi = vct.origin.xyz + vec3(vct.grid.xyz) / invH;
  float blocked = 0.0, all = 0.0;
  for (int k = 0; k < vct.counts.z; ++k)
  {
    vec4 d = vct.disk[k];
    vec3 ray = dir + vct.apex.w * (d.x * u + d.y * v);
    float len = length(ray);
    float weight = max(0.0, dot(ray, n) / len);
    all += weight;
    int steps = max(1, int(ceil((t1 - t0) * len / rayStep)));
    float step = (t1 - t0) / float(steps);
    int mBegin = 0, mEnd = steps;
    if (!frustum)
    {
      float enter = t0, exit = t1;
      for (int d = 0; d < 3; ++d)
      {
        if (ray[d] == 0.0)
        {
          if (apex[d] < boxLo[d] || apex[d] > boxHi[d])
            exit = -1.0;
          continue;
        }
        float a = (boxLo[d] - apex[d]) / ray[d], b = (boxHi[d] - apex[d]) / ray[d];
        enter = max(enter, min(a, b));
        exit = min(exit, max(a, b));
      }
      if (exit < enter - step)
        continue;
      mBegin = max(0, int(floor((enter - t0) / step)) - 1);
      mEnd = min(steps, int(ceil((exit - t0) / step)) + 1);
    }
    for (int m = mBegin; m < mEnd; ++m)
    {
      float tau = t0 + (float(m) + 0.5) * step;
      if (frustum)
      {
        int i, j;
        float sl;
        if (FrustumCell(apex + tau * ray, i, j, sl) && sl >= 0.0 && sl < float(vct.grid.z) &&
          Bit(i, j, int(sl)))
        {
          blocked += weight;
          break;
        }
        continue;
      }
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
  if (vct.counts.y == 0) // no sphere: a radius under the voxel (cao::VCTUnresolvedRadius), no AO
  {
    ao[index] = 1.0;
    return;
  }
  vec3 p = points[index].xyz, n = normals[index].xyz;
  float invH = vct.origin.w;
  vec3 tx, ty;
  Frame(n, tx, ty);
  // Pixels (vct.volumeCount.y: their rows' length): the cones turned by
  // the 4 x 4 pattern's angle of the pixel's cell (cao::VCTPixelRotation).
  float turn = 0.0;
  int row = vct.volumeCount.y;
  if (row > 0)
  {
    int cell = ((index % row) & 3) + 4 * ((index / row) & 3);
    turn = vct.rotations[cell >> 2][cell & 3];
  }
  float cosTurn = cos(turn), sinTurn = sin(turn);
  Turn(cosTurn, sinTurn, tx, ty);
  // The frustum grid's voxels grow with depth: the apex offset and the
  // rays' step follow the local voxel's larger side (ConeTraceAO's).
  bool frustum = vct.frustum[4].x > 0.5;
  float scale = frustum ? FrustumVoxel(p) * vct.origin.w : 1.0;
  vec3 apex = p + scale * vct.apex.x * n;
  float occlusion = 0.0;
  for (int c = 0; c < vct.counts.x; ++c)
  {
    vec4 l = vct.cones[c];
    vec3 dir = l.x * tx + l.y * ty + l.z * n;
    vec3 u, v; // the rays' frame across the cone's axis
    Frame(dir, u, v);
    Turn(cosTurn, sinTurn, u, v);
    // Rays: the cone's rays at once; volume: each sphere's prisms. Then the
    // volumes' opacity over each sphere.
    bool rays = vct.apex.y > 0.5;
    float open = rays ? 1.0 - RayOcclusion(apex, n, dir, u, v, scale * vct.apex.z) : 1.0;
    for (int s = 0; s < vct.counts.y; ++s)
    {
      vec3 centre = apex + vct.spheres[s].x * dir;
      float r = vct.spheres[s].y;
      for (int vol = 0; vol < vct.volumeCount.x; ++vol)
        open *= 1.0 - SphereOpacity(vol, centre, r);
      if (rays)
        continue;
      float gz = (centre.z - vct.origin.z) * invH;
      int set = 0, total = 0;
      for (int k = 0; k < vct.counts.z && frustum; ++k)
      {
        // Each prism the column its disk point falls in, over its chord's
        // slices (SphereOccupancy's frustum branch).
        vec4 d = vct.disk[k];
        int i, j;
        float sc;
        if (!FrustumCell(centre + r * vec3(d.xy, 0.0), i, j, sc))
          continue;
        float ds = r * d.z / vct.frustum[4].z * columns[j * vct.grid.x + i].y;
        float sn = clamp(sc - ds, -1.0, float(vct.grid.z) + 1.0), sf = clamp(sc + ds, -1.0, float(vct.grid.z) + 1.0);
        int k0 = int(ceil(min(sn, sf) - 0.5));
        int k1 = int(floor(max(sn, sf) - 0.5));
        if (k1 < k0)
        {
          k0 = int(floor(clamp(sc, -1.0, float(vct.grid.z) + 1.0)));
          k1 = k0;
        }
        total += k1 - k0 + 1;
        set += CountBits(i, j, k0, k1);
      }
      for (int k = 0; k < vct.counts.z && !frustum; ++k)
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
