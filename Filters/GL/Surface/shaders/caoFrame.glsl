// caoFrame.glsl - a frame kept on the GPU (caoFrameGL): one pixel per
// invocation, the stage chosen by CAO_FRAME_STAGE:
//  0  count the pixels whose drawn depth differs from the last traced one;
//  1  the G-buffer from the drawn depth: cao::FrameFromDepth's twin, in
//     double (the pixel's point unprojected, its normal the cross product of
//     a neighbour per axis, turned to face the camera), into the
//     grid's frame (BitGrid::ToGrid) for the cone tracer (world axes for the
//     screen-space estimators, which also read the NDC depth in the
//     point's w and the pixel's world size in the normal's); counts covered
//     pixels;
//  2  the combine: the colour darkened by the AO, as the pass's CPU combine
//     (ambient term: colour - s (1 - AO) ambient; whole colour: colour (1 - s (1 - AO))).
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_FR_PARAMS) uniform FrameBlock
{
  FrameParams fr;
};
#if CAO_FRAME_DEPTH_TEXTURE
// The drawn depth blitted into a texture of the framebuffer's own format.
layout(binding = CAO_UNIT_DEPTH) uniform sampler2D depthTexture;
float Depth(int index)
{
  return texelFetch(depthTexture, ivec2(index % fr.image.x, index / fr.image.x), 0).r;
}
#else
// The drawn depth read into a buffer (glReadPixels, floats).
layout(std430, binding = CAO_BINDING_FR_DEPTH) readonly buffer DepthBlock
{
  float depth[];
};
float Depth(int index)
{
  return depth[index];
}
#endif
layout(std430, binding = CAO_BINDING_FR_COUNT) buffer CountBlock
{
  uint counts[];
};

#if CAO_FRAME_STAGE == 0
#if CAO_FRAME_DEPTH_TEXTURE
layout(binding = CAO_UNIT_STATE) uniform sampler2D previousTexture;
float Previous(int index)
{
  return texelFetch(previousTexture, ivec2(index % fr.image.x, index / fr.image.x), 0).r;
}
#else
layout(std430, binding = CAO_BINDING_FR_PREVIOUS) readonly buffer PreviousBlock
{
  float previous[];
};
float Previous(int index)
{
  return previous[index];
}
#endif
#elif CAO_FRAME_STAGE == 1
layout(std430, binding = CAO_BINDING_VCT_POINTS) writeonly buffer PointBlock
{
  vec4 points[];
};
layout(std430, binding = CAO_BINDING_VCT_NORMALS) writeonly buffer NormalBlock
{
  vec4 normals[];
};

double Row(int r, dvec4 q)
{
  dvec4 m = dvec4(fr.ndcToWorld[r]) + dvec4(fr.ndcToWorldLow[r]);
  return m.x * q.x + m.y * q.y + m.z * q.z + m.w * q.w;
}

/// cao::NDCToWorld: false when the point is not finite.
bool Unproject(double x, double y, double z, out dvec3 p)
{
  dvec4 q = dvec4(x, y, z, 1.0);
  double w = Row(3, q);
  p = dvec3(Row(0, q), Row(1, q), Row(2, q)) / w;
  return !(isnan(float(p.x)) || isnan(float(p.y)) || isnan(float(p.z)) || isinf(float(p.x)) ||
    isinf(float(p.y)) || isinf(float(p.z)));
}

/// The pixel's drawn point; false on the background or outside the image.
bool Point(int i, int j, out dvec3 p)
{
  p = dvec3(0.0);
  if (i < 0 || j < 0 || i >= fr.image.x || j >= fr.image.y)
    return false;
  double d = double(Depth(j * fr.image.x + i));
  if (!(d >= 0.0 && d < 1.0))
    return false;
  double x = (double(i) + 0.5) / double(fr.image.x) * 2.0 - 1.0;
  double y = (double(j) + 0.5) / double(fr.image.y) * 2.0 - 1.0;
  return Unproject(x, y, 2.0 * d - 1.0, p);
}

vec3 ToGrid(dvec3 p)
{
  return vec3(dot(dvec3(fr.toGrid[0].xyz), p), dot(dvec3(fr.toGrid[1].xyz), p), dot(dvec3(fr.toGrid[2].xyz), p));
}
#elif CAO_FRAME_STAGE == 2
layout(rgba32f, binding = CAO_IMAGE_FR_COLOR) uniform image2D colorImage;
layout(rgba32f, binding = CAO_IMAGE_FR_AMBIENT) readonly uniform image2D ambientImage;
layout(std430, binding = CAO_BINDING_VCT_AO) readonly buffer AOBlock
{
  float ao[];
};
#endif

void main()
{
  int index = int(gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u);
  if (index >= fr.image.x * fr.image.y)
    return;
#if CAO_FRAME_STAGE == 0
  if (floatBitsToUint(Depth(index)) != floatBitsToUint(Previous(index)))
    atomicAdd(counts[0], 1u);
#elif CAO_FRAME_STAGE == 1
  int i = index % fr.image.x, j = index / fr.image.x;
  dvec3 p;
  points[index] = vec4(0.0, 0.0, 0.0, 3.0e38); // w: no NDC depth (the screen-space estimators' "none")
  normals[index] = vec4(0.0);                   // w 0: no point (the cone tracer's)
  if (!Point(i, j, p))
    return;
  // Per axis: with two pixels on each side, the side that continues the
  // pixel's own plane (the smaller |2 p1 - p2 - p0|); else the nearer
  // neighbour (as cao::FrameFromDepth).
  dvec3 tangent[2];
  for (int axis = 0; axis < 2; ++axis)
  {
    ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    dvec3 minus, plus, minus2, plus2;
    bool hasMinus = Point(i - step.x, j - step.y, minus);
    bool hasPlus = Point(i + step.x, j + step.y, plus);
    if (!hasMinus && !hasPlus)
      return;
    dvec3 a = plus - p, b = p - minus;
    bool usePlus = hasPlus && (!hasMinus || dot(a, a) <= dot(b, b));
    if (hasMinus && hasPlus && Point(i - 2 * step.x, j - 2 * step.y, minus2) &&
      Point(i + 2 * step.x, j + 2 * step.y, plus2))
    {
      dvec3 bendPlus = 2.0 * plus - plus2 - p, bendMinus = 2.0 * minus - minus2 - p;
      usePlus = dot(bendPlus, bendPlus) <= dot(bendMinus, bendMinus);
    }
    tangent[axis] = usePlus ? a : b;
  }
  dvec3 n = cross(tangent[0], tangent[1]);
  double len = sqrt(dot(n, n));
  if (!(len > 0.0) || isinf(float(len)))
    return;
  double x = (double(i) + 0.5) / double(fr.image.x) * 2.0 - 1.0;
  double y = (double(j) + 0.5) / double(fr.image.y) * 2.0 - 1.0;
  dvec3 nearPoint, farPoint;
  if (!Unproject(x, y, -1.0, nearPoint) || !Unproject(x, y, 1.0, farPoint))
    return;
  dvec3 ray = normalize(farPoint - nearPoint);
  n /= len;
  double cosine = dot(n, ray);
  n *= cosine > 0.0 ? -1.0 : 1.0; // facing the camera
  // w: the point's NDC depth, and the world size of a pixel there (> 0),
  // as the screen-space estimators read them (cao::gl::ScreenAOEngine's
  // host path computes the same from the world position).
  double z = 2.0 * double(Depth(index)) - 1.0;
  dvec3 side;
  float footprint = 0.0;
  if (Unproject(x + 2.0 / double(fr.image.x), y, z, side))
    footprint = float(length(side - p));
  points[index] = vec4(ToGrid(p), float(z));
  normals[index] = vec4(ToGrid(n), max(footprint, 1.0e-30));
  atomicAdd(counts[1], 1u);
#else
  float a = ao[index];
  if (isnan(a))
    return;
  ivec2 texel = ivec2(index % fr.image.x, index / fr.image.x);
  float dark = fr.scalars.x * (1.0 - clamp(a, 0.0, 1.0));
  vec4 own = imageLoad(colorImage, texel);
  vec3 rgb = fr.image.z == 1 ? own.rgb * (1.0 - dark)
                             : max(vec3(0.0), own.rgb - dark * imageLoad(ambientImage, texel).rgb);
  imageStore(colorImage, texel, vec4(rgb, own.a));
#endif
}
