// The receivers' uniform block: what a light's pose, fit and settings decide,
// and what changes whenever the camera moves, set once per frame for every
// receiver (pvshadows.gl.frame_block.FrameBlock) instead of once per receiver.
// Each receiver reads a light by VTK's index for it. Before this file the
// receiver defines
//
//   PVS_FRAME_LIGHTS   how many of VTK's lights it reads: its highest light index + 1

struct PvsLight
{
  // view coordinates to the light's space
  mat4 viewToLight;
  // columns: params, cone, bias (xyz), filter (x radius in texels, y taps,
  // z layer in a cube array)
  mat4 pack;
  // light space to a spot map's clip space
  mat4 lightToClip;
  // the light in view coordinates, for the facing test of screen masks:
  // (position, 1) for point and spot lights, (direction towards the light, 0)
  // for directional lights
  vec4 lightVC;
  // x: the light's shadow strength
  vec4 shading;
};

layout(std140) uniform pvsFrame
{
  // the VTK index of the light whose visibility a probe frame shows; -1 in a
  // normal frame
  int pvsProbeLight;
  // always 0: added to a loop's count, it keeps the compiler from unrolling
  // the loop (shadow_group.glsl)
  int pvsLoopZero;
  // the renderer's viewport in the window, in pixels: x, y its origin, z, w its
  // size (where screen masks are read)
  vec4 pvsViewport;
  PvsLight pvsLights[PVS_FRAME_LIGHTS];
};
