/**
 * @class   vtkSMCAOLocalAmbientOcclusionProxy
 * @brief   The Local Ambient Occlusion filter's proxy: its opacity follows
 *          the opacity map the Scalars array is displayed with.
 *
 * A ParaView user sees a volume through the opacity map of its array (the
 * per-array transfer function every representation of that array shares).
 * With FollowDisplayOpacity on (the default) and no OpacityFunction chosen,
 * this proxy gives the filter that map (the array's opacity transfer
 * function, registered as "<array>.PiecewiseFunction" once the array has
 * been displayed) when its properties are pushed or its pipeline updated,
 * and follows the Scalars selection to another array's map; an
 * OpacityFunction set by the user is kept. Before the array is displayed
 * there is no map: the filter's ramp over the data range applies. Editing the map then re-executes
 * the filter on the next update, as any input change does. Client-side
 * glue only (server manager, no Qt).
 */
#ifndef vtkSMCAOLocalAmbientOcclusionProxy_h
#define vtkSMCAOLocalAmbientOcclusionProxy_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkSMSourceProxy.h"
#include "vtkWeakPointer.h" // For the map it gave

class CAOPARAVIEWREPRESENTATION_EXPORT vtkSMCAOLocalAmbientOcclusionProxy : public vtkSMSourceProxy
{
public:
  static vtkSMCAOLocalAmbientOcclusionProxy* New();
  vtkTypeMacro(vtkSMCAOLocalAmbientOcclusionProxy, vtkSMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void UpdateVTKObjects() override;
  ///@{
  /// Follow first (the input's arrays are known once it has run), then update.
  void UpdatePipeline() override;
  void UpdatePipeline(double time) override;
  ///@}

protected:
  vtkSMCAOLocalAmbientOcclusionProxy();
  ~vtkSMCAOLocalAmbientOcclusionProxy() override;

  /// The display opacity map into OpacityFunction, when it follows.
  void FollowDisplayOpacity();
  vtkWeakPointer<vtkSMProxy> Followed; ///< the map this proxy set, if any

private:
  vtkSMCAOLocalAmbientOcclusionProxy(const vtkSMCAOLocalAmbientOcclusionProxy&) = delete;
  void operator=(const vtkSMCAOLocalAmbientOcclusionProxy&) = delete;
};

#endif
