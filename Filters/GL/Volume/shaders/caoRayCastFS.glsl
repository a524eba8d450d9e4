// caoRayCastFS.glsl (after caoClipTest.glsl) - the volume ray caster.
//
// Per pixel: the ray through the pixel centre, from the near plane, in
// world units; clipped to the volume's box [0, dims - 1] (voxel index space)
// and to the opaque geometry's depth. Samples are `sampling.x` world units
// apart, from a per-pixel jittered start. At each sample:
//  - the scalar (trilinear) looks up colour and step-corrected opacity in
//    the transfer-function table;
//  - the shadow test against the clip mesh's depth maps (caoClipTest.glsl)
//    removes the sample when it is inside the mesh (subtraction) or outside
//    it (probing); where the ray comes out of the clipped region, the next
//    sample moves onto the clip surface (bisection; CAO_RENDER_CLIP_ENTRY),
//    and the samples after it follow from there;
//  - the AO (trilinear; with clipping, over the unclipped voxels only;
//    with CAO_RENDER_AO_CALIBRATED, against an open half-space of the
//    sample's opacity at the depth the ray has gone into the matter: see
//    Calibrated) scales the ambient term: 1 - strength * (1 - AO);
//  - with shading, gradient Blinn-Phong adds the diffuse and specular terms
//    as vtkVolumeProperty defines them, summed over the renderer's lights
//    (each with its colour and intensity; two-sided, as VTK's ray caster
//    lights a volume, so ParaView's light kit looks the same).
// Front-to-back compositing, premultiplied output, early termination.
//
// CAO_RENDER_PEEL: drawn inside a host's dual depth peeling (VTK's
// vtkDualDepthPeelingPass, ParaView's "Depth Peeling For Volumes"), where
// the framebuffer has no depth to read. The host's peeled depths
// (pairs (-near, far) in window depth) bound the ray segments each stage
// composites, on the same per-pixel sample lattice as a whole ray, so the
// segments join without seams (a sample moved onto the clip surface moves
// the lattice after it within its segment only; the next segment starts on
// the pixel's lattice again):
//  - CAO_PEEL_OUTSIDE: before the nearest translucent layer into the front
//    output, and from the farthest one to the opaque depth into the back;
//  - CAO_PEEL_LAYER: the segments between this peel's outer and inner
//    depths, the front one under-blended with the front colour so far;
//  - CAO_PEEL_REMAINDER: what the peels left, into the back output.
//
// limits.w = k > 1 (interactive frames): drawn into the caster's own
// target, one fragment per k x k pixels; caoUpsampleFS.glsl spreads it.
layout(std140, binding = CAO_BINDING_RENDER_PARAMS) uniform RenderBlock
{
  RenderParams rp;
};
layout(binding = CAO_UNIT_SCALARS) uniform sampler3D scalarTexture;
layout(binding = CAO_UNIT_AO) uniform sampler3D aoTexture;
layout(binding = CAO_UNIT_TABLE) uniform sampler2D tableTexture;
layout(binding = CAO_UNIT_DEPTH) uniform sampler2D depthTexture;
layout(binding = CAO_UNIT_AO_SAMPLES) uniform sampler3D aoSamplesTexture;
layout(binding = CAO_UNIT_HALF_SPACE) uniform sampler2D halfSpaceTexture;
layout(binding = CAO_UNIT_PEEL_OUTER) uniform sampler2D peelOuter;
layout(binding = CAO_UNIT_PEEL_INNER) uniform sampler2D peelInner;
layout(binding = CAO_UNIT_PEEL_FRONT) uniform sampler2D peelFront;
layout(binding = CAO_UNIT_PEEL_OPAQUE) uniform sampler2D peelOpaque;

layout(location = 0) out vec4 fragColor;  // peeling: the back output
layout(location = 1) out vec4 frontColor; // peeling: the front output

/// A deterministic per-pixel offset in [0, 1) (integer hash of the pixel):
/// the same pixel gets the same jitter in every frame, so images repeat.
float Jitter(ivec2 pixel)
{
  uint h = uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + 26699u;
  h = (h ^ (h >> 16u)) * 0x7feb352du;
  h = (h ^ (h >> 15u)) * 0x846ca68bu;
  h ^= h >> 16u;
  return float(h >> 8u) * (1.0 / 16777216.0);
}

/// The clip test the picture uses (CAO_RENDER_CLIP_SMOOTH). The maps hold
/// one depth interval list per pixel, so Inside() sees the clip surface as
/// a staircase of pixels: where the surface runs along the clipping
/// camera's direction (its silhouette in the maps) a step can be many
/// voxels deep, and a thin sliver of matter left by the clip shows the
/// staircase as stripes. Here each of the 4 nearest pixel centres gives a
/// signed depth distance to its nearest interval boundary (positive
/// inside), clamped to one pixel's size in depth units (a pixel without an
/// interval counts as one pixel outside), and the point is inside where
/// their bilinear blend is positive: the same surface at pixel centres,
/// continuous between them. The classifier keeps Inside() (bit for bit the
/// CPU's); the two differ only within a pixel of the surface.
bool InsideSmooth(vec3 q)
{
  float u = dot(clip.toCamera[0].xyz, q) + clip.toCamera[0].w - 0.5;
  float v = dot(clip.toCamera[1].xyz, q) + clip.toCamera[1].w - 0.5;
  float depth = dot(clip.toCamera[2].xyz, q) + clip.toCamera[2].w;
  // One pixel in depth units: |depth row| / |u row| (orthonormal axes).
  float h = length(clip.toCamera[2].xyz) / max(length(clip.toCamera[0].xyz), 1e-30);
  if (!(u > -1.0 && v > -1.0 && u < float(clip.map.x) && v < float(clip.map.y)))
    return false;
  int x0 = int(floor(u)), y0 = int(floor(v));
  vec2 f = vec2(u - float(x0), v - float(y0));
  int layerSize = clip.map.x * clip.map.y * clip.map.z;
  float sum = 0.0;
  for (int n = 0; n < 4; ++n)
  {
    int x = x0 + (n & 1), y = y0 + (n >> 1);
    float sd = -h;
    if (x >= 0 && y >= 0 && x < clip.map.x && y < clip.map.y)
    {
      int base = (y * clip.map.x + x) * clip.map.z;
      for (int l = 0; l < clip.map.z; ++l)
      {
        float front = maps[base + l], back = maps[base + layerSize + l];
        if (front <= back)
          sd = max(sd, min(depth - front, back - depth));
      }
    }
    float w = ((n & 1) != 0 ? f.x : 1.0 - f.x) * ((n >> 1) != 0 ? f.y : 1.0 - f.y);
    sum += w * clamp(sd, -h, h);
  }
  return sum > 0.0;
}

vec3 Unproject(vec2 ndc, float z)
{
  mat4 m = mat4(rp.ndcToWorld[0], rp.ndcToWorld[1], rp.ndcToWorld[2], rp.ndcToWorld[3]);
  vec4 p = m * vec4(ndc, z, 1.0);
  return p.xyz / p.w;
}

/// The LAO at `depth` voxels below an open flat face (0: the last empty
/// layer) of matter of LAO-step opacity `a` (cao::HalfSpaceTable, linear in
/// both; depths past the table's read its deepest layer); and, in y, the
/// LAO of that matter enclosed (the deepest layer).
vec2 HalfSpace(float depth, float a)
{
  // (the table as a texture, texel centres at the table's points: one
  // filtered fetch is the bilinear lookup, clamped at its edges; green holds
  // the deepest layer at every depth: the matter enclosed, for `a`)
  return texture(halfSpaceTexture,
    vec2((clamp(a, 0.0, 1.0) * float(CAO_HALF_SPACE_OPACITIES - 1) + 0.5) /
        float(CAO_HALF_SPACE_OPACITIES),
      (clamp(depth, 0.0, float(CAO_HALF_SPACE_LAYERS - 1)) + 0.5) / float(CAO_HALF_SPACE_LAYERS)))
    .rg;
}

/// The least share of the way from an open half-space's LAO down to opaque
/// enclosure that the calibration divides the shortfall by (0.4: the grain
/// of 0.5, and more of a slot's darkening kept).
#define CAO_CALIBRATION_FLOOR 0.4

/// The AO at index-space point p: trilinear over the 8 voxels around it,
/// over those the clip leaves when the frame clips (a clipped voxel holds an
/// AO that no longer means anything: its matter is gone, and blending it in
/// would darken the cut surfaces; weights renormalised; 1 when all 8 are
/// clipped). One filtered fetch of the AO samples (caoAOSamples.glsl: the
/// RayCaster made them for this frame's clip, AO and opacity) gives the
/// four trilinear sums.
///
/// `calibrated` (CAO_RENDER_AO_CALIBRATED): the AO as the share of the
/// light that an open flat half-space of the same matter gives at the same
/// depth. The ray caster composites the samples behind a face too, inside
/// the matter, where even an open half-space's LAO is low: that is the
/// matter's own depth, not occlusion by the scene. The matter's opacity is
/// the mean of the voxels' that hold matter, by their trilinear weights
/// (`a`: continuous from voxel to voxel, as their largest is not, which
/// showed as blocks); the depth is, in the face's layer,
/// the weight of the voxels that hold matter (0 at the last empty layer, 1
/// at the first full one, as the trilinear ramp between them), and where
/// all 8 hold matter, `inMatter` (the ray's estimate: see CastRay; on an
/// oblique face it overestimates the depth, so an open face stays at 1).
/// The shortfall from that half-space, over the range between it and the
/// matter's enclosed interior (see `range`), is what the scene occludes. `depth` returns the depth used.
float VoxelAO(vec3 p, bool calibrated, float inMatter, out float depth)
{
  vec4 sums = texture(aoSamplesTexture, (clamp(p, vec3(0.0), rp.boxMax.xyz) + 0.5) * rp.invDims.xyz);
  float sum = sums.r, weight = sums.g, a = sums.b, matter = sums.a;
  // (where every voxel the clip leaves holds matter, the two channels hold
  // the same values and filter to the same sum)
  depth = weight > 0.0 && matter < weight ? matter / weight : inMatter;
  if (!(weight > 0.0))
    return 1.0;
  float ao = sum / weight;
  if (!calibrated)
    return ao;
  a = matter > 0.0 ? a / matter : 0.0;
  vec2 table = HalfSpace(depth, a);
  float open = table.x; // an open half-space at this depth; y: enclosed
  // The range: down to this matter enclosed on all sides, but at least
  // CAO_CALIBRATION_FLOOR of the way down to opaque matter enclosing it
  // (aoCalibration.x: the LAO enclosed by opaque matter). Clear matter's
  // own range is small, and dividing by it made the rays' noise in fog a
  // grain of dark specks (carotid.vtk: local luminance deviation 1.25x AO
  // off's; with the floor at 0.4 or 0.5, 1.00x).
  float range = max(open - table.y,
    CAO_CALIBRATION_FLOOR * (open - rp.aoCalibration.x));
  // With one sample per ray every LAO is 1: the range is empty and nothing
  // is occluded.
  return range > 1e-6 ? clamp(1.0 - (open - ao) / range, 0.0, 1.0) : 1.0;
}

/// CastRay's depth chain (see InMatter) after a sample the colour map
/// leaves empty; after one the clip removes (and holds matter) it restarts
/// from 0 (a cut face is open).
#define CAO_DEPTH_AFTER_EMPTY (-1.0)

/// The share of the voxels around index-space point p that hold matter, of
/// those the clip leaves (0 where it leaves none): VoxelAO's depth in a
/// face's layer.
float MatterShare(vec3 p)
{
  vec4 sums = texture(aoSamplesTexture, (clamp(p, vec3(0.0), rp.boxMax.xyz) + 0.5) * rp.invDims.xyz);
  return sums.g > 0.0 ? sums.a / sums.g : 0.0;
}

/// The depth into the matter (voxels) of a sample whose 8 voxels all hold
/// matter, from the sample a step before it (at `pBefore`, depth `before`,
/// optical depth per step `muBefore`; this one's: `mu`): the depth before
/// plus a step, the part past the face's layer converted to this sample's
/// matter by the ratio of optical depths (so that clear matter in front of
/// dense matter counts for little), at least the face layer's 1. After an
/// empty sample the depth before is where that sample lay in the face's
/// layer: the colour map leaves a sample empty wherever the interpolated
/// scalar is under its opacity ramp, which on a sharp face is most of the
/// layer, and counting from 0 there put the next sample, a step deeper in
/// the matter, back at the layer's end (a plate's face head on, perspective,
/// no jitter: rings where the lattice first lands past the layer, 0.84 of
/// the light where an open face has 1).
float InMatter(float before, float muBefore, float mu, vec3 pBefore, float stepVoxels)
{
  float start = before == CAO_DEPTH_AFTER_EMPTY ? MatterShare(pBefore) : min(before, 1.0);
  float past = max(before - 1.0, 0.0) * muBefore / mu;
  return max(1.0, start + past + stepVoxels);
}

/// The program is specialised per variant (RayCaster): without
/// CAO_WITH_AO or CAO_WITH_AO_CALIBRATION the code that only those frames
/// run is not compiled (a constant false removes it), so a frame with AO
/// off or uncalibrated runs a smaller program.
#ifdef CAO_WITH_AO
const bool CAO_AO_COMPILED = true;
#else
const bool CAO_AO_COMPILED = false;
#endif
#ifdef CAO_WITH_AO_CALIBRATION
const bool CAO_CALIBRATION_COMPILED = true;
#else
const bool CAO_CALIBRATION_COMPILED = false;
#endif

/// Whether the clip removes the sample at index-space point p.
bool Removed(vec3 p, int flags)
{
  return ((flags & CAO_RENDER_CLIP_SMOOTH) != 0 ? InsideSmooth(p) : Inside(p)) ==
    (clip.map.w == CAO_MODE_SUBTRACT);
}

/// Bisection steps that put the first sample behind a cut onto the clip
/// surface (a step / 256).
#define CAO_CLIP_ENTRY_BISECTIONS 8

float Scalar(vec3 tc)
{
  return texture(scalarTexture, tc).r;
}

// The ray of this pixel, set once by main().
vec2 g_ndc;
vec3 g_nearWorld, g_dirWorld, g_origin, g_dir;
float g_tEnter, g_tExit, g_first;

/// Window depth z (0 near, 1 far) as t, world units along the ray.
float DepthToT(float z)
{
  if (z >= 1.0)
    return 3.0e38;
  if (z <= 0.0)
    return 0.0;
  return dot(Unproject(g_ndc, z * 2.0 - 1.0) - g_nearWorld, g_dirWorld);
}

/// CAO_RENDER_AO_CALIBRATED: the depth into the matter (and its optical
/// depth per step) that CastRay's samples from the ray's start would have
/// reached at lattice sample k0, from the samples before it (as far back as
/// the half-space table is deep): a segment of a peeled ray starts where the
/// whole ray would be, so that the segments add up to the ray.
void DepthBefore(float k0, int flags, float stepVoxels, out float depth, out float mu)
{
  mu = 1.0;
  float step = rp.sampling.x;
  float first = max(0.0, ceil((g_tEnter - g_first) / step));
  float from = max(first, k0 - ceil(float(CAO_HALF_SPACE_LAYERS + 1) / max(stepVoxels, 1e-6)));
  // (a window that starts after the ray's first sample starts as after an
  // empty one: exact where that was empty, the depth read from the voxels
  // where it held matter)
  depth = from > first ? CAO_DEPTH_AFTER_EMPTY : 0.0;
  bool clipped = (flags & CAO_RENDER_CLIP) != 0;
  for (float k = from; k < k0; k += 1.0)
  {
    vec3 p = g_origin + (g_first + k * step) * g_dir;
    float sv = Scalar((p + 0.5) * rp.invDims.xyz);
    vec4 c = isnan(sv) ? vec4(0.0) : texture(tableTexture, vec2(sv * rp.sampling.y +
        rp.sampling.z, 0.5));
    if (c.a <= 0.0 || (clipped && Removed(p, flags)))
    {
      depth = c.a <= 0.0 ? CAO_DEPTH_AFTER_EMPTY : 0.0;
      continue;
    }
    float m = -log(max(1.0 - c.a, 1e-6));
    VoxelAO(p, true, InMatter(depth, mu, m, p - step * g_dir, stepVoxels), depth);
    mu = m;
  }
}

/// Composite the samples with tFrom <= t < tTo (t <= tTo when `inclusive`)
/// of the pixel's lattice t = first + k * step, within the volume's box:
/// premultiplied colour, front to back.
vec4 CastRay(float tFrom, float tTo, bool inclusive)
{
  int flags = rp.dims.w;
  float step = rp.sampling.x;
  float tEnd = min(tTo, g_tExit);
  float k0 = max(0.0, ceil((max(tFrom, g_tEnter) - g_first) / step));
  float t = g_first + k0 * step;
  vec3 origin = g_origin, dir = g_dir, dirWorld = g_dirWorld;
  mat3 normalMatrix = mat3(rp.normalToWorld[0].xyz, rp.normalToWorld[1].xyz,
    rp.normalToWorld[2].xyz);
  vec3 texel = rp.invDims.xyz;
  vec4 sum = vec4(0.0);
  // CAO_RENDER_AO_CALIBRATED (see VoxelAO, InMatter): the previous
  // sample's depth into the matter (voxels; 0 after a cut,
  // CAO_DEPTH_AFTER_EMPTY after an empty sample) and its optical depth per
  // step.
  float depthBefore = 0.0, muBefore = 1.0;
  float stepVoxels = step * length(dir);
  if (CAO_CALIBRATION_COMPILED && (flags & (CAO_RENDER_AO | CAO_RENDER_AO_CALIBRATED)) ==
      (CAO_RENDER_AO | CAO_RENDER_AO_CALIBRATED) && k0 > 0.0)
    DepthBefore(k0, flags, stepVoxels, depthBefore, muBefore);
  // A segment that starts after the ray's first sample carries on from
  // the sample before it: whether that one was clipped away (so that the
  // first sample behind a cut still moves onto the clip surface).
  bool wasRemoved = k0 > 0.0 && (flags & CAO_RENDER_CLIP) != 0 &&
    Removed(origin + (t - step) * dir, flags);
  // The ray's first sample in the box, in matter: the matter starts at the
  // box's face, and the AO there changes fast with depth (opaque matter:
  // from the face's to the enclosed value within a voxel), so the
  // per-pixel jitter of the sample's depth showed as grain on the faces.
  // Its AO is read at the face, where the ray enters: only the ray's first
  // lattice sample (i == 0), never one the clip entry moved, and only where
  // the face itself holds matter the clip keeps. Decided here, once a
  // segment, not in the loop (whose body llvmpipe runs for every sample).
  vec3 face = origin + g_tEnter * dir;
  vec3 tcFace = (face + 0.5) * rp.invDims.xyz;
  bool aoAtFace = false;
  if (CAO_AO_COMPILED && (flags & CAO_RENDER_AO) != 0 && k0 == 0.0)
  {
    float sf = Scalar(tcFace);
    aoAtFace = !isnan(sf) &&
      texture(tableTexture, vec2(sf * rp.sampling.y + rp.sampling.z, 0.5)).a > 0.0 &&
      !((flags & CAO_RENDER_CLIP) != 0 && Removed(face, flags));
  }
  for (int i = int(k0); i < rp.limits.x && (inclusive ? t <= tEnd : t < tEnd); ++i, t += step)
  {
    vec3 p = origin + t * dir;
    vec3 tc = (p + 0.5) * rp.invDims.xyz;
    float s = Scalar(tc);
    // A NaN voxel (and the samples it enters by interpolation) is empty,
    // as the LAO's opacity takes it.
    vec4 c = isnan(s) ? vec4(0.0) : texture(tableTexture, vec2(s * rp.sampling.y + rp.sampling.z, 0.5));
    if (c.a <= 0.0)
    {
      depthBefore = CAO_DEPTH_AFTER_EMPTY;
      continue;
    }
    if ((flags & CAO_RENDER_CLIP) != 0)
    {
      if (Removed(p, flags))
      {
        wasRemoved = true;
        depthBefore = 0.0;
        continue;
      }
      // (With CAO_RENDER_CLIP_ENTRY off, the first sample stays where the
      // step put it.)
      if (wasRemoved && (flags & CAO_RENDER_CLIP_ENTRY) != 0)
      {
        // The ray came out of the clipped region since the last sample:
        // sample the matter at the clip surface (bisection between the step
        // before and this one), not at a step-quantized depth behind it.
        // Behind a curved cut the AO changes fast with depth, and that
        // quantization showed as concentric rings (jitter off) or grain
        // (jitter on). The samples after it follow from the surface.
        float lo = t - step, hi = t;
        for (int k = 0; k < CAO_CLIP_ENTRY_BISECTIONS; ++k)
        {
          float mid = 0.5 * (lo + hi);
          if (Removed(origin + mid * dir, flags))
            lo = mid;
          else
            hi = mid;
        }
        wasRemoved = false;
        t = hi;
        p = origin + t * dir;
        tc = (p + 0.5) * rp.invDims.xyz;
        s = Scalar(tc);
        c = isnan(s) ? vec4(0.0) : texture(tableTexture, vec2(s * rp.sampling.y + rp.sampling.z, 0.5));
        if (c.a <= 0.0)
          continue;
      }
    }
    float ambient = 1.0;
    if (CAO_AO_COMPILED && (flags & CAO_RENDER_AO) != 0)
    {
      bool clipped = (flags & CAO_RENDER_CLIP) != 0;
      bool calibrated = CAO_CALIBRATION_COMPILED && (flags & CAO_RENDER_AO_CALIBRATED) != 0;
      float mu = -log(max(1.0 - c.a, 1e-6));
      float depth = 0.0;
      // (the first sample's AO at the box's face: aoAtFace, above)
      bool atFace = aoAtFace && i == 0 && depthBefore <= 0.0;
      vec3 pAO = atFace ? face : p, tcAO = atFace ? tcFace : tc;
      float ao = clipped || calibrated ?
        VoxelAO(pAO, calibrated, InMatter(depthBefore, muBefore, mu, p - step * dir, stepVoxels), depth)
        : texture(aoTexture, tcAO).r;
      ambient = 1.0 - rp.sampling.w * (1.0 - ao);
      depthBefore = depth;
      muBefore = mu;
    }
    vec3 color;
    if ((flags & CAO_RENDER_SHADE) != 0)
    {
      vec3 g = vec3(Scalar(tc + vec3(texel.x, 0, 0)) - Scalar(tc - vec3(texel.x, 0, 0)),
        Scalar(tc + vec3(0, texel.y, 0)) - Scalar(tc - vec3(0, texel.y, 0)),
        Scalar(tc + vec3(0, 0, texel.z)) - Scalar(tc - vec3(0, 0, texel.z)));
      // Where the field is flat (inside matter, and so on the faces the
      // clip cuts through it) the gradient has no direction: blend towards
      // a normal facing the viewer, as a cut face would be lit.
      if (any(isnan(g)))
        g = vec3(0.0); // beside a NaN voxel: no direction (faces the viewer)
      vec3 n = normalMatrix * g;
      float len = length(n);
      vec3 facing = -dirWorld;
      n = len > 0.0 ? n / len : facing;
      if (dot(n, dirWorld) > 0.0)
        n = -n; // two-sided: the normal faces the viewer
      n = normalize(mix(facing, n, smoothstep(0.0, 0.02, len)));
      vec3 diffuse = vec3(0.0), specular = vec3(0.0);
      for (int l = 0; l < rp.limits.y; ++l)
      {
        vec3 lightDir = rp.lights[l].w > 0.5 ? -dirWorld : normalize(rp.lights[l].xyz);
        vec3 halfway = normalize(lightDir - dirWorld);
        diffuse += rp.lightColors[l].rgb * abs(dot(n, lightDir));
        specular += rp.lightColors[l].rgb * pow(abs(dot(n, halfway)), rp.shading.w);
      }
      color = c.rgb * (rp.shading.x * ambient + rp.shading.y * diffuse) +
        rp.shading.z * specular;
    }
    else
    {
      color = c.rgb * ambient;
    }
    float a = c.a * (1.0 - sum.a);
    sum.rgb += a * color;
    sum.a += a;
    if (sum.a >= rp.boxMax.w)
      break;
  }
  return sum;
}

/// The stages of the host's dual depth peeling, as vtkDualDepthPeelingPass
/// draws its own volumes: which segments go to the back output (location
/// 0) and which to the front one (location 1).
void Peel(ivec2 pixel)
{
  int stage = rp.limits.z;
  if (stage == CAO_PEEL_OUTSIDE)
  {
    vec2 inner = texelFetch(peelInner, pixel, 0).xy;
    vec2 outer = texelFetch(peelOuter, pixel, 0).xy;
    bool opaque = outer.y >= 0.0;
    bool translucent = inner.x != -1.0;
    vec4 front = vec4(0.0), back = vec4(0.0);
    if (!opaque && !translucent)
      back = CastRay(0.0, DepthToT(1.0), true);
    else if (!translucent)
      back = CastRay(0.0, DepthToT(inner.y), true);
    else
    {
      front = CastRay(0.0, DepthToT(-inner.x), false);
      if (front.a < rp.boxMax.w)
        back = CastRay(DepthToT(inner.y), DepthToT(opaque ? outer.y : 1.0), true);
    }
    fragColor = back;
    frontColor = front;
  }
  else if (stage == CAO_PEEL_LAYER)
  {
    vec2 inner = texelFetch(peelInner, pixel, 0).xy;
    vec2 outer = texelFetch(peelOuter, pixel, 0).xy;
    vec4 last = texelFetch(peelFront, pixel, 0);
    if (outer.x == -1.0)
      discard; // peeled already
    float frontStart = -outer.x, frontEnd = -inner.x;
    float backStart = inner.y, backEnd = outer.y;
    bool onlyBack = frontStart == backStart && frontEnd == backEnd;
    bool noInner = inner.x == -1.0;
    if (noInner)
      frontEnd = outer.y;
    float opaqueDepth = texelFetch(peelOpaque, pixel, 0).x;
    bool behindOpaque = frontEnd >= opaqueDepth;
    vec4 front = onlyBack ?
      vec4(0.0) :
      CastRay(DepthToT(frontStart), DepthToT(behindOpaque ? opaqueDepth : frontEnd), false);
    vec4 back = vec4(0.0);
    if (!behindOpaque && !noInner)
      back = CastRay(DepthToT(backStart), DepthToT(backEnd), false);
    fragColor = back;
    // Under-blend the front segment (the host keeps 1 - alpha for its MAX
    // blending); drawn into the caster's own target (one ray per k x k
    // pixels, or a kept draw) the spread does it per pixel.
    // (precise: the same bits as the spread's under-blend, caoUpsampleFS.glsl,
    // with no fused multiply-add in one and not the other)
    float transmitted = 1.0 - last.a;
    precise vec4 under =
      vec4(transmitted * front.rgb + last.rgb, 1.0 - transmitted * (1.0 - front.a));
    frontColor = rp.limits.w > 1 || (rp.dims.w & CAO_RENDER_OWN_TARGET) != 0 ? front : under;
  }
  else
  {
    vec2 range = texelFetch(peelOuter, pixel, 0).xy;
    if (range.x == -1.0)
      discard;
    fragColor = CastRay(DepthToT(-range.x), DepthToT(range.y), true);
    frontColor = vec4(0.0);
  }
}

void main()
{
  int flags = rp.dims.w;
  // The pixel's position in the viewport; with an image sample distance k
  // > 1, this fragment is one ray for k x k pixels, through their centre,
  // reading the peeled depths and the opaque depth of one of them.
  float k = float(max(rp.limits.w, 1));
  vec2 frag = (gl_FragCoord.xy - rp.viewport.xy) * k;
  ivec2 pixel = min(ivec2(frag), ivec2(round(1.0 / rp.viewport.zw)) - 1);
  g_ndc = frag * rp.viewport.zw * 2.0 - 1.0;
  g_nearWorld = Unproject(g_ndc, -1.0);
  vec3 farWorld = Unproject(g_ndc, 1.0);
  g_dirWorld = normalize(farWorld - g_nearWorld);

  mat4 toIndex = mat4(rp.worldToIndex[0], rp.worldToIndex[1], rp.worldToIndex[2],
    rp.worldToIndex[3]);
  g_origin = (toIndex * vec4(g_nearWorld, 1.0)).xyz;
  g_dir = mat3(toIndex) * g_dirWorld; // index units per world unit

  // Slab test against [0, boxMax]; t in world units from the near plane.
  vec3 inv = 1.0 / g_dir;
  vec3 t0 = (vec3(0.0) - g_origin) * inv;
  vec3 t1 = (rp.boxMax.xyz - g_origin) * inv;
  vec3 tLow = min(t0, t1), tHigh = max(t0, t1);
  g_tEnter = max(max(max(tLow.x, tLow.y), tLow.z), 0.0);
  g_tExit = min(min(tHigh.x, tHigh.y), tHigh.z);
  if (!(g_tExit > g_tEnter))
    discard;
  g_first = g_tEnter + rp.sampling.x * ((flags & CAO_RENDER_JITTER) != 0 ? Jitter(pixel) : 0.5);
  if ((flags & CAO_RENDER_PEEL) != 0)
  {
    Peel(pixel);
    return;
  }
  float tEnd = g_tExit;
  if ((flags & CAO_RENDER_OPAQUE_DEPTH) != 0)
  {
    float depth = texelFetch(depthTexture, pixel, 0).r;
    if (depth < 1.0)
      tEnd = min(tEnd, DepthToT(depth));
  }
  if (!(tEnd > g_tEnter))
    discard;
  fragColor = CastRay(g_tEnter, tEnd, true);
  frontColor = vec4(0.0);
}
