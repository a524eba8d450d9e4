#include "vtkSMCAOLocalAmbientOcclusionProxy.h"

#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMInputProperty.h"
#include "vtkObjectFactory.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyProperty.h"
#include "vtkSMSessionProxyManager.h"

#include <string>

vtkStandardNewMacro(vtkSMCAOLocalAmbientOcclusionProxy);

vtkSMCAOLocalAmbientOcclusionProxy::vtkSMCAOLocalAmbientOcclusionProxy() = default;
vtkSMCAOLocalAmbientOcclusionProxy::~vtkSMCAOLocalAmbientOcclusionProxy() = default;

//------------------------------------------------------------------------------
void vtkSMCAOLocalAmbientOcclusionProxy::UpdateVTKObjects()
{
  this->FollowDisplayOpacity();
  this->Superclass::UpdateVTKObjects();
}

void vtkSMCAOLocalAmbientOcclusionProxy::UpdatePipeline()
{
  this->FollowDisplayOpacity();
  this->Superclass::UpdateVTKObjects();
  this->Superclass::UpdatePipeline();
}

void vtkSMCAOLocalAmbientOcclusionProxy::UpdatePipeline(double time)
{
  this->FollowDisplayOpacity();
  this->Superclass::UpdateVTKObjects();
  this->Superclass::UpdatePipeline(time);
}

//------------------------------------------------------------------------------
void vtkSMCAOLocalAmbientOcclusionProxy::FollowDisplayOpacity()
{
  vtkSMProperty* follow = this->GetProperty("FollowDisplayOpacity");
  vtkSMProxyProperty* opacity = vtkSMProxyProperty::SafeDownCast(this->GetProperty("OpacityFunction"));
  vtkSMProperty* scalars = this->GetProperty("SelectInputScalars");
  vtkSMSessionProxyManager* pxm = this->GetSessionProxyManager();
  if (!follow || !opacity || !scalars || !pxm)
    return;
  vtkSMProxy* current = opacity->GetNumberOfProxies() > 0 ? opacity->GetProxy(0) : nullptr;
  if (vtkSMPropertyHelper(follow).GetAsInt() == 0)
  {
    if (current && current == this->Followed)
      opacity->RemoveAllProxies(); // the map this proxy gave goes with the switch
    this->Followed = nullptr;
    return;
  }
  if (current && current != this->Followed)
    return; // chosen by the user: kept
  std::string array = vtkSMPropertyHelper(scalars).GetAsString(4) ? vtkSMPropertyHelper(scalars).GetAsString(4) : "";
  if (array.empty())
  {
    // No array chosen: the filter uses the input's active point scalars.
    auto* input = vtkSMInputProperty::SafeDownCast(this->GetProperty("Input"));
    auto* source = input && input->GetNumberOfProxies() > 0
      ? vtkSMSourceProxy::SafeDownCast(input->GetProxy(0))
      : nullptr;
    if (source)
      source->UpdatePipeline(); // its arrays are known once it has run (it must, for this filter)
    vtkPVDataInformation* info =
      source ? source->GetDataInformation(input->GetOutputPortForConnection(0)) : nullptr;
    vtkPVArrayInformation* active = info
      ? info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS)
      : nullptr;
    if (active && active->GetName())
      array = active->GetName();
  }
  if (array.empty())
    return;
  // Only a map that exists: one the array is (or was) displayed with. A new
  // one would not be fitted to the data's range yet.
  vtkSMProxy* map = pxm->GetProxy("piecewise_functions", (array + ".PiecewiseFunction").c_str());
  if (!map && current && current == this->Followed)
  {
    // Another array, not displayed yet: the ramp, not the old array's map.
    opacity->RemoveAllProxies();
    this->Followed = nullptr;
  }
  else if (map && map != current)
  {
    vtkSMPropertyHelper(opacity).Set(map);
    this->Followed = map;
  }
}

//------------------------------------------------------------------------------
void vtkSMCAOLocalAmbientOcclusionProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Followed: " << this->Followed.GetPointer() << "\n";
}
