// The receivers' uniform block: what changes whenever the camera moves, set
// once per frame for every receiver (pvshadows.gl.frame_block.FrameBlock)
// instead of once per receiver. Before this file the receiver defines
//
//   PVS_FRAME_LIGHTS   how many of VTK's lights it reads: its highest light index + 1

layout(std140) uniform pvsFrame
{
  // view coordinates to each light's space, by VTK's light index
  mat4 pvsViewToLight[PVS_FRAME_LIGHTS];
};
