/**
 * vtkCAOForeignEvents — private: running an event whose observer may run
 * the application's event loop inside a render (a ProgressEvent: ParaView's
 * GUI paints its other OpenGL widgets then, and leaves their context
 * current, or repaints this one, which binds its widget's framebuffer), and
 * giving the window its context back afterwards. Kept apart from
 * vtkCAOWindowGL.h because its definition lives with VTK's GLEW
 * (vtkCAOWindowGLEW.cxx), which cannot see the compute layer's GL
 * declarations. Not wrapped, not installed.
 */
#ifndef vtkCAOForeignEvents_h
#define vtkCAOForeignEvents_h

#include "caoFiltersCoreModule.h"

#include <functional>

class vtkRenderWindow;

namespace vtkCAO
{
/// Runs `event`; then, when `window`'s context was current before it,
/// makes it current again if it no longer is and binds its draw and read
/// framebuffers as they were (and VTK's cache of them), so that the
/// frame's next GL calls and VTK's cached GL state stay this window's.
/// False when the context was current before and cannot be made current
/// again (the window went away meanwhile): no more GL for this frame.
CAOFILTERSCORE_EXPORT bool AroundForeignEvents(vtkRenderWindow* window, const std::function<void()>& event);
}

#endif
