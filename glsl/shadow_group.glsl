// The lights of one group (one kind of map read with one filter), looked up
// one after another with the group's uniform arrays. Each filter's taps loop
// over a uniform count, so the driver keeps them loops: the receiver's shader
// grows by one small lookup per light, not by lights x taps (inlining
// constant tap counts made 16 lights with 16-tap PCF compile for minutes on
// llvmpipe). The lights are not one GLSL loop over sampler arrays: with
// ARB_gpu_shader5's dynamically indexed samplers, LLVM 15 (llvmpipe) crashes
// compiling a PCF loop over sampler2DShadow arrays; the cubes of point lights
// are therefore layers of one cube map array where the context has them, and
// those lights are one loop (PVS_GROUP_LOOP below). Instantiated once per
// group, after that kind's filters (shadow_filters.glsl, whose PVS_* names are
// still defined); before this file the receiver defines:
//
//   PVS_GROUP_CUBE, _CUBES, _SPOT or _SUN  the kind of map (_CUBES: layers of a cube array)
//   PVS_GROUP_LIT, _HARD, _PCF, _RANDOM or _PCSS   the filter (hard: PCF's box
//                            of 2 x 2 compares cut at one half, a loop too:
//                            straight-line compares cost LLVM more to compile
//                            than loops do)
//   PVS_GROUP_SIZE           lights in the group (sizes the uniform arrays)
//   PVS_GROUP_LOOKUP         name of the function defined here
//   PVS_GROUP_RECEIVER       the kind's receiver function
//   PVS_GROUP_INDEX          const int[]: each light's index in VTK's lights,
//                            its entry of pvsLights (frame_block.glsl), which holds
//                            its view-to-light matrix, its pack (params, cone, bias,
//                            filter) and a spot map's light-to-clip matrix
//   PVS_GROUP_DEPTH, PVS_GROUP_RAW   sampler arrays: the maps for comparisons,
//                            plain views of them (PCSS)
//   PVS_GROUP_OFFSETS        the disk offsets (random, PCSS): one texture for the
//                            group, whose lights share a sample count
//   PVS_GROUP_TRANSLUCENT    defined for lights whose casters include translucent
//                            ones: the filter's result is multiplied by PVS_TRANSMIT
//                            read from PVS_GROUP_TRANSMIT, the companions' sampler array
//   PVS_GROUP_ALL(EACH)      EACH(0, pvsMapVisibility<i>) EACH(1, ...) ...: every
//                            light, by constant index (GLSL 1.50 indexes sampler
//                            arrays with constants only) and the global float its
//                            visibility goes to
//
//   PVS_GROUP_LOOP           defined for maps that are layers of one texture (cube
//                            arrays): the lights are looked up in one loop over
//                            PVS_GROUP_COUNT, a count the compiler cannot fold,
//                            with one sampler each (PVS_GROUP_DEPTH, ... are
//                            then not arrays), so each
//                            filter is in the shader once whatever the number of lights
//
// The macros are on one line each: GLSL 1.50 has no line continuation.

#if defined(PVS_GROUP_LOOP)
#define PVS_GROUP_SAMPLER(samplers, j) samplers
#else
#define PVS_GROUP_SAMPLER(samplers, j) samplers[j]
#endif

#define PVS_GROUP_LIGHT(j) pvsLights[PVS_GROUP_INDEX[j]]
#define PVS_GROUP_VIEW(j) PVS_GROUP_LIGHT(j).viewToLight
#define PVS_GROUP_PACK(j) PVS_GROUP_LIGHT(j).pack
#define PVS_GROUP_CLIP(j) PVS_GROUP_LIGHT(j).lightToClip

#if defined(PVS_GROUP_CUBE)
#define PVS_GROUP_MAP(j) PvsCubeMap(PVS_GROUP_PACK(j)[0], PVS_GROUP_PACK(j)[1])
#elif defined(PVS_GROUP_CUBES)
#define PVS_GROUP_MAP(j) PvsCubesMap(PVS_GROUP_PACK(j)[0], PVS_GROUP_PACK(j)[1], PVS_GROUP_PACK(j)[3].z)
#elif defined(PVS_GROUP_SPOT)
#define PVS_GROUP_MAP(j) PvsSpotMap(PVS_GROUP_CLIP(j), PVS_GROUP_PACK(j)[0], PVS_GROUP_PACK(j)[1])
#else
#define PVS_GROUP_MAP(j) PvsSunMap(PVS_GROUP_PACK(j)[0])
#endif

#define PVS_GROUP_TAPS(j) int(PVS_GROUP_PACK(j)[3].y)

#if defined(PVS_GROUP_LIT)
#define PVS_GROUP_FILTER(j, r) PVS_LIT(PVS_GROUP_MAP(j), r)
#elif defined(PVS_GROUP_HARD)
// The 3 x 3 texels round the receiver weighted as 2 x 2 bilinear compares would
// weight them, cut at one half: a hard edge through the middle of the texels on
// either side of it, not along their outlines (a staircase many pixels wide up close).
#define PVS_GROUP_FILTER(j, r) step(0.5, PVS_PCF(PVS_GROUP_SAMPLER(PVS_GROUP_DEPTH, j), PVS_GROUP_MAP(j), r, PVS_GROUP_TAPS(j)))
#elif defined(PVS_GROUP_PCF)
#define PVS_GROUP_FILTER(j, r) PVS_PCF(PVS_GROUP_SAMPLER(PVS_GROUP_DEPTH, j), PVS_GROUP_MAP(j), r, PVS_GROUP_TAPS(j))
#elif defined(PVS_GROUP_RANDOM)
#define PVS_GROUP_FILTER(j, r) PVS_RANDOM(PVS_GROUP_SAMPLER(PVS_GROUP_DEPTH, j), PVS_GROUP_MAP(j), r, PVS_GROUP_OFFSETS, PVS_GROUP_TAPS(j), PVS_GROUP_PACK(j)[3].x)
#else
#define PVS_GROUP_FILTER(j, r) PVS_PCSS(PVS_GROUP_SAMPLER(PVS_GROUP_DEPTH, j), PVS_GROUP_SAMPLER(PVS_GROUP_RAW, j), PVS_GROUP_MAP(j), r, PVS_GROUP_OFFSETS, PVS_GROUP_TAPS(j))
#endif

#if defined(PVS_GROUP_TRANSLUCENT)
#define PVS_GROUP_ONE(j, visibility) { PvsReceiver receiver = PVS_GROUP_RECEIVER(PVS_GROUP_MAP(j), PVS_GROUP_VIEW(j), PVS_GROUP_PACK(j)[2].xyz, posVC, normalVC); visibility = PVS_GROUP_FILTER(j, receiver) * PVS_TRANSMIT(PVS_GROUP_TRANSMIT[j], PVS_GROUP_MAP(j), receiver); }
#else
#define PVS_GROUP_ONE(j, visibility) visibility = PVS_GROUP_FILTER(j, PVS_GROUP_RECEIVER(PVS_GROUP_MAP(j), PVS_GROUP_VIEW(j), PVS_GROUP_PACK(j)[2].xyz, posVC, normalVC));
#endif
#define PVS_GROUP_GLOBAL(j, visibility) float visibility = 1.0;

// Each light's visibility, 1 until the lookup sets it.
PVS_GROUP_ALL(PVS_GROUP_GLOBAL)

#if defined(PVS_GROUP_LOOP)
// Each light's visibility goes to its global through a ladder of selects: a
// local array indexed by the loop counter costs llvmpipe about as much to
// compile as one filter per light (32 lights: 10.9 s against 4.4 s, where
// VTK's own shader takes 3.7 s).
#define PVS_GROUP_PICK(k, visibility) visibility = j == k ? found : visibility;

void PVS_GROUP_LOOKUP(vec3 posVC, vec3 normalVC)
{
  for (int j = 0; j < PVS_GROUP_COUNT; ++j)
  {
    float found;
    PVS_GROUP_ONE(j, found)
    PVS_GROUP_ALL(PVS_GROUP_PICK)
  }
}

#undef PVS_GROUP_PICK
#else
void PVS_GROUP_LOOKUP(vec3 posVC, vec3 normalVC)
{
  PVS_GROUP_ALL(PVS_GROUP_ONE)
}
#endif

#undef PVS_GROUP_SAMPLER
#undef PVS_GROUP_MAP
#undef PVS_GROUP_TAPS
#undef PVS_GROUP_VIEW
#undef PVS_GROUP_LIGHT
#undef PVS_GROUP_PACK
#undef PVS_GROUP_CLIP
#undef PVS_GROUP_FILTER
#undef PVS_GROUP_ONE
#undef PVS_GROUP_GLOBAL
