// caoVoxelize.glsl - the GPU twin of cao::VoxelizeWorld (caoVoxelConeTracing.cxx):
// one mesh rasterized along the grid's z axis in a compute shader (no
// hardware rasterizer, whose sub-pixel snapping differs between GPUs),
// one workgroup per triangle, its threads striding over the triangle's
// column box. Coverage at column centres with the top-left rule and the
// depth's slice, in double, operation for operation as the C++ does
// (`precise`: no contraction into FMA), so the bits are the CPU's.
// CAO_VX_STAGE 0: rasterize one mesh into its own bits (XOR from the
// crossing to the top for a solid mesh, the crossing's slice for a shell);
// 1: OR the mesh's bits (and its surface voxels) into the grid.
// CAO_VX_FRUSTUM 1: the frustum grid (cao::PlanFrustumGrid): the points
// are the host's screen triangles (cao::FrustumScreenTriangles: pixel x, y
// and 1 / w or NDC z), each crossing's depth goes to its column's slice
// (near depth and slices per depth, in double), each column's crossings
// are counted, and stage 1 inverts a solid mesh's column with an odd count
// (the parity from beyond the far depth), as RasterizeFrustum does.
#if CAO_VX_STAGE == 0
layout(local_size_x = 64) in;
#else
layout(local_size_x = 256) in;
#endif

layout(std430, binding = CAO_BINDING_VX_POINTS) readonly buffer PointBlock
{
  double points[];
};
layout(std430, binding = CAO_BINDING_VX_IDS) readonly buffer IdBlock
{
  int ids[];
};
layout(std430, binding = CAO_BINDING_VX_BITS) buffer BitBlock
{
  uint bits[];
};
layout(std430, binding = CAO_BINDING_VX_GRID) buffer GridBlock
{
  uint grid[];
};
layout(std430, binding = CAO_BINDING_VX_SURFACE) buffer SurfaceBlock
{
  uint surface[];
};

#if CAO_VX_FRUSTUM
layout(std430, binding = CAO_BINDING_VX_COLUMNS) readonly buffer ColumnBlock
{
  double columnDepths[]; // per column: near depth, slices per depth
};
layout(std430, binding = CAO_BINDING_VX_PARITY) buffer ParityBlock
{
  uint parity[];
};
uniform int perspective; // stage 0: the key is 1 / w (else NDC z)
uniform dvec2 shell;     // stage 0: x, an open mesh's shell depth in slices per (depth x slices per depth)
#endif

uniform ivec4 gridSize;    // nx, ny, slices, words
uniform int triangleCount; // stage 0
uniform int solid;         // stage 0: 1 solid (XOR), 0 shell (OR)
uniform int surfaceVoxels; // stage 0, solid: also OR the crossing's slice into `surface`
uniform uint wordCount;    // stage 1

#if CAO_VX_STAGE == 0
dvec3 Point(int id)
{
  return dvec3(points[3 * id], points[3 * id + 1], points[3 * id + 2]);
}

// 2D edge function of the directed edge u -> v at p (the C++'s Edge).
double Edge(dvec3 u, dvec3 v, double px, double py)
{
  precise double a = (v.x - u.x) * (py - u.y);
  precise double b = (v.y - u.y) * (px - u.x);
  precise double e = a - b;
  return e;
}

bool Owned(dvec3 u, dvec3 v)
{
  double dy = v.y - u.y, dx = v.x - u.x;
  return dy < 0.0LF || (dy == 0.0LF && dx > 0.0LF);
}

bool Inside(double e, dvec3 u, dvec3 v)
{
  return e > 0.0LF || (e == 0.0LF && Owned(u, v));
}

void main()
{
  int t = int(gl_WorkGroupID.x) + int(gl_WorkGroupID.y) * int(gl_NumWorkGroups.x);
  if (t >= triangleCount)
    return;
  dvec3 v0 = Point(ids[3 * t]), v1 = Point(ids[3 * t + 1]), v2 = Point(ids[3 * t + 2]);
  precise double area = Edge(v0, v1, v2.x, v2.y);
  if (area == 0.0LF || isinf(area) || isnan(area))
    return;
  dvec3 a = v0, b = area > 0.0LF ? v1 : v2, c = area > 0.0LF ? v2 : v1;
  area = abs(area);
  double minX = min(a.x, min(b.x, c.x)), maxX = max(a.x, max(b.x, c.x));
  double minY = min(a.y, min(b.y, c.y)), maxY = max(a.y, max(b.y, c.y));
  // Clamped in double first: a frustum grid's triangle cut at the eye plane
  // reaches far beyond the screen (an int would overflow), as the C++ does.
  int i0 = int(clamp(ceil(minX - 0.5LF), 0.0LF, double(gridSize.x)));
  int i1 = int(clamp(floor(maxX - 0.5LF), -1.0LF, double(gridSize.x - 1)));
  int j0 = int(clamp(ceil(minY - 0.5LF), 0.0LF, double(gridSize.y)));
  int j1 = int(clamp(floor(maxY - 0.5LF), -1.0LF, double(gridSize.y - 1)));
  if (i1 < i0 || j1 < j0)
    return;
  int width = i1 - i0 + 1;
  int columns = width * (j1 - j0 + 1);
#if !CAO_VX_FRUSTUM
  // An open mesh's shell: the slices the plane spans over a column's width
  // around each crossing, within the triangle's own (VoxelizeWorld's).
  precise double gx = (-(c.y - b.y) * a.z + -(a.y - c.y) * b.z) + -(b.y - a.y) * c.z;
  precise double gy = ((c.x - b.x) * a.z + (a.x - c.x) * b.z) + (b.x - a.x) * c.z;
  precise double spread = 0.5LF * ((abs(gx) + abs(gy)) / area);
  double lowest = floor(min(a.z, min(b.z, c.z))), highest = floor(max(a.z, max(b.z, c.z)));
#endif
  for (int n = int(gl_LocalInvocationID.x); n < columns; n += 64)
  {
    int i = i0 + n % width, j = j0 + n / width;
    double px = double(i) + 0.5LF, py = double(j) + 0.5LF;
    double ea = Edge(b, c, px, py), eb = Edge(c, a, px, py), ec = Edge(a, b, px, py);
    if (!Inside(ea, b, c) || !Inside(eb, c, a) || !Inside(ec, a, b))
      continue;
    precise double num = (ea * a.z + eb * b.z) + ec * c.z;
    precise double s = num / area;
#if CAO_VX_FRUSTUM
    double shellSlices = 1.0LF; // an open mesh's slices per crossing
    {
      uint col = uint(j * gridSize.x + i);
      precise double depth = perspective != 0 ? 1.0LF / s : s;
      precise double d = depth - columnDepths[2u * col];
      s = d * columnDepths[2u * col + 1u];
      if (s < 0.0LF && s > -0.5LF) // the column's visible surface, but for rounding
        s = 0.0LF;
      if (solid != 0)
        atomicXor(parity[col], 1u);
      // A shell a pixel deep (RasterizeFrustum's).
      precise double t = ((perspective != 0 ? depth : 1.0LF) * shell.x) * columnDepths[2u * col + 1u];
      shellSlices = min(double(gridSize.z), max(1.0LF, ceil(t)));
    }
#endif
    uint column = uint(j * gridSize.x + i) * uint(gridSize.w);
    if (solid != 0 && surfaceVoxels != 0)
    {
      double k = floor(s);
      if (k >= 0.0LF && k < double(gridSize.z))
      {
        int kk = int(k);
        atomicOr(surface[column + uint(kk >> 5)], 1u << uint(kk & 31));
      }
    }
    if (solid != 0)
    {
      // Every slice whose centre lies beyond the crossing: k + 1/2 > s.
      double first = floor(s - 0.5LF) + 1.0LF;
      if (first >= double(gridSize.z))
        continue;
      int k0 = first < 0.0LF ? 0 : int(first);
      int w = k0 >> 5;
      atomicXor(bits[column + uint(w)], 0xFFFFFFFFu << uint(k0 & 31));
      for (++w; w < gridSize.w; ++w)
        atomicXor(bits[column + uint(w)], 0xFFFFFFFFu);
    }
    else
    {
#if CAO_VX_FRUSTUM
      double k = floor(s);
      for (double kk = max(k, 0.0LF); kk < k + shellSlices && kk < double(gridSize.z); kk += 1.0LF)
#else
      precise double below = s - spread, above = s + spread;
      double k = floor(s); // (its own slice always: rounding may put s just outside)
      double lo = max(min(max(floor(below), lowest), k), 0.0LF);
      double hi = min(max(min(floor(above), highest), k), double(gridSize.z) - 1.0LF);
      for (double kk = lo; kk <= hi; kk += 1.0LF)
#endif
      {
        int q = int(kk);
        atomicOr(bits[column + uint(q >> 5)], 1u << uint(q & 31));
      }
    }
  }
}
#else
void main()
{
  uint w = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 256u;
  if (w >= wordCount)
    return;
#if CAO_VX_FRUSTUM
  uint own = (parity[w / uint(gridSize.w)] & 1u) != 0u ? ~bits[w] : bits[w];
  grid[w] |= own | surface[w];
#else
  grid[w] |= bits[w] | surface[w];
#endif
}
#endif
