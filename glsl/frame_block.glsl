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
};

layout(std140) uniform pvsFrame
{
  PvsLight pvsLights[PVS_FRAME_LIGHTS];
};
