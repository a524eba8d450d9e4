/**
 * vtkCAOFrameIO — the pass's pixels: the renderer's viewport read from the
 * framebuffer it is drawing into right now (an outer pass's framebuffer,
 * such as ParaView's tone mapping or FXAA, or the window's render
 * framebuffer, multisampling resolved by the window), and colour written
 * back into it, each leaving the GL state (enables, viewport, scissor,
 * blend, depth mask, framebuffer bindings) as it found it. Private.
 */
#ifndef vtkCAOFrameIO_h
#define vtkCAOFrameIO_h

#include <string>
#include <vector>

class vtkRenderer;

namespace vtkCAO
{
/// RGBA floats, row by row from the viewport's bottom-left.
bool ReadViewportColor(vtkRenderer* renderer, std::vector<float>& rgba, std::string& error);
/// Window depth (0 near .. 1 far) per pixel; false (with the reason) when
/// the framebuffer has no depth the pass can read.
bool ReadViewportDepth(vtkRenderer* renderer, std::vector<float>& depth, std::string& error);
/// The framebuffer the renderer draws into now, its viewport (x0, y0,
/// width, height) and whether it is multisampled, for the GPU frame; false
/// when there is none.
bool DrawTarget(vtkRenderer* renderer, unsigned& framebuffer, int rect[4], bool& multisampled, std::string& error);
/// Writes `rgba` over the viewport, colour only (no blending, no depth).
bool WriteViewportColor(vtkRenderer* renderer, std::vector<float>& rgba, std::string& error);
}

#endif
