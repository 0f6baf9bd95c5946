// The filters, written once for every kind of map. Before this file, the
// receiver's shader defines which kind it serves and which filters to compile:
//
//   PVS_MAP           the kind's parameter struct         (PvsCubeMap, ...)
//   PVS_COMPARE_MAP   its comparison sampler type         (samplerCubeShadow, ...)
//   PVS_RAW_MAP       its plain sampler type              (samplerCube, ...)
//   PVS_FRAME         (map, kind, receiver) -> PvsTexelFrame, the map's texel grid there
//   PVS_TAP           (kind, receiver, frame, offset) -> texel position of a tap `offset`
//                     texels across the lookup direction
//   PVS_TEXEL         (map, kind, receiver, frame, t) -> visibility of the texel holding t
//   PVS_TEXEL_DEPTH   (raw, kind, receiver, frame, t, out receiverDepth) -> its stored depth
//   PVS_SEARCH_RADIUS / PVS_PENUMBRA_RADIUS   in texels, for PCSS
//   PVS_TRANSMIT_MAP  sampler type of the transmittance companion (sampler2D, samplerCube)
//   PVS_FRAME_OF_SIZE (size, kind, receiver) -> PvsTexelFrame, as PVS_FRAME for a map of size
//   PVS_TEXEL_TRANSMITTED (transmit, kind, receiver, frame, t) -> what the translucent
//                     casters let through at the texel holding t
//   PVS_LIT, PVS_PCF, PVS_RANDOM, PVS_PCSS   names of the filter functions (hard is
//                                            PCF's 2 x 2 box cut at one half: shadow_group.glsl)
//   PVS_BOX                                  name of the box PCF sums
//   PVS_TRANSMIT                             name of the translucent casters' lookup
//   PVS_WITH_LIT, PVS_WITH_PCF, ...          which to compile (PVS_WITH_TRANSMIT: the
//                                            lookup of lights with translucent casters)
//
// Every compare reads one texel at its centre against the receiver's own
// tangent plane along the ray through that centre (see PvsTexelFrame), so no
// filter moves a shadow's edge: the hard compare puts it where the map's
// texel centres put it, and the soft filters are centred on the receiver.

#ifdef PVS_WITH_LIT
// No map to read (nothing can shadow a visible receiver): lit where the
// visible side faces the light and lies in its cone.
float PVS_LIT(PVS_MAP kind, PvsReceiver r)
{
  return r.lit;
}
#endif

#ifdef PVS_WITH_PCF
// What side x side bilinear compares one texel apart would return, from the
// (side + 1)^2 texels they touch, each compared at its own centre: a box of
// side texels centred on the receiver, its first and last texels weighted by
// how much of them it covers.
float PVS_BOX(PVS_COMPARE_MAP depthMap, PVS_MAP kind, PvsReceiver r, int side)
{
  PvsTexelFrame f = PVS_FRAME(depthMap, kind, r);
  vec2 start = f.at - 0.5 * float(side);
  vec2 first = floor(start);
  vec2 cut = start - first;
  float sum = 0.0;
  for (int i = 0; i <= side; ++i)
  {
    float wx = i == 0 ? 1.0 - cut.x : (i == side ? cut.x : 1.0);
    for (int j = 0; j <= side; ++j)
    {
      float wy = j == 0 ? 1.0 - cut.y : (j == side ? cut.y : 1.0);
      sum += wx * wy * PVS_TEXEL(depthMap, kind, r, f, first + vec2(float(i), float(j)) + 0.5);
    }
  }
  return sum / float(side * side);
}
#endif

#ifdef PVS_WITH_PCF
float PVS_PCF(PVS_COMPARE_MAP depthMap, PVS_MAP kind, PvsReceiver r, int side)
{
  return r.lit == 0.0 ? 0.0 : PVS_BOX(depthMap, kind, r, side);
}
#endif

#if defined(PVS_WITH_RANDOM) || defined(PVS_WITH_PCSS)
// `samples` taps over a jittered disk of `radius` texels, the disk rotated per
// pixel by the offset texture; when the first eight (the outer ring) agree,
// the point is fully lit or fully dark and the rest are skipped.
float PVS_RANDOM(PVS_COMPARE_MAP depthMap, PVS_MAP kind, PvsReceiver r, sampler3D offsets,
                 int samples, float radius)
{
  if (r.lit == 0.0)
  {
    return 0.0;
  }
  PvsTexelFrame f = PVS_FRAME(depthMap, kind, r);
  float sum = 0.0;
  for (int i = 0; i < 8; ++i)
  {
    sum += PVS_TEXEL(depthMap, kind, r, f, PVS_TAP(kind, r, f, radius * pvsDiskOffset(offsets, i)));
  }
  if (sum < 0.001 || sum > 7.999 || samples <= 8)
  {
    return sum / 8.0;
  }
  for (int i = 8; i < samples; ++i)
  {
    sum += PVS_TEXEL(depthMap, kind, r, f, PVS_TAP(kind, r, f, radius * pvsDiskOffset(offsets, i)));
  }
  return sum / float(samples);
}
#endif

#ifdef PVS_WITH_PCSS
// Percentage-closer soft shadows: the average depth of the blockers found
// over the region through which the point could see the light sets the
// penumbra width, then the disk filter of that width (contact hardening).
float PVS_PCSS(PVS_COMPARE_MAP depthMap, PVS_RAW_MAP raw, PVS_MAP kind, PvsReceiver r,
               sampler3D offsets, int samples)
{
  if (r.lit == 0.0)
  {
    return 0.0;
  }
  PvsTexelFrame f = PVS_FRAME(depthMap, kind, r);
  float search = clamp(PVS_SEARCH_RADIUS(kind, r), 1.0, 32.0);
  float blockers = 0.0;
  float depthSum = 0.0;
  for (int i = 0; i < 16; ++i)
  {
    float receiverDepth;
    vec2 t = PVS_TAP(kind, r, f, search * pvsDiskOffset(offsets, i));
    float depth = PVS_TEXEL_DEPTH(raw, kind, r, f, t, receiverDepth);
    if (depth < receiverDepth)
    {
      blockers += 1.0;
      depthSum += depth;
    }
  }
  if (blockers == 0.0)
  {
    return 1.0;
  }
  float radius = clamp(PVS_PENUMBRA_RADIUS(kind, r, depthSum / blockers), 0.5, 48.0);
  return PVS_RANDOM(depthMap, kind, r, offsets, samples, radius);
}
#endif

#ifdef PVS_WITH_TRANSMIT
// What the light's translucent casters let through to the receiver, read once
// at its own texel of the transmittance companion (the same grid as the depth
// map): the product of every translucent surface's 1 - opacity over it where
// the receiver lies beyond the nearest of them. The opaque casters' filter
// result is multiplied by it.
float PVS_TRANSMIT(PVS_TRANSMIT_MAP transmit, PVS_MAP kind, PvsReceiver r)
{
  PvsTexelFrame f = PVS_FRAME_OF_SIZE(float(textureSize(transmit, 0).x), kind, r);
  return PVS_TEXEL_TRANSMITTED(transmit, kind, r, f, f.at);
}
#endif
