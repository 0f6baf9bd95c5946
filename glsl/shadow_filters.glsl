// The filters, written once for every kind of map. Before this file, the
// receiver's shader defines which kind it serves and which filters to compile:
//
//   PVS_MAP           the kind's parameter struct         (PvsCubeMap, ...)
//   PVS_COMPARE_MAP   its comparison sampler type         (samplerCubeShadow, ...)
//   PVS_RAW_MAP       its plain sampler type              (samplerCube, ...)
//   PVS_COMPARE       tap compare: (map, kind, receiver, offset) -> visibility
//   PVS_BLOCKER       tap depth: (raw, kind, receiver, offset, out receiverDepth) -> blocker depth
//   PVS_SEARCH_RADIUS / PVS_PENUMBRA_RADIUS   in texels, for PCSS
//   PVS_LIT, PVS_HARD, PVS_PCF, PVS_RANDOM, PVS_PCSS   names of the filter functions
//   PVS_WITH_LIT, PVS_WITH_HARD, ...                   which to compile
//
// Every tap is a hardware comparison with linear filtering (2x2 texels), each
// against the receiver's own tangent plane along the tap.

#ifdef PVS_WITH_LIT
// No map to read (nothing can shadow a visible receiver): lit where the
// visible side faces the light and lies in its cone.
float PVS_LIT(PVS_MAP kind, PvsReceiver r)
{
  return r.lit;
}
#endif

#ifdef PVS_WITH_HARD
float PVS_HARD(PVS_COMPARE_MAP depthMap, PVS_MAP kind, PvsReceiver r)
{
  return r.lit == 0.0 ? 0.0 : PVS_COMPARE(depthMap, kind, r, vec2(0.0));
}
#endif

#ifdef PVS_WITH_PCF
// side x side taps one texel apart.
float PVS_PCF(PVS_COMPARE_MAP depthMap, PVS_MAP kind, PvsReceiver r, int side)
{
  if (r.lit == 0.0)
  {
    return 0.0;
  }
  float sum = 0.0;
  for (int i = 0; i < side; ++i)
  {
    for (int j = 0; j < side; ++j)
    {
      sum += PVS_COMPARE(depthMap, kind, r, vec2(float(i), float(j)) - 0.5 * float(side - 1));
    }
  }
  return sum / float(side * side);
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
  float sum = 0.0;
  for (int i = 0; i < 8; ++i)
  {
    sum += PVS_COMPARE(depthMap, kind, r, radius * pvsDiskOffset(offsets, i));
  }
  if (sum < 0.001 || sum > 7.999 || samples <= 8)
  {
    return sum / 8.0;
  }
  for (int i = 8; i < samples; ++i)
  {
    sum += PVS_COMPARE(depthMap, kind, r, radius * pvsDiskOffset(offsets, i));
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
  float search = clamp(PVS_SEARCH_RADIUS(kind, r), 1.0, 32.0);
  float blockers = 0.0;
  float depthSum = 0.0;
  for (int i = 0; i < 16; ++i)
  {
    float receiverDepth;
    float depth = PVS_BLOCKER(raw, kind, r, search * pvsDiskOffset(offsets, i), receiverDepth);
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
