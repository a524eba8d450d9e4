// caoLineGBuffer.glsl - the GPU side of cao::LineFrameFromDepth with
// drawings (caoCapsules.cxx), in double, and of cao::LineHalfBallAt
// (caoLineAO.cxx): the same formulas in the same order, so that a pixel's
// chosen segment differs from the CPU's only where two candidates tie
// within a float's precision of their key. The CPU searches a tree per
// pixel; here each segment visits the drawn pixels within its reach on
// screen (LineGBufferParams, caoGPULayout.h). One stage per program
// (CAO_LG_STAGE), after caoLineGridMap.glsl:
//   0, per drawn pixel (slot): its ray (LineRay), its key reset;
//   1, per segment: the best key of each candidate pixel (atomicMin: covering
//      before passing beside (the high bit), then the smaller t past the
//      nearest a candidate may lie (a cover limit more for one covering
//      beside an end only), or the smaller distance);
//   2, per segment: the lowest segment of that key (atomicMin);
//   3, per slot: the chosen segment's surface point (on its cylinder, as
//      the CPU's CylinderEntry), normal, tangent and axis point, and its
//      half ball as a LineAOPixel for caoLineAO.glsl.
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_LG_PARAMS) uniform LineGBufferBlock
{
  LineGBufferParams lg;
};
layout(std430, binding = CAO_BINDING_LG_SLOTS) readonly buffer SlotsBlock
{
  int slots[];
};
layout(std430, binding = CAO_BINDING_LG_DRAWN) readonly buffer DrawnBlock
{
  uvec2 drawn[];
};
layout(std430, binding = CAO_BINDING_LG_RAYS) buffer RaysBlock
{
  LineRay rays[];
};
layout(std430, binding = CAO_BINDING_LG_SEGMENTS) readonly buffer SegmentsBlock
{
  dvec4 ends[];
};
layout(std430, binding = CAO_BINDING_LG_DRAWINGS) readonly buffer DrawingsBlock
{
  dvec4 drawings[];
};
layout(std430, binding = CAO_BINDING_LG_KEYS) buffer KeysBlock
{
  uint keys[];
};
layout(std430, binding = CAO_BINDING_LG_RECORDS) writeonly buffer RecordsBlock
{
  LineAOPixel records[];
};

const uint None = 0xffffffffu;
const double Huge = 1e300lf; // (beyond any interval's end: the CPU's infinity)

uint Invocation()
{
  return gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
}

bool Finite(dvec3 p)
{
  return !any(isnan(p)) && !any(isinf(p));
}

/// cao::NDCToWorld (its products summed in the same order; no dynamic
/// index into a vector: one NVIDIA compiler fails to link those in double).
bool NDCToWorld(double x, double y, double z, out dvec3 p)
{
  const dvec4 r0 = lg.ndcToWorld[0], r1 = lg.ndcToWorld[1], r2 = lg.ndcToWorld[2], r3 = lg.ndcToWorld[3];
  precise double w = r3.x * x + r3.y * y + r3.z * z + r3.w;
  precise dvec3 q = dvec3((r0.x * x + r0.y * y + r0.z * z + r0.w) / w, (r1.x * x + r1.y * y + r1.z * z + r1.w) / w,
    (r2.x * x + r2.y * y + r2.z * z + r2.w) / w);
  p = q;
  return Finite(p);
}

/// Segment [a, b] against slot's ray as drawn by `own` (the CPU's
/// Evaluate): its point nearest the ray (s, t, distance), whether it is a
/// candidate, whether it covers the pixel and whether that point is not
/// clamped to an end (interior).
bool Evaluate(LineRay r, dvec3 a, dvec3 b, dvec4 own, out double s, out double t, out double distance,
  out bool covers, out bool interior)
{
  const dvec3 o = r.origin.xyz, v = r.direction.xyz, drawnPoint = r.drawn.xyz;
  const double footprint = r.direction.w, tDrawn = r.origin.w, behind = r.drawn.w;
  // (`precise`: no contraction into FMA, as the CPU's -ffp-contract=off;
  // stages 1 and 2 must rank a candidate alike.)
  precise dvec3 u = b - a;
  precise double C = dot(u, u), B = dot(v, u);
  precise dvec3 w0 = o - a;
  precise double si = 0.0;
  precise double denominator = C - B * B;
  if (C > 0.0 && denominator > 1e-12lf * C)
    si = (dot(u, w0) - B * dot(v, w0)) / denominator;
  else if (C > 0.0)
    si = dot(drawnPoint - a, u) / C;
  interior = si >= 0.0 && si <= 1.0;
  si = min(1.0, max(0.0, si));
  precise dvec3 q = a + si * u;
  precise double ti = dot(q - o, v);
  precise double di = length(o + ti * v - q);
  precise double reach = own.x * footprint;
  const double widestSlack = lg.scalars.y;
  precise double slack = widestSlack > 0.0 ? behind * (own.z / widestSlack) : 0.0;
  precise double coverLimit = (own.y + lg.constants.y) * footprint;
  precise double front = tDrawn - reach, back = tDrawn + slack + reach;
  s = si;
  t = ti;
  distance = di;
  covers = di <= coverLimit;
  return di <= reach && ti >= front && ti <= back;
}

#if CAO_LG_STAGE == 0
void main()
{
  const uint slot = Invocation();
  if (slot >= uint(lg.counts.w))
    return;
  keys[2 * slot] = None;
  keys[2 * slot + 1] = None;
  const uint pixel = drawn[slot].x;
  const double d = double(uintBitsToFloat(drawn[slot].y));
  const int W = lg.counts.x, H = lg.counts.y;
  const int i = int(pixel % uint(W)), j = int(pixel / uint(W));
  LineRay r;
  r.origin = dvec4(0.0, 0.0, 0.0, 0.0);
  r.direction = dvec4(0.0);
  r.drawn = dvec4(0.0);
  // cao::PixelRay, then the drawn point, its footprint and the stretch
  // behind it (the CPU's DrawnRayOf).
  const double x = (double(i) + 0.5) / double(W) * 2.0 - 1.0, y = (double(j) + 0.5) / double(H) * 2.0 - 1.0;
  const double z = 2.0 * d - 1.0;
  dvec3 o = dvec3(0.0), farPoint = dvec3(0.0), p = dvec3(0.0), px = dvec3(0.0), py = dvec3(0.0), pHi = dvec3(0.0);
  bool ok = NDCToWorld(x, y, -1.0, o) && NDCToWorld(x, y, 1.0, farPoint);
  dvec3 v = farPoint - o;
  const double l = length(v);
  ok = ok && l > 0.0 && !isinf(l);
  ok = ok && NDCToWorld(x, y, z, p) && NDCToWorld(x + 2.0 / double(W), y, z, px) &&
    NDCToWorld(x, y + 2.0 / double(H), z, py) && NDCToWorld(x, y, 2.0 * min(1.0, d + lg.scalars.y) - 1.0, pHi);
  if (!ok)
  {
    r.direction.w = -1.0; // (none: no segment is a candidate)
    rays[slot] = r;
    return;
  }
  v /= l;
  precise double footprint = max(length(px - p), length(py - p));
  precise double tDrawn = dot(p - o, v);
  precise double behind = max(0.0, min(dot(pHi - o, v), tDrawn + lg.constants.x * footprint) - tDrawn);
  r.origin = dvec4(o, tDrawn);
  r.direction = dvec4(v, footprint);
  r.drawn = dvec4(p, behind);
  rays[slot] = r;
}
#elif CAO_LG_STAGE == 1 || CAO_LG_STAGE == 2
/// A pixel's key for a candidate: covering (0) before passing beside (the
/// high bit), then t past the nearest a candidate may lie (covering; one
/// covering beside an end only, its nearest point clamped, a cover limit
/// further: the CPU's LineFrameFromDepth says why) or the distance
/// (beside), as a non-negative float's bits (ordered as the value).
uint KeyOf(LineRay r, dvec4 own, double t, double distance, bool covers, bool interior)
{
  precise double nearest = r.origin.w - lg.scalars.w * r.direction.w;
  precise double penalty = interior ? 0.0lf : (own.y + lg.constants.y) * r.direction.w;
  precise double metric = covers ? t + penalty - nearest : distance;
  return (covers ? 0u : 0x80000000u) | (floatBitsToUint(float(max(0.0, metric))) >> 1);
}

/// The segment [ca, cb] (clip space) cut to where plane . c >= offset;
/// false when none of it is.
bool Clip(dvec4 plane, double offset, inout dvec4 ca, inout dvec4 cb)
{
  const double fa = dot(plane, ca) - offset, fb = dot(plane, cb) - offset;
  if (fa < 0.0 && fb < 0.0)
    return false;
  if (fa < 0.0)
    ca = mix(ca, cb, fa / (fa - fb));
  else if (fb < 0.0)
    cb = mix(cb, ca, fb / (fb - fa));
  return true;
}

void Visit(int pixel, uint segment, dvec3 a, dvec3 b, dvec4 own)
{
  const int slot = slots[pixel];
  if (slot < 0)
    return;
  const LineRay r = rays[slot];
  if (r.direction.w < 0.0)
    return;
  double s, t, distance;
  bool covers, interior;
  if (!Evaluate(r, a, b, own, s, t, distance, covers, interior))
    return;
  const uint key = KeyOf(r, own, t, distance, covers, interior);
#if CAO_LG_STAGE == 1
  atomicMin(keys[2 * slot], key);
#else
  if (keys[2 * slot] == key)
    atomicMin(keys[2 * slot + 1], segment);
#endif
}

void main()
{
  const uint segment = Invocation();
  if (segment >= uint(lg.counts.z))
    return;
  const dvec4 A = ends[2 * segment], B = ends[2 * segment + 1];
  const dvec4 own = drawings[int(A.w)];
  const dvec3 a = A.xyz, b = B.xyz;
  // The segment in clip space, cut where it passes behind the eye and at
  // the sides R pixels beyond the image (a pixel farther from them is no
  // candidate), so that its pixel coordinates stay small.
  const dmat4 m = dmat4(lg.worldToClip[0], lg.worldToClip[1], lg.worldToClip[2], lg.worldToClip[3]); // (rows)
  dvec4 ca = dvec4(a, 1.0) * m, cb = dvec4(b, 1.0) * m; // (row vector times the transpose: the rows' dots)
  const int W = lg.counts.x, H = lg.counts.y;
  // A candidate's nearest point lies within its reach of the pixel's ray,
  // at most a reach in front of the drawn depth: on screen within the reach
  // times the host's screen scale (the depths' ratio, at most 1.5 for the
  // reaches it takes, times the obliquity of the image's corners), and a
  // pixel's rounding.
  const float R = float(own.x * lg.scalars.x) + 1.5;
  const double kx = 1.0 + 2.0 * (double(R) + 1.0) / double(W), ky = 1.0 + 2.0 * (double(R) + 1.0) / double(H);
  // (In front of the eye, not of the near plane: a candidate up to a reach
  // in front of a drawn depth may lie before the near plane.)
  const double eps = 1e-9lf * max(abs(ca.w), abs(cb.w));
  if (!Clip(dvec4(0, 0, 0, 1), eps, ca, cb) || !Clip(dvec4(1, 0, 0, kx), 0.0, ca, cb) ||
    !Clip(dvec4(-1, 0, 0, kx), 0.0, ca, cb) || !Clip(dvec4(0, 1, 0, ky), 0.0, ca, cb) ||
    !Clip(dvec4(0, -1, 0, ky), 0.0, ca, cb))
    return;
  if (!(ca.w > 0.0) || !(cb.w > 0.0))
    return;
  const dvec2 size = dvec2(W, H);
  // Pixel coordinates (pixel i's centre at i).
  vec2 pa = vec2((ca.xy / ca.w * 0.5 + 0.5) * size - 0.5), pb = vec2((cb.xy / cb.w * 0.5 + 0.5) * size - 0.5);
  const bool alongX = abs(pb.x - pa.x) >= abs(pb.y - pa.y);
  if (!alongX)
  {
    pa = pa.yx;
    pb = pb.yx;
  }
  if (pb.x < pa.x)
  {
    const vec2 swap = pa;
    pa = pb;
    pb = swap;
  }
  const int major = alongX ? W : H, minor = alongX ? H : W;
  const float slope = pb.x > pa.x ? (pb.y - pa.y) / (pb.x - pa.x) : 0.0;
  const int c0 = max(0, int(ceil(pa.x - R))), c1 = min(major - 1, int(floor(pb.x + R)));
  for (int c = c0; c <= c1; ++c)
  {
    // Pixels within R of the segment have, at their major coordinate c, a
    // segment point within R along the major axis, and within R across.
    const float u0 = clamp(float(c) - R, pa.x, pb.x), u1 = clamp(float(c) + R, pa.x, pb.x);
    const float m0 = pa.y + slope * (u0 - pa.x), m1 = pa.y + slope * (u1 - pa.x);
    const int r0 = max(0, int(ceil(min(m0, m1) - R))), r1 = min(minor - 1, int(floor(max(m0, m1) + R)));
    for (int r = r0; r <= r1; ++r)
      Visit(alongX ? r * W + c : c * W + r, segment, a, b, own);
  }
}
#elif CAO_LG_STAGE == 3
/// cao::CapsuleInterval's SolveQuadratic.
bool SolveQuadratic(dvec3 p, dvec3 v, double r2, out double t0, out double t1)
{
  t0 = t1 = 0.0;
  const double a = dot(v, v), b = dot(p, v);
  const dvec3 w = p - (b / a) * v;
  const double h = r2 - dot(w, w);
  if (!(h >= 0.0))
    return false;
  const double root = sqrt(a * h);
  // (copysign: -0 counts as negative, as the CPU's std::copysign)
  const bool negative = (unpackDouble2x32(b).y & 0x80000000u) != 0u;
  const double q = -(b + (negative ? -root : root));
  if (q == 0.0)
    return true;
  const double x0 = q / a, x1 = (dot(p, p) - r2) / q;
  t0 = min(x0, x1);
  t1 = max(x0, x1);
  return true;
}

/// cao::CapsuleInterval: the ray's interval inside the capsule.
bool CapsuleInterval(dvec3 o, dvec3 d, dvec3 a, dvec3 b, double r2, out double entry, out double leave)
{
  bool hit = false;
  entry = Huge;
  leave = -Huge;
  double t0, t1;
  if (SolveQuadratic(o - a, d, r2, t0, t1))
  {
    entry = min(entry, t0);
    leave = max(leave, t1);
    hit = true;
  }
  const dvec3 ba = b - a;
  const double l2 = dot(ba, ba);
  if (l2 == 0.0)
    return hit;
  if (SolveQuadratic(o - b, d, r2, t0, t1))
  {
    entry = min(entry, t0);
    leave = max(leave, t1);
    hit = true;
  }
  if (!(l2 > 1e-24lf * r2))
    return hit;
  const dvec3 oa = o - a;
  const double along = dot(oa, ba), speed = dot(d, ba);
  double s0 = -Huge, s1 = Huge;
  if (speed != 0.0)
  {
    const double u0 = -along / speed, u1 = (l2 - along) / speed;
    s0 = min(u0, u1);
    s1 = max(u0, u1);
  }
  else if (along < 0.0 || along > l2)
    return hit;
  const dvec3 p = oa - (along / l2) * ba, v = d - (speed / l2) * ba;
  double c0 = -Huge, c1 = Huge;
  if (dot(v, v) > 0.0)
  {
    if (!SolveQuadratic(p, v, r2, c0, c1))
      return hit;
  }
  else if (dot(p, p) > r2)
    return hit;
  c0 = max(c0, s0);
  c1 = min(c1, s1);
  if (c0 <= c1)
  {
    entry = min(entry, c0);
    leave = max(leave, c1);
    hit = true;
  }
  return hit;
}

/// The CPU's CylinderEntry: where the ray o + t d (d unit) enters the
/// infinite cylinder of `radius` around the line through a and b, when that
/// point lies within the segment's capsule span along the axis (a tube
/// impostor's surface: no end caps).
bool CylinderEntry(dvec3 o, dvec3 d, dvec3 a, dvec3 b, double radius, out double entry)
{
  entry = 0.0;
  const dvec3 ba = b - a;
  const double l2 = dot(ba, ba);
  if (!(l2 > 1e-24lf * radius * radius))
    return false;
  const dvec3 oa = o - a;
  const double along = dot(oa, ba), speed = dot(d, ba);
  const dvec3 p = oa - (along / l2) * ba, v = d - (speed / l2) * ba;
  double c0, c1;
  if (!(dot(v, v) > 1e-12lf) || !SolveQuadratic(p, v, radius * radius, c0, c1) || !(c1 > 0.0))
    return false;
  entry = max(0.0, c0);
  const double l = sqrt(l2), x = (along + entry * speed) / l;
  return x >= -radius && x <= l + radius;
}

/// A world direction in the grid's frame, a world point in voxel units
/// (caoLineGridMap.glsl).
dvec3 ToGrid(dvec3 x)
{
  return GridDirection(lg.map, x);
}
dvec3 ToVoxels(dvec3 x)
{
  return GridVoxels(lg.map, x);
}
dvec3 Normalized(dvec3 v)
{
  return dot(v, v) > 0.0 ? normalize(v) : v;
}

void main()
{
  const uint slot = Invocation();
  if (slot >= uint(lg.counts.w))
    return;
  const uint pixel = drawn[slot].x;
  const int W = lg.counts.x;
  LineAOPixel record;
  record.centre = vec4(0.0);
  record.plane = vec4(0.0);
  record.tangent = vec4(0.0);
  record.pixel = ivec4(int(slot), 4, 0, 0);
  const uint segment = keys[2 * slot + 1];
  if (segment == None)
  {
    records[slot] = record;
    return;
  }
  const LineRay r = rays[slot];
  const dvec4 A = ends[2 * segment], B = ends[2 * segment + 1];
  const dvec4 own = drawings[int(A.w)];
  const dvec3 a = A.xyz, b = B.xyz, o = r.origin.xyz, v = r.direction.xyz;
  const double footprint = r.direction.w;
  double s, t, distance;
  bool covers, interior;
  Evaluate(r, a, b, own, s, t, distance, covers, interior);
  // The CPU's WriteDrawnPixel.
  const dvec3 axisPoint = a + s * (b - a);
  dvec3 tangent = b - a;
  const double tl = length(tangent);
  if (tl > 0.0)
    tangent /= tl;
  dvec3 position = o + t * v, normal = dvec3(0.0);
  const bool tubes = own.w != 0.0;
  const double radius = own.y * footprint;
  double entry, leave;
  bool cylinder = false;
  if (tubes && CylinderEntry(o, v, a, b, radius, entry))
  {
    position = o + entry * v;
    cylinder = true;
  }
  else if (tubes && CapsuleInterval(o, v, a, b, radius * radius, entry, leave) && leave > 0.0)
    position = o + max(0.0, entry) * v;
  if (tubes)
  {
    const dvec3 ab = b - a;
    double along = dot(ab, ab) > 0.0 ? dot(position - a, ab) / dot(ab, ab) : 0.0;
    if (!cylinder)
      along = min(1.0, max(0.0, along));
    normal = position - (a + along * ab);
    const double nl = length(normal);
    if (!(nl > 0.5 * footprint) || !(nl > 0.0))
      normal = dvec3(0.0);
    else
      normal /= nl;
  }
  // cao::LineHalfBallAt.
  const double rho = lg.scalars.z, halfDiagonal = lg.constants.z;
  dvec3 T = ToGrid(tangent);
  const bool line = dot(T, T) > 0.0;
  if (line)
    T = normalize(T);
  dvec3 centre, w;
  double base;
  bool cosine = lg.flags.x == 1 && any(notEqual(normal, dvec3(0.0)));
  if (cosine)
  {
    // (turned across the line, the base past the own voxels from the
    // point's distance to the axis: as the CPU twin)
    centre = ToVoxels(position);
    w = Normalized(ToGrid(normal));
    if (line)
      w -= dot(w, T) * T;
    if (length(w) > 0.1lf)
    {
      w = normalize(w);
      dvec3 radial = centre - ToVoxels(axisPoint);
      if (line)
        radial -= dot(radial, T) * T;
      base = max(0.0lf, max(rho, halfDiagonal) - length(radial));
    }
    else
      cosine = false;
  }
  if (!cosine)
  {
    centre = ToVoxels(axisPoint);
    const dvec3 toCamera = -Normalized(ToGrid(v));
    w = line ? toCamera - dot(toCamera, T) * T : toCamera;
    if (!(length(w) > 1e-9lf))
      w = cross(T, abs(T.x) < 0.6lf ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0));
    w = normalize(w);
    base = max(rho, halfDiagonal);
  }
  const int i = int(pixel % uint(W)), j = int(pixel / uint(W));
  record.centre = vec4(vec3(centre), float(base + 1e-9lf));
  record.plane = vec4(vec3(w), 0.0);
  record.tangent = vec4(vec3(T), 0.0);
  record.pixel = ivec4(int(slot), (line ? 1 : 0) | (cosine ? 2 : 0), (i & 3) + 4 * (j & 3), 0);
  records[slot] = record;
}
#endif
