// caoClipDepthMaps.glsl - the GPU twin of caoClipDepthMaps.cxx: clip-mesh depth
// maps, depth-peeled into L layers, dilated and eroded by a sphere. Every
// depth, edge function and slack is computed in double, operation for
// operation as the C++ does (`precise` forbids contraction into FMA), and
// rounded outward to float the same way, so the maps are bit-identical to
// the CPU's. One file, four stages chosen by CAO_DM_STAGE:
//  - SETUP (compute, per triangle): project the corners, orient, pixel box;
//  - FRAGMENT (fragment shader of the raster pass, see caoClipDepthMapsVS):
//    the exact watertight coverage test with the top-left rule, then
//    CAO_DM_PASS 0 counts the hits and 1 appends (depth, winding) to the
//    pixel's list;
//  - RESOLVE (compute, per pixel): the winding sweep over the pixel's hits
//    in (depth, winding) order gives the inside intervals = the layers;
//  - DILATE (compute, per pixel): Minkowski sum and difference of every
//    layer with the sphere, over the window the host computed
//    (cao::DilationWindow), so the square roots are the CPU's too.
#define CAO_DM_SETUP 0
#define CAO_DM_FRAGMENT 1
#define CAO_DM_RESOLVE 2
#define CAO_DM_DILATE 3

#if CAO_DM_STAGE == CAO_DM_SETUP
layout(local_size_x = 64) in;
#elif CAO_DM_STAGE != CAO_DM_FRAGMENT
layout(local_size_x = 8, local_size_y = 8) in;
#endif

layout(std430, binding = CAO_BINDING_DM_POINTS) readonly buffer PointBlock
{
  double points[];
};
// 3 point ids per triangle, then one winding weight per triangle
// (caoClipDepthMaps.h TriangleMesh: 1 unless a composite gave others).
layout(std430, binding = CAO_BINDING_DM_IDS) readonly buffer IdBlock
{
  int ids[];
};
layout(std430, binding = CAO_BINDING_DM_TRIANGLES) buffer TriangleBlock
{
  DMTriangle triangles[];
};
layout(std430, binding = CAO_BINDING_DM_HEADS) buffer HeadBlock
{
  uint heads[];
};
layout(std430, binding = CAO_BINDING_DM_HITS) buffer HitBlock
{
  DMHit hits[];
};
// Six maps of width * height * layers floats, pixel-major with the layers of
// a pixel adjacent: front, back, dilated front/back, eroded front/back.
layout(std430, binding = CAO_BINDING_DM_MAPS) buffer MapBlock
{
  float maps[];
};
layout(std430, binding = CAO_BINDING_DM_WINDOW) readonly buffer WindowBlock
{
  DMOffset window[];
};
layout(std430, binding = CAO_BINDING_DM_STATS) buffer StatBlock
{
  int stats[];
};

uniform ivec3 mapSize;     // width, height, layers
uniform int triangleCount; // SETUP
uniform int minimumWinding; // RESOLVE: 0 = inside where the winding is not 0, k = at least k
uniform dvec3 camOrigin;   // SETUP: the clipping camera (caoClipDepthMaps.h ClipCamera)
uniform dvec3 camRight;
uniform dvec3 camUp;
uniform dvec3 camDirection;
uniform dvec2 pixelSize;
uniform uint hitCapacity; // FRAGMENT pass 1
uniform int windowCount;  // DILATE
uniform ivec2 windowHalf; // DILATE: rx, ry

const float PositiveInfinity = uintBitsToFloat(0x7F800000u);
const float NegativeInfinity = uintBitsToFloat(0xFF800000u);

// Outward rounding to float, as RoundDown/RoundUp in caoClipDepthMaps.cxx: the
// nearest float, bumped by one ulp when it lies on the wrong side. Correct
// whatever rounding the double-to-float conversion uses.
float NextDown(float f)
{
  const uint bits = floatBitsToUint(f);
  if (f > 0.0)
    return uintBitsToFloat(bits - 1u);
  if (f == 0.0)
    return uintBitsToFloat(0x80000001u);
  return uintBitsToFloat(bits + 1u);
}
float NextUp(float f)
{
  const uint bits = floatBitsToUint(f);
  if (f < 0.0)
    return uintBitsToFloat(bits - 1u);
  if (f == 0.0)
    return uintBitsToFloat(0x00000001u);
  return uintBitsToFloat(bits + 1u);
}
float RoundDown(double x)
{
  float f = float(x);
  if (double(f) > x)
    f = NextDown(f);
  return f;
}
float RoundUp(double x)
{
  float f = float(x);
  if (double(f) < x)
    f = NextUp(f);
  return f;
}

#if CAO_DM_STAGE == CAO_DM_SETUP || CAO_DM_STAGE == CAO_DM_FRAGMENT
// Edge function of corners i -> j at (px, py), from the lower point id
// first (caoClipDepthMaps.cxx Edge): a shared edge gives the same magnitude in
// both of its triangles.
double Edge(DMTriangle t, int i, int j, double px, double py)
{
  const bool flip = t.ids[j] < t.ids[i];
  const int a = flip ? j : i;
  const int b = flip ? i : j;
  precise double e = (t.u[b] - t.u[a]) * (py - t.v[a]) - (t.v[b] - t.v[a]) * (px - t.u[a]);
  return flip ? -e : e;
}
#endif

#if CAO_DM_STAGE == CAO_DM_SETUP
// caoClipDepthMaps.cxx LocalToCamera: ((d.x r.x + d.y r.y) + d.z r.z) / size.
void ToCamera(int id, out double u, out double v, out double z)
{
  precise double dx = points[3 * id] - camOrigin.x;
  precise double dy = points[3 * id + 1] - camOrigin.y;
  precise double dz = points[3 * id + 2] - camOrigin.z;
  precise double du = (dx * camRight.x + dy * camRight.y) + dz * camRight.z;
  precise double dv = (dx * camUp.x + dy * camUp.y) + dz * camUp.z;
  precise double dd = (dx * camDirection.x + dy * camDirection.y) + dz * camDirection.z;
  u = du / pixelSize.x;
  v = dv / pixelSize.y;
  z = dd;
}

// caoClipDepthMaps.cxx PixelSpan.
ivec2 PixelSpan(double lo, double hi, int size)
{
  return ivec2(int(max(0.0LF, min(double(size), ceil(lo - 0.5LF)))),
    int(max(-1.0LF, min(double(size - 1), floor(hi - 0.5LF)))));
}

void main()
{
  const int t = int(gl_GlobalInvocationID.x);
  if (t >= triangleCount)
    return;
  DMTriangle tri;
  bool finite = true;
  for (int k = 0; k < 3; ++k)
  {
    tri.ids[k] = ids[3 * t + k];
    ToCamera(tri.ids[k], tri.u[k], tri.v[k], tri.z[k]);
    finite = finite && !isinf(tri.u[k]) && !isnan(tri.u[k]) && !isinf(tri.v[k]) &&
      !isnan(tri.v[k]) && !isinf(tri.z[k]) && !isnan(tri.z[k]);
  }
  tri.u[3] = tri.v[3] = tri.z[3] = 0.0LF;
  tri.box = ivec4(1, 1, 0, 0);
  tri.ids.w = 0;
  const double area = Edge(tri, 0, 1, tri.u[2], tri.v[2]);
  if (!finite)
  {
    atomicAdd(stats[CAO_DM_STAT_NONFINITE], 1);
  }
  else if (area != 0.0LF) // edge-on triangles cover no centre consistently
  {
    // The outward normal's view component has the sign of the area
    // (right x up = direction): positive = leaving the solid.
    const int weight = ids[3 * triangleCount + t];
    tri.ids.w = area > 0.0LF ? -weight : weight;
    if (area < 0.0LF) // counter-clockwise for the coverage test
    {
      const int i = tri.ids[1];
      tri.ids[1] = tri.ids[2];
      tri.ids[2] = i;
      const double u = tri.u[1], v = tri.v[1], z = tri.z[1];
      tri.u[1] = tri.u[2];
      tri.v[1] = tri.v[2];
      tri.z[1] = tri.z[2];
      tri.u[2] = u;
      tri.v[2] = v;
      tri.z[2] = z;
    }
    const ivec2 xs = PixelSpan(min(min(tri.u[0], tri.u[1]), tri.u[2]),
      max(max(tri.u[0], tri.u[1]), tri.u[2]), mapSize.x);
    const ivec2 ys = PixelSpan(min(min(tri.v[0], tri.v[1]), tri.v[2]),
      max(max(tri.v[0], tri.v[1]), tri.v[2]), mapSize.y);
    tri.box = ivec4(xs.x, ys.x, xs.y, ys.y);
  }
  triangles[t] = tri;
}

#elif CAO_DM_STAGE == CAO_DM_FRAGMENT
flat in int triangleId;

// caoClipDepthMaps.cxx TopLeft, for the counter-clockwise triangle in a y-up frame.
bool TopLeft(DMTriangle t, int a, int b)
{
  return (t.v[b] < t.v[a]) || (t.v[b] == t.v[a] && t.u[b] < t.u[a]);
}

void main()
{
  const DMTriangle t = triangles[triangleId];
  const int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
  if (x < t.box.x || x > t.box.z || y < t.box.y || y > t.box.w)
    return;
  const double px = double(x) + 0.5LF, py = double(y) + 0.5LF;
  const double w0 = Edge(t, 1, 2, px, py); // opposite corner 0
  const double w1 = Edge(t, 2, 0, px, py);
  const double w2 = Edge(t, 0, 1, px, py);
  const bool in0 = w0 > 0.0LF || (w0 == 0.0LF && TopLeft(t, 1, 2));
  const bool in1 = w1 > 0.0LF || (w1 == 0.0LF && TopLeft(t, 2, 0));
  const bool in2 = w2 > 0.0LF || (w2 == 0.0LF && TopLeft(t, 0, 1));
  if (!(in0 && in1 && in2))
    return;
#if CAO_DM_PASS == 0
  atomicAdd(stats[CAO_DM_STAT_HITS], 1);
#else
  const uint slot = uint(atomicAdd(stats[CAO_DM_STAT_HITS], 1));
  if (slot >= hitCapacity)
    return; // cannot happen: pass 0 counted the same fragments
  // (a triangle at one depth, as a flat face seen head on: that depth
  // exactly, as the CPU's RasterizeDepthLayers; the weighted mean's
  // rounding would scatter it over two floats and break the dilation's
  // uniform windows)
  precise double z = t.z[0] == t.z[1] && t.z[1] == t.z[2]
    ? t.z[0]
    : ((w0 * t.z[0] + w1 * t.z[1]) + w2 * t.z[2]) / ((w0 + w1) + w2);
  DMHit hit;
  hit.z = z;
  hit.winding = t.ids.w;
  hit.next = atomicExchange(heads[y * mapSize.x + x], slot);
  hits[slot] = hit;
#endif
}

#elif CAO_DM_STAGE == CAO_DM_RESOLVE
int intervalCount = 0;

// caoClipDepthMaps.h InsideWinding.
bool InsideWinding(int w)
{
  return minimumWinding > 0 ? w >= minimumWinding : w != 0;
}

// Layer `intervalCount` gets [f, b]; intervals past the last layer merge
// into it (its back moves to theirs), as in caoClipDepthMaps.cxx.
void AddInterval(uint base, uint layerSize, double f, double b)
{
  const int layers = mapSize.z;
  if (intervalCount < layers)
  {
    maps[base + uint(intervalCount)] = RoundDown(f);
    maps[layerSize + base + uint(intervalCount)] = RoundUp(b);
  }
  else
  {
    maps[layerSize + base + uint(layers - 1)] = RoundUp(b);
  }
  ++intervalCount;
}

void main()
{
  const ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
  if (xy.x >= mapSize.x || xy.y >= mapSize.y)
    return;
  const uint pixel = uint(xy.y * mapSize.x + xy.x);
  const uint layerSize = uint(mapSize.x * mapSize.y * mapSize.z);
  const uint base = pixel * uint(mapSize.z);
  for (int l = 0; l < mapSize.z; ++l)
  {
    maps[base + uint(l)] = PositiveInfinity;
    maps[layerSize + base + uint(l)] = NegativeInfinity;
  }
  const uint head = heads[pixel];
  if (head == CAO_DM_END)
    return;
  // Visit the hits in (depth, winding) order without sorting in place: each
  // step finds the smallest key above the previous one and its multiplicity
  // (equal keys are interchangeable, so this is the CPU's sorted order).
  int w = 0;
  double start = 0.0LF;
  bool havePrevious = false;
  double previousZ = 0.0LF;
  int previousWinding = 0;
  while (true)
  {
    bool found = false;
    double keyZ = 0.0LF;
    int keyWinding = 0;
    int multiplicity = 0;
    for (uint n = head; n != CAO_DM_END; n = hits[n].next)
    {
      const double z = hits[n].z;
      const int wn = hits[n].winding;
      if (havePrevious && !(z > previousZ || (z == previousZ && wn > previousWinding)))
        continue;
      if (!found || z < keyZ || (z == keyZ && wn < keyWinding))
      {
        found = true;
        keyZ = z;
        keyWinding = wn;
        multiplicity = 1;
      }
      else if (z == keyZ && wn == keyWinding)
      {
        ++multiplicity;
      }
    }
    if (!found)
      break;
    for (int i = 0; i < multiplicity; ++i)
    {
      const bool wasInside = InsideWinding(w);
      w += keyWinding;
      const bool inside = InsideWinding(w);
      if (!wasInside && inside)
        start = keyZ;
      else if (wasInside && !inside && keyZ > start)
        AddInterval(base, layerSize, start, keyZ);
    }
    havePrevious = true;
    previousZ = keyZ;
    previousWinding = keyWinding;
  }
  if (w != 0)
  {
    atomicAdd(stats[CAO_DM_STAT_UNMATCHED], 1);
    if (InsideWinding(w) && previousZ > start)
      AddInterval(base, layerSize, start, previousZ);
  }
  if (intervalCount == 0)
    return;
  atomicAdd(stats[CAO_DM_STAT_COVERED], 1);
  if (intervalCount > mapSize.z)
    atomicAdd(stats[CAO_DM_STAT_OVERFLOW], 1);
  for (int l = 0; l < min(intervalCount, mapSize.z); ++l)
  {
    atomicMin(stats[CAO_DM_STAT_BOXES + 4 * l], xy.x);
    atomicMin(stats[CAO_DM_STAT_BOXES + 4 * l + 1], xy.y);
    atomicMax(stats[CAO_DM_STAT_BOXES + 4 * l + 2], xy.x);
    atomicMax(stats[CAO_DM_STAT_BOXES + 4 * l + 3], xy.y);
  }
}

#elif CAO_DM_STAGE == CAO_DM_DILATE
void main()
{
  const ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
  if (xy.x >= mapSize.x || xy.y >= mapSize.y)
    return;
  const uint layerSize = uint(mapSize.x * mapSize.y * mapSize.z);
  for (int l = 0; l < mapSize.z; ++l)
  {
    const uint i = uint((xy.y * mapSize.x + xy.x) * mapSize.z + l);
    maps[2u * layerSize + i] = PositiveInfinity;
    maps[3u * layerSize + i] = NegativeInfinity;
    maps[4u * layerSize + i] = PositiveInfinity;
    maps[5u * layerSize + i] = NegativeInfinity;
    const ivec4 box = ivec4(stats[CAO_DM_STAT_BOXES + 4 * l], stats[CAO_DM_STAT_BOXES + 4 * l + 1],
      stats[CAO_DM_STAT_BOXES + 4 * l + 2], stats[CAO_DM_STAT_BOXES + 4 * l + 3]);
    // Outside the covered box grown by the window both results are empty
    // (the CPU does not visit those pixels either).
    if (box.x > box.z || xy.x < box.x - windowHalf.x || xy.x > box.z + windowHalf.x ||
      xy.y < box.y - windowHalf.y || xy.y > box.w + windowHalf.y)
      continue;
    bool anyInside = false, erodedEmpty = false;
    double dFront = 0.0LF, dBack = 0.0LF, eFront = 0.0LF, eBack = 0.0LF;
    for (int k = 0; k < windowCount; ++k)
    {
      const DMOffset o = window[k];
      const int sx = xy.x + o.dx, sy = xy.y + o.dy;
      if (sx < 0 || sy < 0 || sx >= mapSize.x || sy >= mapSize.y)
      {
        erodedEmpty = true;
        continue;
      }
      const uint s = uint((sy * mapSize.x + sx) * mapSize.z + l);
      const float f = maps[s], b = maps[layerSize + s];
      if (!(f <= b))
      {
        erodedEmpty = true;
        continue;
      }
      precise double fl = double(f) - o.h;
      precise double bh = double(b) + o.h;
      precise double fh = double(f) + o.h;
      precise double bl = double(b) - o.h;
      dFront = anyInside ? min(dFront, fl) : fl;
      dBack = anyInside ? max(dBack, bh) : bh;
      eFront = anyInside ? max(eFront, fh) : fh;
      eBack = anyInside ? min(eBack, bl) : bl;
      anyInside = true;
    }
    if (anyInside)
    {
      maps[2u * layerSize + i] = RoundDown(dFront);
      maps[3u * layerSize + i] = RoundUp(dBack);
    }
    if (anyInside && !erodedEmpty && eFront <= eBack)
    {
      const float ef = RoundUp(eFront), eb = RoundDown(eBack);
      if (ef <= eb)
      {
        maps[4u * layerSize + i] = ef;
        maps[5u * layerSize + i] = eb;
      }
    }
  }
}
#endif
