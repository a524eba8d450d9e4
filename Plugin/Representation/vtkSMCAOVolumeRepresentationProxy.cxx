#include "vtkSMCAOVolumeRepresentationProxy.h"

#include "vtkCAOFrameReportInformation.h"
#include "vtkClientServerStream.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVSession.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSession.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMStringVectorProperty.h"

#include <algorithm>
#include <cstring>
#include <set>

vtkStandardNewMacro(vtkSMCAOVolumeRepresentationProxy);

namespace
{
/// Every live proxy of the class (server-manager proxies are made and used
/// on the application's main thread). Never destroyed: a proxy released
/// during the exit's static destruction still finds it.
std::vector<vtkSMCAOVolumeRepresentationProxy*>& Instances()
{
  static auto* instances = new std::vector<vtkSMCAOVolumeRepresentationProxy*>();
  return *instances;
}
}

vtkSMCAOVolumeRepresentationProxy::vtkSMCAOVolumeRepresentationProxy()
{
  Instances().push_back(this);
}

vtkSMCAOVolumeRepresentationProxy::~vtkSMCAOVolumeRepresentationProxy()
{
  auto& all = Instances();
  all.erase(std::remove(all.begin(), all.end(), this), all.end());
  if (this->Watched)
    this->Watched->RemoveObserver(this->Observer);
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::PushPointerHeld(bool held)
{
  vtkSMSession* session = this->GetSession();
  if (!this->ObjectsCreated || !(this->GetLocation() & vtkPVSession::RENDER_SERVER) || !session ||
    !session->GetIsAlive())
    return;
  vtkClientServerStream stream;
  stream << vtkClientServerStream::Invoke << VTKOBJECT(this) << "SetPointerHeld" << (held ? 1 : 0)
         << vtkClientServerStream::End;
  this->ExecuteStream(stream, false, vtkPVSession::RENDER_SERVER);
}

//------------------------------------------------------------------------------
std::vector<vtkSMCAOVolumeRepresentationProxy*>
vtkSMCAOVolumeRepresentationProxy::ShownInRemoteSessions()
{
  std::vector<vtkSMCAOVolumeRepresentationProxy*> found;
  std::set<vtkSMSession*> sessions;
  for (vtkSMCAOVolumeRepresentationProxy* proxy : Instances())
  {
    vtkSMSession* session = proxy->GetSession();
    vtkSMProxy* parent = proxy->GetParentProxy();
    if (!proxy->ObjectsCreated || !session || !session->IsA("vtkSMSessionClient") ||
      sessions.count(session) || !parent || !parent->GetProperty("Representation"))
      continue;
    const char* type = vtkSMPropertyHelper(parent, "Representation").GetAsString();
    if (type && std::strcmp(type, TypeName()) == 0)
    {
      sessions.insert(session);
      found.push_back(proxy);
    }
  }
  return found;
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::UpdatePropertyInformationInternal(vtkSMProperty* property)
{
  this->Superclass::UpdatePropertyInformationInternal(property);
  auto* report = vtkSMStringVectorProperty::SafeDownCast(this->GetProperty("FrameReport"));
  if (!report || (property && property != report) || !this->ObjectsCreated ||
    !this->GetSession() || !this->GetSession()->IsA("vtkSMSessionClient"))
    return;
  vtkNew<vtkCAOFrameReportInformation> information;
  this->GatherInformation(information, vtkPVSession::RENDER_SERVER);
  report->SetElement(0, information->GetReport());
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::CreateVTKObjects()
{
  if (this->ObjectsCreated)
    return;
  this->Superclass::CreateVTKObjects();
  vtkSMProxy* parent = this->GetParentProxy();
  vtkSMProperty* representation = parent ? parent->GetProperty("Representation") : nullptr;
  if (representation && !this->Watched)
  {
    this->Watched = representation;
    this->Observer = representation->AddObserver(
      vtkCommand::ModifiedEvent, this, &vtkSMCAOVolumeRepresentationProxy::RepresentationChanged);
  }
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::RepresentationChanged()
{
  auto* parent = vtkSMPVRepresentationProxy::SafeDownCast(this->GetParentProxy());
  if (this->Choosing || !parent || !this->Watched)
    return;
  const char* type = vtkSMPropertyHelper(this->Watched).GetAsString();
  if (!type || std::strcmp(type, TypeName()) != 0 || parent->GetUsingScalarColoring())
    return;
  vtkSMProperty* colorArray = parent->GetProperty("ColorArrayName");
  auto* arrays = colorArray ? colorArray->FindDomain<vtkSMArrayListDomain>() : nullptr;
  if (!arrays || arrays->GetNumberOfStrings() == 0)
    return; // nothing to colour by: the representation says so when it draws
  // A point array with one component (the mapper draws one), else any point
  // array, else the first. The components are the input's: the represented
  // data is still the previous representation's (an outline has no arrays)
  // until the new type is pushed.
  vtkSMPropertyHelper input(parent, "Input", /*quiet=*/true);
  auto* source = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
  vtkPVDataInformation* data =
    source ? source->GetDataInformation(input.GetOutputPort()) : nullptr;
  auto components = [&](unsigned int i) {
    vtkPVArrayInformation* info =
      data ? data->GetArrayInformation(arrays->GetString(i), arrays->GetFieldAssociation(i)) : nullptr;
    return info ? info->GetNumberOfComponents() : 0;
  };
  const unsigned int count = arrays->GetNumberOfStrings();
  unsigned int index = count;
  for (unsigned int i = 0; i < count && index == count; ++i)
    if (arrays->GetFieldAssociation(i) == vtkDataObject::FIELD_ASSOCIATION_POINTS && components(i) == 1)
      index = i;
  for (unsigned int i = 0; i < count && index == count; ++i)
    if (arrays->GetFieldAssociation(i) == vtkDataObject::FIELD_ASSOCIATION_POINTS)
      index = i;
  if (index == count)
    index = 0;
  this->Choosing = true;
  if (parent->SetScalarColoring(arrays->GetString(index), arrays->GetFieldAssociation(index)))
    parent->RescaleTransferFunctionToDataRange(false, false);
  this->Choosing = false;
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Watching: " << (this->Watched ? "the parent's Representation" : "nothing")
     << "\n";
}
