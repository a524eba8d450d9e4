// caoScreenAO.glsl - the GPU side of cao::HBAOFrame and cao::VolumetricAOFrame
// (caoScreenSpaceAO.cxx), in float, one invocation per pixel: the same
// pattern, samples, marches and closed-form pipes as the CPU twin, before
// its depth-aware blur or filter (the host applies it, or
// caoScreenFilter.glsl on the GPU frame). Specialised with CAO_SS_METHOD 0
// (horizon-based AO, seed 002) or 1 (volumetric AO, seed 001); after
// caoScreenCommon.glsl.
layout(std430, binding = CAO_BINDING_SS_AO) writeonly buffer AOBlock
{
  float ao[];
};
layout(std430, binding = CAO_BINDING_SS_DISK) readonly buffer DiskBlock
{
  vec4 disk[];
};

const float Pi = 3.14159265358979;

/// The pixel a world point falls in (-1: off the screen or behind the
/// camera) and its NDC depth.
int Lookup(vec3 q, out float z)
{
  vec4 p = vec4(q, 1.0);
  float cw = dot(ss.worldToNDC[3], p);
  z = 0.0;
  if (!(cw > 0.0))
    return -1;
  float x = dot(ss.worldToNDC[0], p) / cw, y = dot(ss.worldToNDC[1], p) / cw;
  z = dot(ss.worldToNDC[2], p) / cw;
  float fi = floor((x + 1.0) * 0.5 * float(ss.image.x)), fj = floor((y + 1.0) * 0.5 * float(ss.image.y));
  if (!(fi >= 0.0 && fi < float(ss.image.x) && fj >= 0.0 && fj < float(ss.image.y)))
    return -1;
  return int(fj) * ss.image.x + int(fi);
}

vec3 NDCToWorld(vec3 ndc)
{
  vec4 p = vec4(ndc, 1.0);
  return vec3(dot(ss.ndcToWorld[0], p), dot(ss.ndcToWorld[1], p), dot(ss.ndcToWorld[2], p)) /
    dot(ss.ndcToWorld[3], p);
}

/// Pixel k's direction to the camera, and its world size at its depth
/// (computed by the host in double: float NDC depth loses it in deep
/// frustums).
void Ray(int k, out vec3 toCamera, out float footprint)
{
  int i = k % ss.image.x, j = k / ss.image.x;
  float x = (float(i) + 0.5) / float(ss.image.x) * 2.0 - 1.0, y = (float(j) + 0.5) / float(ss.image.y) * 2.0 - 1.0;
  vec3 n = NDCToWorld(vec3(x, y, -1.0)), f = NDCToWorld(vec3(x, y, 1.0));
  toCamera = normalize(n - f);
  footprint = normals[k].w;
}

void Complete(vec3 n, out vec3 t1, out vec3 t2)
{
  vec3 a = abs(n.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  t1 = normalize(cross(a, n));
  t2 = cross(n, t1);
}

#if CAO_SS_METHOD == 0
float Attenuation(float r)
{
  return (ss.hbao.w & 2) != 0 ? max(0.0, 1.0 - r / ss.scalars.x) : 1.0;
}

float PixelAO(int k)
{
  int i = k % ss.image.x, j = k / ss.image.x;
  int tile = ss.image.w;
  int cell = (j % tile) * tile + (i % tile);
  float rotation = ss.pattern[cell].x, jitter = ss.pattern[cell].y;
  int directions = ss.hbao.x, steps = ss.hbao.y, normalRays = ss.hbao.z;
  bool deflect = (ss.hbao.w & 1) != 0;
  float R = ss.scalars.x;
  vec3 toCamera;
  float footprint;
  Ray(k, toCamera, footprint);
  // cao::HBAOFrame: R, or the screen's span at the pixel's depth if shorter.
  float stepLength = (footprint > 0.0 ? min(R, footprint * length(vec2(ss.image.xy))) : R) / float(steps);
  vec3 n = normals[k].xyz;
  vec3 p = positions[k].xyz + (ss.scalars.y * footprint) * n;
  vec3 t1, t2;
  Complete(n, t1, t2);
  float horizonOcclusion = 0.0, normalOcclusion = 0.0;
  for (int d = 0; d < directions; ++d)
  {
    float theta = rotation + 2.0 * Pi * float(d) / float(directions);
    vec3 t = cos(theta) * t1 + sin(theta) * t2;
    vec3 dir = t;
    float H = 0.0, occlusion = 0.0;
    for (int m = 0; m < steps; ++m)
    {
      float z;
      int q = Lookup(p + ((float(m) + jitter) * stepLength) * dir, z);
      if (q < 0)
        break;
      if (!Covered(q) || (deflect && !(z > positions[q].w)))
        continue;
      vec3 v = positions[q].xyz - p;
      float r = length(v), up = dot(v, n), along = dot(v, t);
      if (!(r < R) || !(along > 0.0))
        continue;
      float len = sqrt(up * up + along * along);
      float height = up / len;
      if (height > H)
      {
        occlusion += (height * height - H * H) * Attenuation(r);
        H = height;
        if (deflect)
          dir = (up * n + along * t) / len;
      }
    }
    horizonOcclusion += occlusion;
    for (int ray = 0; ray < normalRays; ++ray)
    {
      float z2 = H * H + (float(ray) + jitter * 0.999) * (1.0 - H * H) / float(normalRays);
      vec3 rd = sqrt(z2) * n + sqrt(max(0.0, 1.0 - z2)) * t;
      for (int m = 0; m < steps; ++m)
      {
        float z;
        float distance = (float(m) + jitter) * stepLength;
        int q = Lookup(p + distance * rd, z);
        if (q < 0)
          break;
        if (!Covered(q) || !(z > positions[q].w))
          continue;
        vec3 v = positions[q].xyz - p;
        if (!(dot(v, n) > 0.0) || !(dot(v, v) < R * R))
          continue;
        normalOcclusion += Attenuation(length(v)) * (1.0 - H * H) / float(directions * normalRays);
        break;
      }
    }
  }
  return clamp(1.0 - (horizonOcclusion / float(directions) + normalOcclusion), 0.0, 1.0);
}
#else
float PixelAO(int k)
{
  int i = k % ss.image.x, j = k / ss.image.x;
  int tile = ss.image.w, sets = ss.volumetric.y, n = ss.volumetric.x;
  int set = (j % tile) * tile + (i % tile);
  float R = ss.scalars.x;
  vec3 Z;
  float footprint;
  Ray(k, Z, footprint);
  // The screen's right direction, across the pixel's ray.
  vec3 right = normalize(NDCToWorld(vec3(1.0, 0.0, 0.0)) - NDCToWorld(vec3(-1.0, 0.0, 0.0)));
  vec3 X = normalize(right - dot(right, Z) * Z), Y = cross(Z, X);
  vec3 p = positions[k].xyz, N = normals[k].xyz;
  float nx = dot(N, X), ny = dot(N, Y), nz = max(1e-6, dot(N, Z));
  float sum = 0.0, scale = 4.0 / (R * R * R * R);
  for (int s = 0; s < n; ++s)
  {
    vec2 xy = disk[set + sets * s].xy;
    float chord = sqrt(max(0.0, R * R - dot(xy, xy)));
    float zNDC;
    int q = Lookup(p + xy.x * X + xy.y * Y, zNDC);
    float surface = -3.0e38;
    if (q >= 0 && q != k && Covered(q)) // (the pixel itself: its tangent plane only, as on the CPU)
    {
      surface = dot(positions[q].xyz - p, Z);
      if (ss.volumetric.z != 0 && surface >= chord)
        surface = -3.0e38;
    }
    float tangent = -(xy.x * nx + xy.y * ny) / nz;
    float zMin = max(max(-chord, surface), tangent), zMax = chord;
    if (zMin < zMax)
      sum += scale * ((xy.x * nx + xy.y * ny) * (zMax - zMin) + nz * (zMax * zMax - zMin * zMin) * 0.5);
  }
  return R * R * sum / float(n);
}
#endif

void main()
{
  int k = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (k >= ss.image.x * ss.image.y)
    return;
  ao[k] = Covered(k) ? PixelAO(k) : uintBitsToFloat(0x7fc00000u); // NaN: not covered
}
