/**
 * caoSurface — `cao surface`: ambient occlusion of triangle meshes seen by
 * one camera, by one method (the ray-traced reference, VTK's vtkSSAOPass,
 * or none), as a shaded picture or as the AO term alone (a 16-bit grey PNG,
 * 1 = open, background transparent) so that two methods' outputs compare
 * pixel by pixel. Every method uses the same camera and the same default
 * radius (a tenth of the scene's bounding-box diagonal).
 */
#ifndef caoSurface_h
#define caoSurface_h

namespace caocli
{
extern const char* SurfaceUsage;
/// argv[1] is "surface". Exit codes as the rest of `cao`.
int RunSurface(int argc, char* argv[]);
}

#endif
