// caoLineAO.glsl - the GPU side of cao::LineAOFrame (caoLineAO.cxx), in
// float, one invocation per covered pixel of the pixel's half ball (set up
// by the host in double: caoGPULayout.h's LineAOPixel): with flag 4 the
// rays of cao::LineRaysOf marched through the lines' bit grid (and the
// solids'); else the prisms counted in it, weighted as cao::LineOccupancyOf
// weights them, and turned into AO as cao::LineFrameAO does.
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_LA_PARAMS) uniform LineAOBlock
{
  LineAOParams la;
};
layout(std430, binding = CAO_BINDING_LA_BITS) readonly buffer BitsBlock
{
  uint bits[];
};
layout(std430, binding = CAO_BINDING_LA_SOLIDS) readonly buffer SolidsBlock
{
  uint solids[];
};
layout(std430, binding = CAO_BINDING_LA_PIXELS) readonly buffer PixelsBlock
{
  LineAOPixel balls[];
};
layout(std430, binding = CAO_BINDING_LA_SAMPLES) readonly buffer SamplesBlock
{
  vec4 disk[];
};
layout(std430, binding = CAO_BINDING_LA_AO) writeonly buffer AOBlock
{
  float ao[];
};

/// Set bits in slices [k0, k1] of column (i, j) of the lines' grid
/// (solid: the solids'), clamped; 0 outside (cao::BitGrid::CountBits).
int CountBits(bool solid, int i, int j, int k0, int k1)
{
  if (i < 0 || j < 0 || i >= la.grid.x || j >= la.grid.y)
    return 0;
  k0 = max(k0, 0);
  k1 = min(k1, la.grid.z - 1);
  if (k1 < k0)
    return 0;
  int column = (j * la.grid.x + i) * la.grid.w;
  int count = 0;
  for (int w = k0 >> 5; w <= (k1 >> 5); ++w)
  {
    uint word = solid ? solids[column + w] : bits[column + w];
    int lo = w == (k0 >> 5) ? (k0 & 31) : 0, hi = w == (k1 >> 5) ? (k1 & 31) : 31;
    word &= (0xffffffffu << uint(lo)) & (0xffffffffu >> uint(31 - hi));
    count += bitCount(word);
  }
  return count;
}

/// Clamped to just outside the grid before the cast (CountBits counts
/// nothing there), as the CPU's index().
int Index(float v, int n)
{
  return int(min(float(n), max(-1.0, v)));
}

/// Bit (i, j, k) of the lines' grid (solid: the solids'); false outside.
bool Bit(bool solid, ivec3 c)
{
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, la.grid.xyz)))
    return false;
  int word = (c.y * la.grid.x + c.x) * la.grid.w + (c.z >> 5);
  return (((solid ? solids[word] : bits[word]) >> uint(c.z & 31)) & 1u) != 0u;
}

/// cao::LineRaysOf: cosine-distributed rays from the centre to R, each line
/// voxel past the base plane passing exp(-sigma l), a solid one nothing.
float Rays(vec3 o, vec3 w, float base, int first, bool withSolids)
{
  const float R = la.scalars.x, sigma = la.paper.y, offset = la.paper.z;
  const int count = la.counts.x;
  vec3 t1 = normalize(cross(w, abs(w.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 t2 = cross(w, t1);
  vec2 shift = 0.5 * (disk[first].xy + 1.0);
  // (cao::LineRaysOf: a centre outside the grid padded by R sees nothing;
  // a walk stops once outside and leaving, and visits at most the grid's
  // cells.)
  if (any(lessThanEqual(o, vec3(-R - 1.0))) || any(greaterThanEqual(o, vec3(la.grid.xyz) + R + 1.0)) ||
    any(isnan(o)))
    return 1.0;
  const int cells = la.grid.x + la.grid.y + la.grid.z + 3;
  float sum = 0.0;
  for (int n = 0; n < count; ++n)
  {
    // cao::HemisphereDirection: Hammersley, turned by the pixel's set.
    float u = fract((float(n) + 0.5) / float(count) + shift.x);
    float v = fract(float(bitfieldReverse(uint(n))) * 2.3283064365386963e-10 + shift.y);
    float r = sqrt(u), phi = 6.283185307179586 * v;
    vec3 d = r * cos(phi) * t1 + r * sin(phi) * t2 + sqrt(max(0.0, 1.0 - u)) * w;
    ivec3 cell = ivec3(floor(o));
    ivec3 stepDir = ivec3(d.x > 0.0 ? 1 : -1, d.y > 0.0 ? 1 : -1, d.z > 0.0 ? 1 : -1);
    vec3 magnitude = abs(d);
    vec3 delta, next;
    for (int c = 0; c < 3; ++c)
    {
      bool moves = magnitude[c] > 1e-12;
      delta[c] = moves ? 1.0 / magnitude[c] : 1e30;
      next[c] = moves ? (d[c] > 0.0 ? float(cell[c]) + 1.0 - o[c] : o[c] - float(cell[c])) / magnitude[c] : 1e30;
    }
    float t = 0.0, depth = 0.0;
    bool blocked = false;
    for (int visited = 0; t < R && visited < cells; ++visited)
    {
      int c = next.x <= next.y && next.x <= next.z ? 0 : next.y <= next.z ? 1 : 2;
      float leave = min(next[c], R);
      bool away = false;
      for (int a = 0; a < 3; ++a)
        away = away || (cell[a] < 0 && stepDir[a] < 0) || (cell[a] >= la.grid[a] && stepDir[a] > 0);
      if (away)
        break; // (outside, leaving: the rest of the ray is empty)
      if (dot(vec3(cell) + 0.5 - o, w) >= base)
      {
        // (cao::LineSolidOffset: a mesh's voxels overhang its surface.)
        if (withSolids && t >= CAO_LINE_SOLID_OFFSET && Bit(true, cell))
        {
          blocked = true;
          break;
        }
        // (LineAOSettings::voxelOffset: a tube's voxels overhang its surface too.)
        if (Bit(false, cell) && leave > offset)
          depth += leave - max(t, offset);
      }
      t = leave;
      next[c] += delta[c];
      cell[c] += stepDir[c];
    }
    if (!blocked)
      sum += exp(-sigma * depth);
  }
  return sum / float(count);
}

void main()
{
  int k = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (k >= la.counts.y)
    return;
  LineAOPixel ball = balls[k];
  if ((ball.pixel.y & 4) != 0)
  {
    ao[k] = uintBitsToFloat(0x7fc00000u); // (no line: NaN)
    return;
  }
  const vec3 centre = ball.centre.xyz, w = ball.plane.xyz, T = ball.tangent.xyz;
  const float base = ball.centre.w;
  const bool line = (ball.pixel.y & 1) != 0, cosine = (ball.pixel.y & 2) != 0;
  const bool paper = (la.counts.z & 1) != 0, withSolids = (la.counts.z & 2) != 0;
  const float R = la.scalars.x, h = la.scalars.y;
  const int samples = la.counts.x, first = ball.pixel.z * samples;
  if ((la.counts.z & 4) != 0)
  {
    ao[k] = Rays(centre, w, base, first, withSolids);
    return;
  }
  float sum = 0.0, solidSum = 0.0, weights = 0.0;
  for (int n = 0; n < samples; ++n)
  {
    vec2 s = disk[first + n].xy;
    // The prism along the view axis through the voxel centres of the
    // column nearest the sample.
    float ci = floor(centre.x + R * s.x), cj = floor(centre.y + R * s.y);
    vec3 c = vec3(ci + 0.5, cj + 0.5, centre.z);
    float lateral2 = (c.x - centre.x) * (c.x - centre.x) + (c.y - centre.y) * (c.y - centre.y);
    float halfChord = sqrt(max(0.0, R * R - lateral2));
    float u0 = -halfChord, u1 = halfChord;
    float along = dot(c - centre, w);
    if (abs(w.z) < 1e-12)
    {
      if (along < base)
        continue;
    }
    else if (w.z > 0.0)
      u0 = max(u0, (base - along) / w.z);
    else
      u1 = min(u1, (base - along) / w.z);
    if (!(u0 <= u1))
      continue;
    float k0 = ceil(c.z + u0 - 0.5), k1 = floor(c.z + u1 - 0.5);
    if (!(k0 <= k1))
      continue;
    int i = Index(ci, la.grid.x), j = Index(cj, la.grid.y), kf = Index(k0, la.grid.z), kl = Index(k1, la.grid.z);
    float cells = k1 - k0 + 1.0;
    float ratio = float(CountBits(false, i, j, kf, kl)) / cells;
    float solidRatio = withSolids ? float(CountBits(true, i, j, kf, kl)) / cells : 0.0;
    vec3 nearEnd = c + vec3(0.0, 0.0, u0) - centre, farEnd = c + vec3(0.0, 0.0, u1) - centre;
    float dm = max(0.5 * (length(nearEnd) + length(farEnd)), 1e-12);
    if (paper)
    {
      float d2 = (dm * h) * (dm * h);
      sum += ratio / d2;
      solidSum += solidRatio / d2;
      weights += 1.0;
      continue;
    }
    vec3 middle = 0.5 * (nearEnd + farEnd);
    float ml = length(middle);
    float angular = !(ml > 0.0) ? 0.0 : cosine ? max(0.0, dot(w, middle) / ml) : line ? length(cross(T, middle)) / ml : 1.0;
    float weight = angular / ((dm / R) * (dm / R));
    sum += weight * ratio;
    solidSum += weight * solidRatio;
    weights += weight;
  }
  float occupancy = weights > 0.0 ? sum / weights : 0.0;
  float solidOccupancy = weights > 0.0 ? solidSum / weights : 0.0;
  float lines = paper ? 1.0 - clamp(la.paper.x * occupancy, 0.0, 1.0) : exp(-la.scalars.w * la.scalars.z * occupancy);
  ao[k] = lines * (1.0 - min(1.0, solidOccupancy));
}
