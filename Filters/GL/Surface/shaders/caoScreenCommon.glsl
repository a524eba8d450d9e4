// caoScreenCommon.glsl - what the screen-space programs share (caoScreenAO.glsl,
// caoScreenFilter.glsl): one invocation per pixel, the parameter block and
// the frame's pixels (caoGPULayout.h: ScreenAOParams, CAO_BINDING_SS_*).
layout(local_size_x = 64) in;

layout(std140, binding = CAO_BINDING_SS_PARAMS) uniform ScreenBlock
{
  ScreenAOParams ss;
};
layout(std430, binding = CAO_BINDING_SS_POSITIONS) readonly buffer PositionBlock
{
  vec4 positions[];
};
layout(std430, binding = CAO_BINDING_SS_NORMALS) readonly buffer NormalBlock
{
  vec4 normals[];
};

/// Whether pixel k holds a surface point (its NDC depth in w).
bool Covered(int k)
{
  return positions[k].w < 1e30;
}
