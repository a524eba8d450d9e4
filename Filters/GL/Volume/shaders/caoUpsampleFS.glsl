// caoUpsampleFS.glsl - spreads a ray cast drawn at one ray per k x k pixels
// (RenderParams limits.w = k, into the caster's own RGBA16F target) over
// the host's viewport: an interactive frame at a fraction of the cost, as
// vtkGPUVolumeRayCastMapper's image sample distance.
//  - Outside depth peeling: the premultiplied colour, filtered linearly
//    (the target is transparent where no ray hit the volume), blended over
//    the framebuffer.
//  - Inside it (CAO_RENDER_PEEL): the nearest ray's back and front outputs,
//    for the host's blending; a pixel draws only where that ray drew
//    (alpha -1: it did not) and where the pixel's own peeled depths say the
//    stage draws; the peel's front segment is under-blended here, with the
//    pixel's own front colour so far.
layout(std140, binding = CAO_BINDING_RENDER_PARAMS) uniform RenderBlock
{
  RenderParams rp;
};
layout(binding = CAO_UNIT_LOW_BACK) uniform sampler2D lowBack;
layout(binding = CAO_UNIT_LOW_FRONT) uniform sampler2D lowFront;
layout(binding = CAO_UNIT_PEEL_OUTER) uniform sampler2D peelOuter;
layout(binding = CAO_UNIT_PEEL_FRONT) uniform sampler2D peelFront;

layout(location = 0) out vec4 fragColor;  // peeling: the back output
layout(location = 1) out vec4 frontColor; // peeling: the front output

void main()
{
  float k = float(max(rp.limits.w, 1));
  vec2 frag = gl_FragCoord.xy - rp.viewport.xy;
  ivec2 size = textureSize(lowBack, 0);
  if ((rp.dims.w & CAO_RENDER_PEEL) == 0)
  {
    fragColor = texture(lowBack, frag / (k * vec2(size)));
    frontColor = vec4(0.0);
    return;
  }
  ivec2 pixel = ivec2(frag);
  ivec2 low = min(ivec2(frag / k), size - 1);
  vec4 back = texelFetch(lowBack, low, 0);
  if (back.a < 0.0)
    discard;
  vec4 front = texelFetch(lowFront, low, 0);
  int stage = rp.limits.z;
  if (stage != CAO_PEEL_OUTSIDE && texelFetch(peelOuter, pixel, 0).x == -1.0)
    discard; // this pixel's peels are done
  if (stage == CAO_PEEL_LAYER)
  {
    vec4 last = texelFetch(peelFront, pixel, 0);
    // (precise: the same bits as the ray cast's own under-blend at k = 1)
    float transmitted = 1.0 - last.a;
    precise vec4 under =
      vec4(transmitted * front.rgb + last.rgb, 1.0 - transmitted * (1.0 - front.a));
    front = under;
  }
  fragColor = back;
  frontColor = front;
}
